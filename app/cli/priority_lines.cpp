#include "priority_lines.hpp"

#include "io/png_output.hpp"

#include <opencv2/imgproc.hpp>

#include <algorithm>
#include <cstdio>

namespace arbor::cli {

namespace {

constexpr int kLeft = 190, kRight = 20, kTop = 40, kRowHeight = 120, kPlotHeight = 90;
const cv::Scalar kKept(40, 110, 230), kDropped(170, 170, 170), kThreshold(40, 40, 210), kText(30, 30, 30);

std::string short_number(double x)
{
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.3g", x);
    return buf;
}

} // namespace

void write_priority_lines(const std::filesystem::path &path, const std::string &title,
                          const std::vector<PriorityRow> &rows)
{
    std::size_t columns = 0;
    for (const PriorityRow &r : rows)
        columns = std::max(columns, r.values.size());
    const int step = columns > 300 ? 1 : (columns > 150 ? 2 : (columns > 60 ? 4 : 8));
    const int plot_width = std::max(600, static_cast<int>(columns) * step);
    cv::Mat image(kTop + kRowHeight * static_cast<int>(rows.size()) + 10, kLeft + plot_width + kRight, CV_8UC3,
                  cv::Scalar(255, 255, 255));
    cv::putText(image, title, {10, 25}, cv::FONT_HERSHEY_SIMPLEX, 0.55, kText, 1, cv::LINE_AA);
    for (std::size_t r = 0; r < rows.size(); ++r) {
        const PriorityRow &row = rows[r];
        const int base = kTop + kRowHeight * static_cast<int>(r + 1) - 20;
        double top = row.threshold;
        for (double v : row.values)
            top = std::max(top, v);
        if (top <= 0)
            top = 1;
        cv::line(image, {kLeft, base}, {kLeft + plot_width, base}, kText, 1);
        cv::putText(image, row.name, {10, base - kPlotHeight / 2}, cv::FONT_HERSHEY_SIMPLEX, 0.5, kText, 1,
                    cv::LINE_AA);
        cv::putText(image, "max " + short_number(top), {10, base - kPlotHeight / 2 + 18}, cv::FONT_HERSHEY_SIMPLEX,
                    0.4, kText, 1, cv::LINE_AA);
        for (std::size_t c = 0; c < row.values.size(); ++c) {
            const int x = kLeft + static_cast<int>(c) * step + step / 2;
            const int h = static_cast<int>(row.values[c] / top * kPlotHeight + 0.5);
            cv::line(image, {x, base}, {x, base - std::max(h, 1)}, row.values[c] > row.threshold ? kKept : kDropped,
                     std::max(1, step / 2));
        }
        const int ty = base - static_cast<int>(row.threshold / top * kPlotHeight + 0.5);
        cv::line(image, {kLeft, ty}, {kLeft + plot_width, ty}, kThreshold, 1, cv::LINE_AA);
        cv::putText(image, "threshold " + short_number(row.threshold), {kLeft + plot_width - 150, ty - 4},
                    cv::FONT_HERSHEY_SIMPLEX, 0.4, kThreshold, 1, cv::LINE_AA);
    }
    io::write_png(path, image);
}

} // namespace arbor::cli
