// plot_frame.hpp - the axes of a figure's plot: linear or logarithmic
// scales with readable ticks (1-2-5 steps, or decades), tick labels, axis
// titles and a light grid, and the mapping from data to the page.
#pragma once

#include "figure.hpp"

#include <string>
#include <vector>

namespace arbor::io {

struct AxisScale {
    double lo = 0.0, hi = 1.0; // the range shown (lo > 0 on a log scale)
    bool log = false;
    std::string title;
};

// Tick positions inside [lo, hi]: round 1-2-5 steps, at most about
// `target` of them; decades (and 2, 5 between them when few) on a log scale.
std::vector<double> axis_ticks(const AxisScale &axis, int target = 6);
// "0.05", "1e-04", "120", "2.5k"-free plain text a reader can check.
std::string tick_label(double value);
// A value in a label (a cut level): four significant digits, so close
// levels stay apart.
std::string value_label(double value);

class PlotFrame {
public:
    // The plotting rectangle on the page (points; y grows downwards).
    PlotFrame(double x, double y, double width, double height, AxisScale xs, AxisScale ys);

    double px(double value) const;
    double py(double value) const;
    double left() const { return x_; }
    double top() const { return y_; }
    double width() const { return w_; }
    double height() const { return h_; }
    const AxisScale &x_axis() const { return xs_; }
    const AxisScale &y_axis() const { return ys_; }

    // Grid, frame, ticks with labels, and the axis titles outside the rectangle.
    void draw_axes(Canvas &canvas, double font_size) const;

private:
    double fraction(const AxisScale &axis, double value) const;
    double x_, y_, w_, h_;
    AxisScale xs_, ys_;
};

} // namespace arbor::io
