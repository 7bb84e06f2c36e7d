#include "figure.hpp"

#include "core/atomic_file.hpp"

#include <cairo-svg.h>
#include <cairo.h>

#include <cmath>
#include <memory>
#include <stdexcept>

namespace arbor::io {

namespace {

constexpr const char *kFont = "DejaVu Sans";

void set_colour(cairo_t *cr, Colour c) { cairo_set_source_rgb(cr, c.r, c.g, c.b); }

cairo_status_t append(void *closure, const unsigned char *data, unsigned int length)
{
    static_cast<std::string *>(closure)->append(reinterpret_cast<const char *>(data), length);
    return CAIRO_STATUS_SUCCESS;
}

struct SurfaceFree {
    void operator()(cairo_surface_t *s) const { cairo_surface_destroy(s); }
};
struct ContextFree {
    void operator()(cairo_t *c) const { cairo_destroy(c); }
};
using Surface = std::unique_ptr<cairo_surface_t, SurfaceFree>;
using Context = std::unique_ptr<cairo_t, ContextFree>;

void check(cairo_status_t status, const std::filesystem::path &path)
{
    if (status != CAIRO_STATUS_SUCCESS)
        throw std::runtime_error(path.string() + ": cannot draw the figure: " + cairo_status_to_string(status));
}

void draw_on(cairo_surface_t *surface, double scale, double width_pt, double height_pt, const Drawing &draw,
             const std::filesystem::path &path)
{
    Context cr(cairo_create(surface));
    check(cairo_status(cr.get()), path);
    cairo_scale(cr.get(), scale, scale);
    cairo_set_source_rgb(cr.get(), 1, 1, 1);
    cairo_rectangle(cr.get(), 0, 0, width_pt, height_pt);
    cairo_fill(cr.get());
    cairo_set_line_join(cr.get(), CAIRO_LINE_JOIN_ROUND);
    Canvas canvas(cr.get());
    draw(canvas);
    check(cairo_status(cr.get()), path);
}

} // namespace

Colour colour_from_8bit(int r, int g, int b) { return {r / 255.0, g / 255.0, b / 255.0}; }

void Canvas::line(double x0, double y0, double x1, double y1, Colour c, double width, bool dashed)
{
    polyline({{x0, y0}, {x1, y1}}, c, width, dashed);
}

void Canvas::polyline(const std::vector<std::pair<double, double>> &points, Colour c, double width, bool dashed)
{
    if (points.size() < 2)
        return;
    cairo_save(cr_);
    set_colour(cr_, c);
    cairo_set_line_width(cr_, width);
    if (dashed) {
        const double dash[] = {4.0 * width, 2.5 * width};
        cairo_set_dash(cr_, dash, 2, 0);
    }
    cairo_move_to(cr_, points[0].first, points[0].second);
    for (std::size_t i = 1; i < points.size(); ++i)
        cairo_line_to(cr_, points[i].first, points[i].second);
    cairo_stroke(cr_);
    cairo_restore(cr_);
}

void Canvas::rectangle(double x, double y, double w, double h, Colour fill)
{
    set_colour(cr_, fill);
    cairo_rectangle(cr_, x, y, w, h);
    cairo_fill(cr_);
}

void Canvas::frame(double x, double y, double w, double h, Colour stroke, double width)
{
    set_colour(cr_, stroke);
    cairo_set_line_width(cr_, width);
    cairo_rectangle(cr_, x, y, w, h);
    cairo_stroke(cr_);
}

void Canvas::marker(double x, double y, Marker shape, double size, Colour fill)
{
    const double r = size / 2;
    switch (shape) {
    case Marker::Circle:
        cairo_arc(cr_, x, y, r, 0, 2 * M_PI);
        break;
    case Marker::Square:
        cairo_rectangle(cr_, x - r * 0.9, y - r * 0.9, 1.8 * r, 1.8 * r);
        break;
    case Marker::Triangle:
        cairo_move_to(cr_, x, y - r * 1.1);
        cairo_line_to(cr_, x + r, y + r * 0.8);
        cairo_line_to(cr_, x - r, y + r * 0.8);
        cairo_close_path(cr_);
        break;
    case Marker::Diamond:
        cairo_move_to(cr_, x, y - r * 1.2);
        cairo_line_to(cr_, x + r, y);
        cairo_line_to(cr_, x, y + r * 1.2);
        cairo_line_to(cr_, x - r, y);
        cairo_close_path(cr_);
        break;
    }
    set_colour(cr_, fill);
    cairo_fill(cr_);
}

void Canvas::font(double size, bool bold)
{
    cairo_select_font_face(cr_, kFont, CAIRO_FONT_SLANT_NORMAL, bold ? CAIRO_FONT_WEIGHT_BOLD : CAIRO_FONT_WEIGHT_NORMAL);
    cairo_set_font_size(cr_, size);
}

double Canvas::text_width(const std::string &text, double size, bool bold)
{
    font(size, bold);
    cairo_text_extents_t e;
    cairo_text_extents(cr_, text.c_str(), &e);
    return e.x_advance;
}

std::string Canvas::fitted(const std::string &text, double size, double width, bool bold)
{
    if (text_width(text, size, bold) <= width)
        return text;
    std::string s = text;
    while (!s.empty()) {
        // Drop whole UTF-8 characters.
        do
            s.pop_back();
        while (!s.empty() && (static_cast<unsigned char>(s.back()) & 0xC0) == 0x80);
        if (text_width(s + "\u2026", size, bold) <= width)
            return s + "\u2026";
    }
    return s;
}

void Canvas::text(double x, double y, const std::string &text, double size, Colour c, TextAnchor anchor, bool bold,
                  double angle)
{
    const double w = text_width(text, size, bold);
    cairo_save(cr_);
    cairo_translate(cr_, x, y);
    cairo_rotate(cr_, -angle * M_PI / 180.0);
    const double dx = anchor == TextAnchor::Start ? 0.0 : (anchor == TextAnchor::Middle ? -w / 2 : -w);
    cairo_move_to(cr_, dx, 0);
    set_colour(cr_, c);
    cairo_show_text(cr_, text.c_str());
    cairo_restore(cr_);
}

void Canvas::image(const cv::Mat &bgr, double x, double y, double w, double h)
{
    if (bgr.empty() || bgr.type() != CV_8UC3)
        throw std::invalid_argument("Canvas::image takes an 8-bit BGR image");
    Surface surface(cairo_image_surface_create(CAIRO_FORMAT_RGB24, bgr.cols, bgr.rows));
    cairo_surface_flush(surface.get());
    unsigned char *data = cairo_image_surface_get_data(surface.get());
    const int stride = cairo_image_surface_get_stride(surface.get());
    for (int r = 0; r < bgr.rows; ++r) {
        auto *row = reinterpret_cast<uint32_t *>(data + static_cast<std::ptrdiff_t>(r) * stride);
        const cv::Vec3b *in = bgr.ptr<cv::Vec3b>(r);
        for (int c = 0; c < bgr.cols; ++c)
            row[c] = (uint32_t{in[c][2]} << 16) | (uint32_t{in[c][1]} << 8) | in[c][0];
    }
    cairo_surface_mark_dirty(surface.get());
    cairo_save(cr_);
    cairo_translate(cr_, x, y);
    cairo_scale(cr_, w / bgr.cols, h / bgr.rows);
    cairo_set_source_surface(cr_, surface.get(), 0, 0);
    cairo_pattern_set_filter(cairo_get_source(cr_), CAIRO_FILTER_NEAREST);
    cairo_rectangle(cr_, 0, 0, bgr.cols, bgr.rows);
    cairo_fill(cr_);
    cairo_restore(cr_);
}

void write_figure(const std::filesystem::path &path, double width_pt, double height_pt, double dpi,
                  const Drawing &draw)
{
    if (!(dpi >= 18 && dpi <= 2400))
        throw std::invalid_argument(path.string() + ": a DPI between 18 and 2400 is expected");
    std::string bytes;
    const std::string ext = path.extension().string();
    if (ext == ".svg") {
        Surface surface(cairo_svg_surface_create_for_stream(append, &bytes, width_pt, height_pt));
        check(cairo_surface_status(surface.get()), path);
        cairo_svg_surface_restrict_to_version(surface.get(), CAIRO_SVG_VERSION_1_1);
        draw_on(surface.get(), 1.0, width_pt, height_pt, draw, path);
        cairo_surface_finish(surface.get());
        check(cairo_surface_status(surface.get()), path);
    } else if (ext == ".png") {
        const double scale = dpi / 72.0;
        const int w = static_cast<int>(std::ceil(width_pt * scale)), h = static_cast<int>(std::ceil(height_pt * scale));
        Surface surface(cairo_image_surface_create(CAIRO_FORMAT_RGB24, w, h));
        check(cairo_surface_status(surface.get()), path);
        draw_on(surface.get(), scale, width_pt, height_pt, draw, path);
        cairo_surface_flush(surface.get());
        check(cairo_surface_write_to_png_stream(surface.get(), append, &bytes), path);
    } else {
        throw std::invalid_argument(path.string() + ": figures are written as .png or .svg");
    }
    AtomicFile out(path);
    out.write(bytes);
    out.commit();
}

void write_figure_with_svg(const std::filesystem::path &png_path, double width_pt, double height_pt, double dpi,
                           const Drawing &draw)
{
    write_figure(png_path, width_pt, height_pt, dpi, draw);
    std::filesystem::path svg = png_path;
    svg.replace_extension(".svg");
    write_figure(svg, width_pt, height_pt, dpi, draw);
}

} // namespace arbor::io
