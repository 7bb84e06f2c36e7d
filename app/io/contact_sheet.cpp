#include "contact_sheet.hpp"

#include "png_output.hpp"

#include <opencv2/imgproc.hpp>

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace arbor::io {

namespace {

const cv::Scalar kBackground(40, 40, 40), kInk(235, 235, 235);
constexpr int kCaption = 26, kMargin = 8, kTitle = 30;

// Premultiplied sRGB over the sheet's grey, as 8-bit BGR.
cv::Mat composite(const RenderedImage &image)
{
    cv::Mat bgr(static_cast<int>(image.height), static_cast<int>(image.width), CV_8UC3);
    for (uint32_t y = 0; y < image.height; ++y)
        for (uint32_t x = 0; x < image.width; ++x) {
            const float *p = &image.rgba[(std::size_t{y} * image.width + x) * 4];
            cv::Vec3b &q = bgr.at<cv::Vec3b>(static_cast<int>(y), static_cast<int>(x));
            for (int c = 0; c < 3; ++c) {
                const double v = p[c] + (1.0 - p[3]) * kBackground[2 - c] / 255.0;
                q[2 - c] = static_cast<uint8_t>(std::lround(255.0 * std::clamp(v, 0.0, 1.0)));
            }
        }
    return bgr;
}

void caption(cv::Mat &sheet, const std::string &text, cv::Point at, int width, double scale)
{
    int base = 0;
    std::string shown = text;
    // Shorten from the end until it fits the tile.
    while (shown.size() > 3 && cv::getTextSize(shown, cv::FONT_HERSHEY_SIMPLEX, scale, 1, &base).width > width)
        shown = shown.substr(0, shown.size() - 4) + "...";
    const cv::Size size = cv::getTextSize(shown, cv::FONT_HERSHEY_SIMPLEX, scale, 1, &base);
    cv::putText(sheet, shown, {at.x + (width - size.width) / 2, at.y}, cv::FONT_HERSHEY_SIMPLEX, scale, kInk, 1,
                cv::LINE_AA);
}

} // namespace

void write_contact_sheet(const std::filesystem::path &path, const std::string &title,
                         const std::vector<ContactSheetTile> &tiles, int tile)
{
    if (tiles.empty())
        throw std::invalid_argument("a contact sheet needs at least one image");
    const int n = static_cast<int>(tiles.size());
    const int columns = static_cast<int>(std::ceil(std::sqrt(static_cast<double>(n))));
    const int rows = (n + columns - 1) / columns;
    int cell_w = 0, cell_h = 0;
    std::vector<cv::Mat> scaled;
    for (const ContactSheetTile &t : tiles) {
        cv::Mat bgr = composite(*t.image);
        const double s = std::min(1.0, static_cast<double>(tile) / std::max(bgr.cols, bgr.rows));
        if (s < 1.0)
            cv::resize(bgr, bgr, cv::Size(), s, s, cv::INTER_AREA);
        cell_w = std::max(cell_w, bgr.cols);
        cell_h = std::max(cell_h, bgr.rows);
        scaled.push_back(std::move(bgr));
    }
    const int w = kMargin + columns * (cell_w + kMargin);
    const int h = kTitle + rows * (cell_h + kCaption + kMargin);
    cv::Mat sheet(h, w, CV_8UC3, kBackground);
    caption(sheet, title, {kMargin, 20}, w - 2 * kMargin, 0.55);
    for (int i = 0; i < n; ++i) {
        const int x = kMargin + (i % columns) * (cell_w + kMargin);
        const int y = kTitle + (i / columns) * (cell_h + kCaption + kMargin);
        const cv::Mat &m = scaled[static_cast<std::size_t>(i)];
        m.copyTo(sheet(cv::Rect(x + (cell_w - m.cols) / 2, y + (cell_h - m.rows) / 2, m.cols, m.rows)));
        caption(sheet, tiles[static_cast<std::size_t>(i)].caption, {x, y + cell_h + 18}, cell_w, 0.5);
    }
    write_png(path, sheet);
}

} // namespace arbor::io
