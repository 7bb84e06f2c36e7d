#include "png_output.hpp"

#include "core/atomic_file.hpp"

#include <opencv2/imgcodecs.hpp>

#include <stdexcept>
#include <vector>

namespace arbor::io {

void write_png(const std::filesystem::path &path, const cv::Mat &image)
{
    std::vector<uchar> bytes;
    if (!cv::imencode(".png", image, bytes))
        throw std::runtime_error(path.string() + ": could not encode the image as PNG");
    AtomicFile file(path);
    file.write(bytes.data(), bytes.size());
    file.commit();
}

} // namespace arbor::io
