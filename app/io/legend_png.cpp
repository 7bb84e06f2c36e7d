#include "legend_png.hpp"

#include "png_output.hpp"

#include <algorithm>
#include <stdexcept>

namespace arbor::io {

void write_legend_png(const std::filesystem::path &path, uint32_t size, const std::vector<float> &rgba)
{
    if (rgba.size() != std::size_t{size} * size * 4)
        throw std::invalid_argument("a legend of " + std::to_string(size) + " pixels square needs " +
                                    std::to_string(std::size_t{size} * size * 4) + " values");
    const int n = static_cast<int>(size);
    cv::Mat bgr(n, n, CV_8UC3);
    for (int y = 0; y < n; ++y)
        for (int x = 0; x < n; ++x) {
            const float *p = &rgba[(static_cast<std::size_t>(y) * size + static_cast<std::size_t>(x)) * 4];
            for (int c = 0; c < 3; ++c) // premultiplied, over white
                bgr.at<cv::Vec3b>(y, x)[2 - c] =
                    static_cast<uint8_t>(std::clamp(p[c] + (1.0f - p[3]), 0.0f, 1.0f) * 255.0f + 0.5f);
        }
    write_png(path, bgr);
}

} // namespace arbor::io
