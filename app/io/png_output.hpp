// png_output.hpp - writing an OpenCV image (8-bit BGR) as a PNG file, replaced
// only once complete.
#pragma once

#include <opencv2/core.hpp>

#include <filesystem>

namespace arbor::io {

// Throws std::runtime_error naming the file on failure.
void write_png(const std::filesystem::path &path, const cv::Mat &image);

} // namespace arbor::io
