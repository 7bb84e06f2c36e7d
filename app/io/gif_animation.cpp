#include "gif_animation.hpp"

#include <gif_lib.h>

#include <fcntl.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstring>
#include <stdexcept>
#include <string>

namespace arbor::io {

namespace {

std::string gif_error(int code)
{
    const char *text = GifErrorString(code);
    return text ? text : "giflib error " + std::to_string(code);
}

} // namespace

GifAnimation::GifAnimation(const std::filesystem::path &path, uint32_t width, uint32_t height, double fps)
    : width_(width), height_(height),
      delay_(static_cast<uint16_t>(std::clamp(std::lround(100.0 / fps), 2L, 65535L))) // browsers slow delays under 2
{
    if (width > 65535 || height > 65535)
        throw std::invalid_argument("a GIF is at most 65535 pixels wide and high");
    // Opened here rather than by giflib, which would make it private (0600).
    const int fd = ::open(path.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0666);
    if (fd < 0)
        throw std::runtime_error("cannot write " + path.string() + ": " + std::strerror(errno));
    int error = 0;
    gif_ = EGifOpenFileHandle(fd, &error); // owns fd from here
    if (!gif_) {
        ::close(fd);
        throw std::runtime_error("cannot write " + path.string() + ": " + gif_error(error));
    }
    EGifSetGifVersion(gif_, true); // GIF89a: frame delays and looping
    if (EGifPutScreenDesc(gif_, static_cast<int>(width), static_cast<int>(height), 8, 0, nullptr) == GIF_ERROR)
        throw std::runtime_error("cannot write " + path.string() + ": " + gif_error(gif_->Error));
    // NETSCAPE2.0: loop forever.
    const GifByteType application[] = {'N', 'E', 'T', 'S', 'C', 'A', 'P', 'E', '2', '.', '0'};
    const GifByteType loop[] = {1, 0, 0};
    if (EGifPutExtensionLeader(gif_, APPLICATION_EXT_FUNC_CODE) == GIF_ERROR ||
        EGifPutExtensionBlock(gif_, sizeof application, application) == GIF_ERROR ||
        EGifPutExtensionBlock(gif_, sizeof loop, loop) == GIF_ERROR || EGifPutExtensionTrailer(gif_) == GIF_ERROR)
        throw std::runtime_error("cannot write " + path.string() + ": " + gif_error(gif_->Error));
}

GifAnimation::~GifAnimation()
{
    if (gif_) {
        int error = 0;
        EGifCloseFile(gif_, &error);
    }
}

void GifAnimation::add(const std::vector<uint8_t> &rgb)
{
    const std::size_t pixels = std::size_t{width_} * height_;
    if (rgb.size() != 3 * pixels)
        throw std::invalid_argument("a GIF frame of the wrong size");
    std::vector<GifByteType> r(pixels), g(pixels), b(pixels), indices(pixels);
    for (std::size_t p = 0; p < pixels; ++p) {
        r[p] = rgb[3 * p];
        g[p] = rgb[3 * p + 1];
        b[p] = rgb[3 * p + 2];
    }
    int colours = 256;
    GifColorType palette[256] = {};
    if (GifQuantizeBuffer(width_, height_, &colours, r.data(), g.data(), b.data(), indices.data(), palette) ==
        GIF_ERROR)
        throw std::runtime_error("cannot quantise a GIF frame");
    ColorMapObject *map = GifMakeMapObject(256, palette);
    if (!map)
        throw std::bad_alloc();
    GraphicsControlBlock control{};
    control.DisposalMode = DISPOSE_DO_NOT;
    control.DelayTime = delay_;
    control.TransparentColor = NO_TRANSPARENT_COLOR;
    GifByteType extension[4];
    const std::size_t length = EGifGCBToExtension(&control, extension);
    bool ok = EGifPutExtension(gif_, GRAPHICS_EXT_FUNC_CODE, static_cast<int>(length), extension) != GIF_ERROR &&
              EGifPutImageDesc(gif_, 0, 0, static_cast<int>(width_), static_cast<int>(height_), false, map) !=
                  GIF_ERROR;
    for (uint32_t y = 0; ok && y < height_; ++y)
        ok = EGifPutLine(gif_, &indices[std::size_t{y} * width_], static_cast<int>(width_)) != GIF_ERROR;
    GifFreeMapObject(map);
    if (!ok)
        throw std::runtime_error("cannot write a GIF frame: " + gif_error(gif_->Error));
}

void GifAnimation::close()
{
    int error = 0;
    GifFileType *gif = gif_;
    gif_ = nullptr;
    if (EGifCloseFile(gif, &error) == GIF_ERROR)
        throw std::runtime_error("cannot finish the GIF: " + gif_error(error));
}

} // namespace arbor::io
