#include "image_output.hpp"

#include "png_output.hpp"

#include <ImfChannelList.h>
#include <ImfFrameBuffer.h>
#include <ImfHeader.h>
#include <ImfOutputFile.h>
#include <half.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace arbor::io {

namespace {

double to_linear(double c)
{
    return c <= 0.04045 ? c / 12.92 : std::pow((c + 0.055) / 1.055, 2.4);
}

void write_png_image(const std::filesystem::path &path, const RenderedImage &image)
{
    cv::Mat bgra(static_cast<int>(image.height), static_cast<int>(image.width), CV_8UC4);
    for (uint32_t y = 0; y < image.height; ++y)
        for (uint32_t x = 0; x < image.width; ++x) {
            const float *p = &image.rgba[(std::size_t{y} * image.width + x) * 4];
            const float a = p[3];
            cv::Vec4b &q = bgra.at<cv::Vec4b>(static_cast<int>(y), static_cast<int>(x));
            for (int c = 0; c < 3; ++c) // straight alpha in PNG
                q[2 - c] = static_cast<uint8_t>(std::lround(255.0f * std::clamp(a > 0 ? p[c] / a : 0.0f, 0.0f, 1.0f)));
            q[3] = static_cast<uint8_t>(std::lround(255.0f * a));
        }
    write_png(path, bgra);
}

void write_exr_image(const std::filesystem::path &path, const RenderedImage &image)
{
    const std::size_t n = std::size_t{image.width} * image.height;
    std::vector<half> rgba(4 * n);
    for (std::size_t i = 0; i < n; ++i) {
        const float a = image.rgba[4 * i + 3];
        for (int c = 0; c < 3; ++c) {
            const double straight = a > 0 ? image.rgba[4 * i + c] / a : 0.0;
            rgba[4 * i + c] = half(static_cast<float>(to_linear(straight) * a));
        }
        rgba[4 * i + 3] = half(a);
    }
    std::vector<float> depth = image.depth;
    const std::filesystem::path partial = path.string() + ".partial";
    try {
        Imf::Header header(static_cast<int>(image.width), static_cast<int>(image.height));
        for (const char *c : {"R", "G", "B", "A"})
            header.channels().insert(c, Imf::Channel(Imf::HALF));
        header.channels().insert("Z", Imf::Channel(Imf::FLOAT));
        Imf::OutputFile file(partial.c_str(), header);
        Imf::FrameBuffer fb;
        const char *names[4] = {"R", "G", "B", "A"};
        for (int c = 0; c < 4; ++c)
            fb.insert(names[c], Imf::Slice(Imf::HALF, reinterpret_cast<char *>(rgba.data() + c), 4 * sizeof(half),
                                           4 * sizeof(half) * image.width));
        fb.insert("Z", Imf::Slice(Imf::FLOAT, reinterpret_cast<char *>(depth.data()), sizeof(float),
                                  sizeof(float) * image.width));
        file.setFrameBuffer(fb);
        file.writePixels(static_cast<int>(image.height));
    } catch (const std::exception &e) {
        std::error_code ec;
        std::filesystem::remove(partial, ec);
        throw std::runtime_error(path.string() + ": could not write OpenEXR: " + e.what());
    }
    std::filesystem::rename(partial, path);
}

} // namespace

void write_image(const std::filesystem::path &path, const RenderedImage &image)
{
    std::string ext = path.extension().string();
    std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return std::tolower(c); });
    if (ext == ".png")
        write_png_image(path, image);
    else if (ext == ".exr")
        write_exr_image(path, image);
    else
        throw std::invalid_argument(path.string() + ": images are written as .png or .exr");
}

double covered_fraction(const RenderedImage &image)
{
    const std::size_t n = std::size_t{image.width} * image.height;
    std::size_t differ = 0;
    for (std::size_t i = 0; i < n; ++i)
        for (int c = 0; c < 4; ++c)
            if (std::fabs(image.rgba[4 * i + c] - image.rgba[c]) > 2.0f / 255.0f) {
                ++differ;
                break;
            }
    return n ? static_cast<double>(differ) / n : 0.0;
}

} // namespace arbor::io
