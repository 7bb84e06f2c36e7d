#include "turntable_output.hpp"

#include "gif_animation.hpp"
#include "image_output.hpp"

#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>
#include <opencv2/videoio.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>
#include <system_error>
#include <vector>

namespace arbor::io {

namespace fs = std::filesystem;

struct TurntableWriter::Video {
    cv::VideoWriter writer;
    std::unique_ptr<GifAnimation> gif; // .gif: giflib instead of OpenCV
    fs::path partial;
    bool done = false;
};

namespace {

std::string lower(std::string s)
{
    std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
    return s;
}

} // namespace

TurntableWriter::TurntableWriter(const fs::path &path, uint32_t width, uint32_t height, double fps)
    : path_(path), width_(width), height_(height)
{
    const std::string suffix = lower(path.extension().string());
    if (suffix.empty()) { // a folder of PNGs
        std::error_code e;
        fs::create_directories(path, e);
        if (e || !fs::is_directory(path))
            throw std::runtime_error("cannot make the folder " + path.string() + ": " + e.message());
        return;
    }
    if (!(fps > 0))
        throw std::invalid_argument("frames per second must be positive");
    if (suffix == ".gif") {
        video_ = std::make_unique<Video>();
        video_->partial = path.parent_path() / ("." + path.stem().string() + ".partial" + suffix);
        video_->gif = std::make_unique<GifAnimation>(video_->partial, width, height, fps);
        return;
    }
    int fourcc = 0;
    if (suffix == ".mp4" || suffix == ".m4v")
        fourcc = cv::VideoWriter::fourcc('m', 'p', '4', 'v');
    else if (suffix == ".avi")
        fourcc = cv::VideoWriter::fourcc('M', 'J', 'P', 'G');
    else
        throw std::invalid_argument("cannot write " + path.string() + ": a turntable is .mp4, .avi, .gif or a "
                                    "folder of PNGs (a path without suffix)");
    video_ = std::make_unique<Video>();
    video_->partial = path.parent_path() / ("." + path.stem().string() + ".partial" + suffix);
    if (!video_->writer.open(video_->partial.string(), cv::CAP_FFMPEG, fourcc, fps,
                             cv::Size(static_cast<int>(width), static_cast<int>(height))))
        throw std::runtime_error("cannot open " + path.string() + " for writing (OpenCV's FFmpeg video writer)");
}

TurntableWriter::~TurntableWriter()
{
    if (video_ && !video_->done) {
        video_->gif.reset();
        video_->writer.release();
        std::error_code e;
        fs::remove(video_->partial, e);
    }
}

const char *TurntableWriter::kind() const
{
    return video_ ? "video" : "png folder";
}

void TurntableWriter::add(const RenderedImage &frame)
{
    if (frame.width != width_ || frame.height != height_)
        throw std::invalid_argument("a turntable's frames all have one size");
    ++frames_;
    if (!video_) {
        char name[32];
        std::snprintf(name, sizeof name, "frame-%04u.png", frames_);
        write_image(path_ / name, frame);
        return;
    }
    cv::Mat bgr(static_cast<int>(height_), static_cast<int>(width_), CV_8UC3);
    for (uint32_t y = 0; y < height_; ++y)
        for (uint32_t x = 0; x < width_; ++x) {
            const float *p = &frame.rgba[(std::size_t{y} * width_ + x) * 4];
            cv::Vec3b &q = bgr.at<cv::Vec3b>(static_cast<int>(y), static_cast<int>(x));
            for (int c = 0; c < 3; ++c) // premultiplied: over black as it is
                q[2 - c] = static_cast<uint8_t>(std::lround(255.0f * std::clamp(p[c], 0.0f, 1.0f)));
        }
    if (video_->gif) {
        std::vector<uint8_t> rgb(3 * std::size_t{width_} * height_);
        cv::Mat view(static_cast<int>(height_), static_cast<int>(width_), CV_8UC3, rgb.data());
        cv::cvtColor(bgr, view, cv::COLOR_BGR2RGB);
        video_->gif->add(rgb);
        return;
    }
    video_->writer.write(bgr);
}

void TurntableWriter::finish()
{
    if (!video_)
        return;
    if (video_->gif)
        video_->gif->close();
    else
        video_->writer.release();
    std::error_code e;
    if (!fs::exists(video_->partial) || fs::file_size(video_->partial, e) == 0)
        throw std::runtime_error("OpenCV wrote no video to " + path_.string());
    fs::rename(video_->partial, path_, e);
    if (e)
        throw std::runtime_error("cannot move the video into place as " + path_.string() + ": " + e.message());
    video_->done = true;
}

} // namespace arbor::io
