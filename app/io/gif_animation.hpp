// gif_animation.hpp - an animated GIF through giflib: each frame quantised
// to its own 256 colours (median cut, GifQuantizeBuffer), shown for
// 1 / fps seconds (in GIF's hundredths), looping forever.
#pragma once

#include <cstdint>
#include <filesystem>
#include <vector>

struct GifFileType;

namespace arbor::io {

class GifAnimation {
public:
    // Throws std::runtime_error when the file cannot be made.
    GifAnimation(const std::filesystem::path &path, uint32_t width, uint32_t height, double frames_per_second);
    ~GifAnimation(); // closes the file if close() was not called
    GifAnimation(const GifAnimation &) = delete;
    GifAnimation &operator=(const GifAnimation &) = delete;

    // One frame of 8-bit RGB, row by row from the top.
    void add(const std::vector<uint8_t> &rgb);
    void close();

private:
    GifFileType *gif_ = nullptr;
    uint32_t width_, height_;
    uint16_t delay_; // hundredths of a second per frame
};

} // namespace arbor::io
