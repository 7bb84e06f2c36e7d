#include "plot_frame.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>

namespace arbor::io {

namespace {

const Colour kInk{0.12, 0.12, 0.12}, kGrid{0.88, 0.88, 0.88};

} // namespace

std::vector<double> axis_ticks(const AxisScale &axis, int target)
{
    std::vector<double> ticks;
    const double lo = std::min(axis.lo, axis.hi), hi = std::max(axis.lo, axis.hi);
    if (!(hi > lo) || !std::isfinite(lo) || !std::isfinite(hi))
        return {lo};
    if (axis.log) {
        if (!(lo > 0))
            throw std::invalid_argument("a log axis needs a positive range");
        const int first = static_cast<int>(std::floor(std::log10(lo))), last = static_cast<int>(std::ceil(std::log10(hi)));
        const int decades = last - first;
        const int every = std::max(1, decades / std::max(1, target));
        for (int e = first; e <= last; e += every)
            for (const double m : decades <= 2 ? std::vector<double>{1, 2, 5} : std::vector<double>{1}) {
                const double t = m * std::pow(10.0, e);
                if (t >= lo * (1 - 1e-9) && t <= hi * (1 + 1e-9))
                    ticks.push_back(t);
            }
        return ticks;
    }
    const double raw = (hi - lo) / std::max(1, target);
    const double magnitude = std::pow(10.0, std::floor(std::log10(raw)));
    double step = magnitude;
    for (const double m : {1.0, 2.0, 5.0, 10.0})
        if (m * magnitude >= raw) {
            step = m * magnitude;
            break;
        }
    for (double t = std::ceil(lo / step - 1e-9) * step; t <= hi + step * 1e-9; t += step)
        ticks.push_back(std::abs(t) < step * 1e-9 ? 0.0 : t);
    return ticks;
}

std::string tick_label(double value)
{
    char buf[32];
    const double a = std::abs(value);
    if (value == 0)
        return "0";
    if (a >= 1e5 || a < 1e-3)
        std::snprintf(buf, sizeof buf, "%.0e", value);
    else
        std::snprintf(buf, sizeof buf, "%.4g", value);
    return buf;
}

std::string value_label(double value)
{
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.4g", value);
    return buf;
}

PlotFrame::PlotFrame(double x, double y, double width, double height, AxisScale xs, AxisScale ys)
    : x_(x), y_(y), w_(width), h_(height), xs_(std::move(xs)), ys_(std::move(ys))
{
    for (const AxisScale *a : {&xs_, &ys_})
        if (a->log && !(a->lo > 0 && a->hi > 0))
            throw std::invalid_argument("a log axis needs a positive range");
}

double PlotFrame::fraction(const AxisScale &axis, double value) const
{
    if (axis.hi == axis.lo)
        return 0.5;
    if (axis.log)
        return (std::log(std::max(value, axis.lo * 1e-6)) - std::log(axis.lo)) / (std::log(axis.hi) - std::log(axis.lo));
    return (value - axis.lo) / (axis.hi - axis.lo);
}

double PlotFrame::px(double value) const { return x_ + w_ * fraction(xs_, value); }
double PlotFrame::py(double value) const { return y_ + h_ * (1.0 - fraction(ys_, value)); }

void PlotFrame::draw_axes(Canvas &canvas, double font_size) const
{
    const std::vector<double> xt = axis_ticks(xs_), yt = axis_ticks(ys_);
    for (const double t : xt)
        canvas.line(px(t), y_, px(t), y_ + h_, kGrid, 0.5);
    for (const double t : yt)
        canvas.line(x_, py(t), x_ + w_, py(t), kGrid, 0.5);
    canvas.frame(x_, y_, w_, h_, kInk, 0.8);
    const double tick = font_size * 0.4;
    for (const double t : xt) {
        canvas.line(px(t), y_ + h_, px(t), y_ + h_ + tick, kInk, 0.8);
        canvas.text(px(t), y_ + h_ + tick + font_size, tick_label(t), font_size, kInk, TextAnchor::Middle);
    }
    double widest = 0;
    for (const double t : yt) {
        canvas.line(x_ - tick, py(t), x_, py(t), kInk, 0.8);
        canvas.text(x_ - tick - 2, py(t) + font_size * 0.35, tick_label(t), font_size, kInk, TextAnchor::End);
        widest = std::max(widest, canvas.text_width(tick_label(t), font_size));
    }
    if (!xs_.title.empty())
        canvas.text(x_ + w_ / 2, y_ + h_ + tick + 2.3 * font_size, canvas.fitted(xs_.title, font_size, w_), font_size,
                    kInk, TextAnchor::Middle);
    if (!ys_.title.empty())
        canvas.text(x_ - tick - widest - 0.6 * font_size, y_ + h_ / 2, canvas.fitted(ys_.title, font_size, h_),
                    font_size, kInk, TextAnchor::Middle, false, 90.0);
}

} // namespace arbor::io
