#include "diagram_plot.hpp"

#include "io/figure.hpp"
#include "io/plot_frame.hpp"
#include "topology/persistence_diagram.hpp"

#include <algorithm>
#include <array>
#include <cstdio>
#include <limits>

namespace arbor::cli {

namespace {

const io::Colour kInk{0.1, 0.1, 0.1};
const io::Colour kDiagonal{0.45, 0.45, 0.45};
// Colour-blind safe (Okabe-Ito): blue, vermillion, bluish green; black for
// the essential pair.
const std::array<io::Colour, 3> kDimensionColour{io::Colour{0.0, 0.447, 0.698}, io::Colour{0.835, 0.369, 0.0},
                                                 io::Colour{0.0, 0.620, 0.451}};
const std::array<io::Marker, 3> kDimensionMarker{io::Marker::Circle, io::Marker::Triangle, io::Marker::Square};

std::string count_text(std::size_t n)
{
    char buf[32];
    std::snprintf(buf, sizeof buf, "%zu", n);
    return buf;
}

} // namespace

void write_diagram_plot(const std::filesystem::path &path, const std::vector<topology::PersistencePair> &pairs,
                        int grid_dimension, const std::string &title, const std::string &unit,
                        const DiagramPlotStyle &style)
{
    double lo = std::numeric_limits<double>::infinity(), hi = -lo;
    std::array<std::size_t, 4> per_dimension{};
    std::size_t essential = 0;
    for (const topology::PersistencePair &p : pairs) {
        lo = std::min(lo, p.birth_value);
        hi = std::max(hi, p.death_value);
        if (p.type == -1)
            ++essential;
        else
            ++per_dimension[static_cast<std::size_t>(std::clamp(topology::pair_dimension(p.type, grid_dimension), 0, 3))];
    }
    if (pairs.empty()) {
        lo = 0;
        hi = 1;
    }
    const double pad = (hi > lo ? hi - lo : 1.0) * 0.03;
    const std::string suffix = unit.empty() ? "" : " (" + unit + ")";
    const io::AxisScale xs{lo - pad, hi + pad, false, "birth" + suffix};
    const io::AxisScale ys{lo - pad, hi + pad, false, "death" + suffix};
    const double side = style.size_inches * 72.0;
    const double font = std::clamp(side / 32.0, 7.0, 11.0);
    const double left = 4.6 * font, bottom = 3.4 * font, top = 2.4 * font, right = 0.8 * font;
    const double plot = std::min(side - left - right, side - top - bottom);
    std::string heading = title + ": " + count_text(pairs.size()) + " pairs";

    io::write_figure(path, side, side, style.dpi, [&](io::Canvas &canvas) {
        const io::PlotFrame frame(left, top, plot, plot, xs, ys);
        frame.draw_axes(canvas, font);
        canvas.text(left + plot / 2, top - 0.9 * font, canvas.fitted(heading, font * 1.1, side - 2 * right, true),
                    font * 1.1, kInk, io::TextAnchor::Middle, true);
        canvas.line(frame.px(xs.lo), frame.py(ys.lo), frame.px(xs.hi), frame.py(ys.hi), kDiagonal, 0.8, true);
        const double marker = std::max(1.6, font * 0.32);
        // Finite pairs, the larger dimension last so that the rarer maxima
        // stay visible; the essential pair on top.
        for (int dim = 0; dim <= 3; ++dim)
            for (const topology::PersistencePair &p : pairs) {
                if (p.type == -1)
                    continue;
                const int d = topology::pair_dimension(p.type, grid_dimension);
                if (d != dim)
                    continue;
                const std::size_t style_index = static_cast<std::size_t>(std::min(d == 0 ? 0 : d == 1 ? 2 : 1, 2));
                canvas.marker(frame.px(p.birth_value), frame.py(p.death_value), kDimensionMarker[style_index], marker,
                              kDimensionColour[style_index]);
            }
        for (const topology::PersistencePair &p : pairs)
            if (p.type == -1)
                canvas.marker(frame.px(p.birth_value), frame.py(p.death_value), io::Marker::Diamond, marker * 2.2,
                              kInk);

        // Legend, top left inside the plot (the empty corner above the diagonal).
        double y = top + 1.4 * font;
        const double x = left + 0.9 * font;
        const auto entry = [&](io::Marker m, const io::Colour &c, double size, const std::string &label) {
            canvas.marker(x, y - 0.3 * font, m, size, c);
            canvas.text(x + 0.9 * font, y, label, font * 0.9, kInk);
            y += 1.3 * font;
        };
        for (int dim = 0; dim <= 3; ++dim) {
            if (per_dimension[static_cast<std::size_t>(dim)] == 0)
                continue;
            const std::size_t style_index = static_cast<std::size_t>(std::min(dim == 0 ? 0 : dim == 1 ? 2 : 1, 2));
            const char *what = dim == 0 ? " (minimum, saddle)" : dim == grid_dimension - 1 ? " (saddle, maximum)" : "";
            entry(kDimensionMarker[style_index], kDimensionColour[style_index], marker * 1.4,
                  "dimension " + std::to_string(dim) + what + ": " +
                      count_text(per_dimension[static_cast<std::size_t>(dim)]));
        }
        if (essential > 0)
            entry(io::Marker::Diamond, kInk, marker * 2.2, "essential (global min, max)");
    });
}

} // namespace arbor::cli
