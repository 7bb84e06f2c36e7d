#include "label_slices.hpp"

#include "io/label_colors.hpp"
#include "io/png_output.hpp"

#include <opencv2/imgproc.hpp>

#include <algorithm>
#include <limits>

namespace arbor::cli {

namespace {

constexpr int kTitle = 28, kGap = 8;

} // namespace

void write_label_slices(const std::filesystem::path &path, const Volume &volume,
                        const std::vector<LabelPanel> &panels)
{
    const Geometry &g = volume.geometry();
    const int nx = static_cast<int>(g.dims[0]), ny = static_cast<int>(g.dims[1]);
    const int64_t k = g.dims[2] / 2;
    const std::size_t first = static_cast<std::size_t>(k) * nx * ny;

    double lo = std::numeric_limits<double>::infinity(), hi = -lo;
    for (std::size_t i = 0; i < static_cast<std::size_t>(nx) * ny; ++i) {
        const double v = volume.value(first + i);
        lo = std::min(lo, v);
        hi = std::max(hi, v);
    }
    const double range = hi > lo ? hi - lo : 1.0;
    // Small slices are enlarged (nearest neighbour) to at least 256 pixels.
    const int scale = std::max(1, 256 / std::max(nx, ny));
    const int w = nx * scale, h = ny * scale;
    const int count = static_cast<int>(panels.size()) + 1;
    cv::Mat image(kTitle + h + kGap, count * (w + kGap) + kGap, CV_8UC3, cv::Scalar(255, 255, 255));
    for (int p = 0; p < count; ++p) {
        const int x0 = kGap + p * (w + kGap);
        const std::string title = p == 0 ? "intensity (slice k=" + std::to_string(k) + ")" : panels[p - 1].title;
        cv::putText(image, title, {x0, 20}, cv::FONT_HERSHEY_SIMPLEX, std::min(0.5, 0.9 * w / (12.0 * title.size())),
                    cv::Scalar(30, 30, 30), 1, cv::LINE_AA);
        for (int j = 0; j < ny; ++j)
            for (int i = 0; i < nx; ++i) {
                const std::size_t v = first + static_cast<std::size_t>(j) * nx + i;
                const double grey = (volume.value(v) - lo) / range;
                cv::Vec3b pixel;
                if (p == 0) {
                    const auto b = static_cast<uint8_t>(255.0 * grey + 0.5);
                    pixel = {b, b, b};
                } else {
                    const io::Rgb8 c = io::label_color((*panels[p - 1].labels)[v]);
                    // Half label colour, half intensity: structures keep their shading.
                    for (int ch = 0; ch < 3; ++ch)
                        pixel[ch] = static_cast<uint8_t>(0.55 * c[2 - ch] + 0.45 * 255.0 * grey + 0.5);
                }
                cv::rectangle(image, cv::Rect(x0 + i * scale, kTitle + j * scale, scale, scale), pixel, cv::FILLED);
            }
    }
    io::write_png(path, image);
}

} // namespace arbor::cli
