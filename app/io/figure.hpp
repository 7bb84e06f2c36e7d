// figure.hpp - figures for reports and papers: one drawing written as a PNG
// (rasterised at a chosen DPI) and as an SVG (vector), through cairo, with
// the same fonts (DejaVu Sans) and geometry in both.  Sizes are in points
// (1/72 inch), so a figure keeps its physical size at any DPI.
#pragma once

#include <opencv2/core.hpp>

#include <filesystem>
#include <functional>
#include <string>
#include <utility>
#include <vector>

typedef struct _cairo cairo_t;

namespace arbor::io {

struct Colour {
    double r = 0, g = 0, b = 0; // 0..1, sRGB
};
Colour colour_from_8bit(int r, int g, int b);

enum class TextAnchor { Start, Middle, End };
enum class Marker { Circle, Square, Triangle, Diamond };

// What a drawing draws with: a cairo context in points.
class Canvas {
public:
    explicit Canvas(cairo_t *cr) : cr_(cr) {}

    void line(double x0, double y0, double x1, double y1, Colour c, double width = 1.0, bool dashed = false);
    void polyline(const std::vector<std::pair<double, double>> &points, Colour c, double width = 1.0,
                  bool dashed = false);
    void rectangle(double x, double y, double w, double h, Colour fill);
    void frame(double x, double y, double w, double h, Colour stroke, double width = 1.0);
    void marker(double x, double y, Marker shape, double size, Colour fill);
    // `y` is the baseline; `angle` in degrees, counter-clockwise.
    void text(double x, double y, const std::string &text, double size, Colour c,
              TextAnchor anchor = TextAnchor::Start, bool bold = false, double angle = 0.0);
    double text_width(const std::string &text, double size, bool bold = false);
    // `text` shortened with an ellipsis until it fits `width`.
    std::string fitted(const std::string &text, double size, double width, bool bold = false);
    // An 8-bit BGR image into the rectangle, pixels drawn as squares (no
    // smoothing: label maps stay exact).
    void image(const cv::Mat &bgr, double x, double y, double w, double h);

private:
    void font(double size, bool bold);
    cairo_t *cr_;
};

using Drawing = std::function<void(Canvas &)>;

// Writes the drawing as `path`: .png (at `dpi`) or .svg; replaced only once
// whole.  Throws std::runtime_error naming the file.
void write_figure(const std::filesystem::path &path, double width_pt, double height_pt, double dpi,
                  const Drawing &draw);

// The PNG at `png_path` and its SVG twin beside it (same name, .svg).
void write_figure_with_svg(const std::filesystem::path &png_path, double width_pt, double height_pt, double dpi,
                           const Drawing &draw);

} // namespace arbor::io
