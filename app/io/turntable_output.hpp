// turntable_output.hpp - the frames of a turntable as a video (.mp4 with
// MPEG-4 part 2, .avi with Motion JPEG, through OpenCV's VideoWriter and its
// FFmpeg backend; .gif through giflib, as OpenCV 4.6 writes none) or as a
// folder of PNGs (frame-0001.png ...).  Video frames
// are composited over black (the premultiplied colours as they are).  The
// video appears under its name only when complete: it is written beside it
// under a temporary name and renamed by finish().
#pragma once

#include "core/rendered_image.hpp"

#include <filesystem>
#include <memory>

namespace arbor::io {

class TurntableWriter {
public:
    // Throws std::invalid_argument for a suffix it cannot write (naming what
    // it can) and std::runtime_error when the file or folder cannot be made.
    TurntableWriter(const std::filesystem::path &path, uint32_t width, uint32_t height, double frames_per_second);
    ~TurntableWriter(); // without finish(): the partial video is removed
    TurntableWriter(const TurntableWriter &) = delete;
    TurntableWriter &operator=(const TurntableWriter &) = delete;

    void add(const RenderedImage &frame);
    void finish();
    // "video" or "png folder".
    const char *kind() const;

private:
    struct Video;
    std::filesystem::path path_;
    uint32_t width_, height_, frames_ = 0;
    std::unique_ptr<Video> video_; // null: a folder of PNGs
};

} // namespace arbor::io
