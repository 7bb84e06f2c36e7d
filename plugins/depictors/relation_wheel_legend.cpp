#include "relation_wheel_legend.hpp"

#include <opencv2/imgproc.hpp>

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

namespace arbor::depictors {

Neighbourhood neighbourhood(const sdk::BranchTreeView &tree, uint32_t selected)
{
    Neighbourhood n;
    n.selected = selected;
    n.parent = tree.parent(selected);
    for (uint32_t c : tree.children(selected))
        n.children.push_back(c);
    if (n.parent >= 0)
        for (uint32_t s : tree.children(static_cast<uint32_t>(n.parent)))
            if (s != selected)
                n.siblings.push_back(s);
    return n;
}

namespace {

constexpr double kPi = 3.14159265358979323846;

// BGR of a fully saturated hue, for the markers.
cv::Scalar hue_colour(double hue)
{
    cv::Mat hsv(1, 1, CV_8UC3, cv::Scalar(hue / 2.0, 220, 235)), bgr;
    cv::cvtColor(hsv, bgr, cv::COLOR_HSV2BGR);
    const cv::Vec3b c = bgr.at<cv::Vec3b>(0, 0);
    return {static_cast<double>(c[0]), static_cast<double>(c[1]), static_cast<double>(c[2])};
}

class WheelCanvas {
public:
    explicit WheelCanvas(cv::Mat &m)
        : m_(m), centre_(m.cols / 2.0, m.rows / 2.0 + 8), outer_(0.36 * std::min(m.cols, m.rows)),
          inner_(0.22 * std::min(m.cols, m.rows))
    {
    }

    cv::Point at(double hue, double radius) const
    {
        const double a = hue * kPi / 180.0; // hue 0 to the right, counter-clockwise
        return {static_cast<int>(std::lround(centre_.x + radius * std::cos(a))),
                static_cast<int>(std::lround(centre_.y - radius * std::sin(a)))};
    }

    void sector(double centre, double width, const cv::Scalar &fill)
    {
        std::vector<cv::Point> ring;
        for (int i = 0; i <= 48; ++i)
            ring.push_back(at(centre - width / 2 + width * i / 48.0, outer_));
        for (int i = 48; i >= 0; --i)
            ring.push_back(at(centre - width / 2 + width * i / 48.0, inner_));
        cv::fillPoly(m_, std::vector<std::vector<cv::Point>>{ring}, fill, cv::LINE_AA);
    }

    void marker(double hue, const std::string &text, double scale)
    {
        const cv::Point p = at(hue, (outer_ + inner_) / 2);
        cv::circle(m_, p, std::max(4, static_cast<int>(0.025 * m_.cols)), hue_colour(hue), cv::FILLED, cv::LINE_AA);
        cv::circle(m_, p, std::max(4, static_cast<int>(0.025 * m_.cols)), cv::Scalar(40, 40, 40), 1, cv::LINE_AA);
        const cv::Point q = at(hue, outer_ + 0.07 * m_.cols);
        int base = 0;
        const cv::Size size = cv::getTextSize(text, cv::FONT_HERSHEY_SIMPLEX, scale, 1, &base);
        cv::putText(m_, text, {q.x - size.width / 2, q.y + size.height / 2}, cv::FONT_HERSHEY_SIMPLEX, scale,
                    cv::Scalar(30, 30, 30), 1, cv::LINE_AA);
    }

    void outline()
    {
        cv::circle(m_, centre_, static_cast<int>(outer_), cv::Scalar(90, 90, 90), 1, cv::LINE_AA);
        cv::circle(m_, centre_, static_cast<int>(inner_), cv::Scalar(90, 90, 90), 1, cv::LINE_AA);
    }

private:
    cv::Mat &m_;
    cv::Point2d centre_;
    double outer_, inner_;
};

} // namespace

void draw_relation_wheel(const Neighbourhood &n, const RelationWheel &wheel, arbor_image &image)
{
    cv::Mat m(static_cast<int>(image.height), static_cast<int>(image.width), CV_8UC3, cv::Scalar(255, 255, 255));
    WheelCanvas canvas(m);
    const double scale = std::clamp(image.width / 700.0, 0.3, 0.8);
    canvas.sector(wheel.children_centre(), RelationWheel::kSectorWidth, cv::Scalar(215, 215, 215));
    canvas.sector(wheel.siblings_centre(), RelationWheel::kSectorWidth, cv::Scalar(215, 215, 215));
    canvas.outline();
    for (std::size_t k = 0; k < n.children.size(); ++k)
        canvas.marker(wheel.child_hue(k, n.children.size()), std::to_string(n.children[k]), scale);
    for (std::size_t k = 0; k < n.siblings.size(); ++k)
        canvas.marker(wheel.sibling_hue(k, n.siblings.size()), std::to_string(n.siblings[k]), scale);
    canvas.marker(wheel.selected_hue(), "selected " + std::to_string(n.selected), scale);
    if (n.parent >= 0)
        canvas.marker(wheel.parent_hue(), "parent " + std::to_string(n.parent), scale);
    cv::putText(m, "children: grey sector at " + std::to_string(static_cast<int>(wheel.children_centre())) +
                       " deg, siblings opposite",
                {8, static_cast<int>(image.height) - 8}, cv::FONT_HERSHEY_SIMPLEX, scale * 0.6, cv::Scalar(90, 90, 90),
                1, cv::LINE_AA);
    for (uint32_t y = 0; y < image.height; ++y)
        for (uint32_t x = 0; x < image.width; ++x) {
            const cv::Vec3b c = m.at<cv::Vec3b>(static_cast<int>(y), static_cast<int>(x));
            float *px = image.rgba + y * image.row_stride + 4 * x;
            px[0] = c[2] / 255.0f;
            px[1] = c[1] / 255.0f;
            px[2] = c[0] / 255.0f;
            px[3] = 1.0f;
        }
    if (image.depth)
        std::fill(image.depth, image.depth + std::size_t{image.width} * image.height,
                  std::numeric_limits<float>::infinity());
}

} // namespace arbor::depictors
