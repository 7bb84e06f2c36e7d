#include "study_figures.hpp"

#include "comparison_report.hpp"
#include "study_grid.hpp"

#include "io/figure.hpp"
#include "io/label_colors.hpp"
#include "io/plot_frame.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <numeric>
#include <set>

namespace arbor::cli {

namespace {

using io::Canvas;
using io::Colour;

const Colour kInk{0.12, 0.12, 0.12}, kMuted{0.55, 0.55, 0.55}, kCutLine{0.80, 0.15, 0.12};
constexpr double kFont = 8.0, kTitleFont = 9.5;

// Distinct line colours (Okabe-Ito, readable by colour-blind readers).
Colour series_colour(std::size_t i)
{
    static const Colour palette[] = {io::colour_from_8bit(0, 114, 178),   io::colour_from_8bit(213, 94, 0),
                                     io::colour_from_8bit(0, 158, 115),   io::colour_from_8bit(204, 121, 167),
                                     io::colour_from_8bit(230, 159, 0),   io::colour_from_8bit(86, 180, 233),
                                     io::colour_from_8bit(120, 120, 120), io::colour_from_8bit(0, 0, 0)};
    return palette[i % std::size(palette)];
}
io::Marker series_marker(std::size_t i)
{
    static const io::Marker markers[] = {io::Marker::Circle, io::Marker::Square, io::Marker::Triangle,
                                         io::Marker::Diamond};
    return markers[i % std::size(markers)];
}

Colour from_rgb8(const io::Rgb8 &c) { return io::colour_from_8bit(c[0], c[1], c[2]); }

// ---- priority lines -------------------------------------------------------

void write_priority_lines(const std::filesystem::path &path, const StudyOutcome &study, const FilterOutcome &f,
                          const FigureOptions &options)
{
    const std::size_t rows = f.simplifiers.size();
    // Columns: the most important branches of every row, so the kept ones and
    // those just below each line are all visible, in branch order.
    std::set<std::size_t> columns;
    const std::size_t per_row = std::max<std::size_t>(20, options.max_priority_columns / std::max<std::size_t>(rows, 1));
    for (const std::vector<double> &values : f.priorities) {
        std::vector<std::size_t> idx(values.size());
        std::iota(idx.begin(), idx.end(), std::size_t{0});
        const std::size_t take = std::min(per_row, idx.size());
        std::partial_sort(idx.begin(), idx.begin() + static_cast<std::ptrdiff_t>(take), idx.end(),
                          [&](std::size_t a, std::size_t b) { return values[a] > values[b]; });
        columns.insert(idx.begin(), idx.begin() + static_cast<std::ptrdiff_t>(take));
    }
    const std::vector<std::size_t> shown(columns.begin(), columns.end());
    const std::size_t total = f.priorities.empty() ? 0 : f.priorities.front().size();
    // Which cuts get a line: all of a few, else the first, middle and last.
    std::vector<std::size_t> lines;
    const std::size_t cuts = study.grid.cuts.size();
    if (cuts <= 4)
        for (std::size_t c = 0; c < cuts; ++c)
            lines.push_back(c);
    else
        lines = {0, cuts / 2, cuts - 1};

    const double row_h = 96, left = 64, right = 92, top = 36, gap = 30;
    const double plot_w = std::clamp(static_cast<double>(shown.size()) * 1.6, 360.0, 900.0);
    const double width = left + plot_w + right, height = top + rows * (row_h + gap) + 24;
    io::write_figure_with_svg(path, width, height, options.dpi, [&](Canvas &cv) {
        cv.text(8, 15,
                cv.fitted("Priority lines (" + f.filter.label + "): " + std::to_string(shown.size()) + " of " +
                              std::to_string(total) + " branches of the " + f.simplifiers.front().simplifier.label +
                              " decomposition, in branch order",
                          kTitleFont, width - 16, true),
                kTitleFont, kInk, io::TextAnchor::Start, true);
        cv.text(8, 27,
                cv.fitted("Each row: one simplifier's importance of the same branches (log scale); coloured bars lie "
                          "above its first cut's line",
                          kFont, width - 16),
                kFont, kMuted);
        for (std::size_t r = 0; r < rows; ++r) {
            const std::vector<double> &values = f.priorities[r];
            double hi = 0, lo = INFINITY;
            for (const std::size_t c : shown)
                if (values[c] > 0) {
                    hi = std::max(hi, values[c]);
                    lo = std::min(lo, values[c]);
                }
            for (const std::size_t l : lines)
                if (f.simplifiers[r].cuts[l].level > 0) {
                    hi = std::max(hi, f.simplifiers[r].cuts[l].level);
                    lo = std::min(lo, f.simplifiers[r].cuts[l].level);
                }
            if (!(hi > 0)) {
                hi = 1;
                lo = 0.1;
            }
            lo = std::pow(10.0, std::floor(std::log10(std::max(lo, hi * 1e-8))));
            hi = std::pow(10.0, std::ceil(std::log10(hi)));
            if (hi <= lo)
                hi = lo * 10;
            const double y0 = top + r * (row_h + gap) + 14;
            const io::PlotFrame frame(left, y0, plot_w, row_h,
                                      {0.0, static_cast<double>(shown.size()), false,
                                       r + 1 == rows ? "branches shown (columns), in branch order" : ""},
                                      {lo, hi, true, "importance"});
            frame.draw_axes(cv, kFont - 1);
            cv.text(left, y0 - 4, cv.fitted(f.simplifiers[r].simplifier.label, kFont + 0.5, plot_w, true),
                    kFont + 0.5, kInk, io::TextAnchor::Start, true);
            const double first_level = f.simplifiers[r].cuts[0].level;
            const double bar = std::max(0.4, std::min(3.0, plot_w / std::max<std::size_t>(shown.size(), 1) * 0.7));
            for (std::size_t i = 0; i < shown.size(); ++i) {
                const double v = values[shown[i]];
                if (!(v > 0))
                    continue;
                const double x = frame.px(static_cast<double>(i) + 0.5);
                cv.line(x, frame.py(lo), x, frame.py(std::max(v, lo)),
                        v > first_level ? series_colour(0) : Colour{0.75, 0.75, 0.75}, bar);
            }
            // Cut lines, their labels moved apart where levels are close.
            double last_label = -INFINITY;
            std::vector<std::pair<double, std::size_t>> marks;
            for (const std::size_t l : lines)
                if (f.simplifiers[r].cuts[l].level > 0)
                    marks.emplace_back(frame.py(std::clamp(f.simplifiers[r].cuts[l].level, lo, hi)), l);
            std::sort(marks.begin(), marks.end());
            for (const auto &[y, l] : marks) {
                cv.line(left, y, left + plot_w, y, kCutLine, 0.8, l != 0);
                const double label_y = std::max(y + 3, last_label + kFont);
                cv.text(left + plot_w + 4, label_y,
                        cut_name(study.grid.cuts[l]) + ": " + io::value_label(f.simplifiers[r].cuts[l].level),
                        kFont - 1, kCutLine);
                last_label = label_y;
            }
        }
    });
}

// ---- Dice against the cut --------------------------------------------------

double cut_value(const pipeline::CutChoice &c)
{
    return c.keep ? static_cast<double>(*c.keep) : c.threshold.value_or(0.0);
}

void write_dice_plot(const std::filesystem::path &path, const StudyOutcome &study, std::size_t t,
                     const FigureOptions &options)
{
    const std::size_t panels = study.filters.size();
    const bool keeps = study.grid.cuts.front().keep.has_value();
    double lo = INFINITY, hi = 0;
    for (const pipeline::CutChoice &c : study.grid.cuts) {
        lo = std::min(lo, cut_value(c));
        hi = std::max(hi, cut_value(c));
    }
    const bool log = lo > 0 && hi / lo >= 8;
    if (hi <= lo) {
        lo = log ? lo / 2 : lo - 1;
        hi = log ? hi * 2 : hi + 1;
    } else if (log) {
        lo /= 1.3;
        hi *= 1.3;
    }
    const double panel_w = 230, panel_h = 170, left = 50, top = 40, between = 40, legend_h = 16;
    const std::size_t series = study.filters.front().simplifiers.size();
    const double width = left + panels * panel_w + (panels - 1) * between + 16;
    const double height = top + panel_h + 44 + legend_h * static_cast<double>((series + 1) / 2);
    const TruthStructure &truth = study.truth[t];
    io::write_figure_with_svg(path, width, height, options.dpi, [&](Canvas &cv) {
        cv.text(8, 15,
                cv.fitted("Dice with " + truth.name + " (" +
                              (truth.name == "label " + std::to_string(truth.label)
                                   ? std::string()
                                   : "label " + std::to_string(truth.label) + ", ") +
                              std::to_string(truth.voxels) + " voxels), one-to-one matching, " +
                              scoring_name(study.scoring) + " regions",
                          kTitleFont, width - 16, true),
                kTitleFont, kInk, io::TextAnchor::Start, true);
        for (std::size_t f = 0; f < panels; ++f) {
            const FilterOutcome &fo = study.filters[f];
            const double x0 = left + f * (panel_w + between);
            const io::PlotFrame frame(x0, top, panel_w, panel_h,
                                      {lo, hi, log, keeps ? "branches kept" : "importance threshold"},
                                      {0.0, 1.0, false, f == 0 ? "Dice" : ""});
            frame.draw_axes(cv, kFont);
            cv.text(x0 + panel_w / 2, top - 5, cv.fitted("filter: " + fo.filter.label, kFont, panel_w), kFont, kInk,
                    io::TextAnchor::Middle);
            for (std::size_t s = 0; s < fo.simplifiers.size(); ++s) {
                std::vector<std::pair<double, double>> points;
                for (std::size_t c = 0; c < study.grid.cuts.size(); ++c)
                    points.emplace_back(frame.px(cut_value(study.grid.cuts[c])),
                                        frame.py(fo.simplifiers[s].cuts[c].scores->one_to_one[t].dice));
                std::sort(points.begin(), points.end());
                cv.polyline(points, series_colour(s), 1.2);
                for (const auto &[x, y] : points)
                    cv.marker(x, y, series_marker(s), 4.5, series_colour(s));
            }
        }
        // Legend under the panels.
        const double ly = top + panel_h + 36;
        for (std::size_t s = 0; s < series; ++s) {
            const double x = left + static_cast<double>(s % 2) * (width - left) / 2.0;
            const double y = ly + legend_h * static_cast<double>(s / 2);
            cv.line(x, y - 3, x + 16, y - 3, series_colour(s), 1.2);
            cv.marker(x + 8, y - 3, series_marker(s), 4.5, series_colour(s));
            cv.text(x + 20, y,
                    cv.fitted(study.filters.front().simplifiers[s].simplifier.label, kFont, (width - left) / 2.0 - 26),
                    kFont, kInk);
        }
    });
}

// ---- label panels ------------------------------------------------------------

struct SliceGrid {
    int64_t width = 0, height = 0, index = 0, count = 0;
    // Voxel index of pixel (x, y) of the slice.
    std::function<std::size_t(int64_t, int64_t)> voxel;
};

SliceGrid slice_grid(const Geometry &g, SliceAxis axis, int64_t index)
{
    const int64_t nx = g.dims[0], ny = g.dims[1], nz = g.dims[2];
    SliceGrid s;
    s.index = index;
    switch (axis) {
    case SliceAxis::Axial:
        s = {nx, ny, index, nz, [=](int64_t x, int64_t y) { return static_cast<std::size_t>((index * ny + y) * nx + x); }};
        break;
    case SliceAxis::Coronal: // x across, z up
        s = {nx, nz, index, ny,
             [=](int64_t x, int64_t y) { return static_cast<std::size_t>(((nz - 1 - y) * ny + index) * nx + x); }};
        break;
    case SliceAxis::Sagittal: // y across, z up
        s = {ny, nz, index, nx,
             [=](int64_t x, int64_t y) { return static_cast<std::size_t>(((nz - 1 - y) * ny + x) * nx + index); }};
        break;
    }
    return s;
}

const char *axis_name(SliceAxis a)
{
    return a == SliceAxis::Axial ? "axial" : (a == SliceAxis::Coronal ? "coronal" : "sagittal");
}

// The slice with the most ground-truth voxels, else the middle one.
int64_t chosen_slice(const StudyOutcome &study, SliceAxis axis, std::string &why)
{
    const Geometry &g = study.geometry;
    const int64_t count = axis == SliceAxis::Axial ? g.dims[2] : (axis == SliceAxis::Coronal ? g.dims[1] : g.dims[0]);
    if (!study.truth_labels) {
        why = "the middle slice";
        return count / 2;
    }
    std::vector<uint64_t> per(static_cast<std::size_t>(count), 0);
    const int64_t nx = g.dims[0], ny = g.dims[1];
    const std::vector<uint32_t> &index = study.truth_labels->index;
    for (std::size_t v = 0; v < index.size(); ++v)
        if (index[v]) {
            const int64_t i = static_cast<int64_t>(v) % nx, j = (static_cast<int64_t>(v) / nx) % ny,
                          k = static_cast<int64_t>(v) / (nx * ny);
            ++per[static_cast<std::size_t>(axis == SliceAxis::Axial ? k : (axis == SliceAxis::Coronal ? j : i))];
        }
    why = "the slice with the most ground-truth voxels";
    return std::max_element(per.begin(), per.end()) - per.begin();
}

// Colours of each simplifier's kept labels, agreeing across panels.
std::vector<std::vector<io::Rgb8>> panel_colours(const StudyOutcome &study)
{
    const PanelMaps &p = study.panels;
    std::vector<std::vector<io::Rgb8>> colours(p.labels.size());
    std::set<std::array<uint8_t, 3>> used;
    for (const TruthStructure &t : study.truth)
        used.insert(t.colour);
    uint32_t next = 1;
    const auto fresh = [&] {
        io::Rgb8 c;
        do
            c = io::label_color(next++);
        while (used.count(c) && next < 100000);
        used.insert(c);
        return c;
    };
    for (std::size_t s = 0; s < p.labels.size(); ++s) {
        const std::vector<KeptRecord> &kept = p.kept[s];
        colours[s].assign(kept.size(), io::label_color(0));
        const CutOutcome &cut = study.filters.front().simplifiers[s].cuts[p.cut];
        std::vector<bool> done(kept.size(), false);
        done[0] = true; // the root stays dark grey
        if (cut.scores)
            for (std::size_t t = 0; t < study.truth.size(); ++t) {
                const long r = cut.scores->one_to_one[t].region;
                if (r > 0) {
                    colours[s][static_cast<std::size_t>(r)] = study.truth[t].colour;
                    done[static_cast<std::size_t>(r)] = true;
                }
            }
        for (std::size_t k = 1; k < kept.size(); ++k) {
            if (done[k])
                continue;
            // The same structure as a region of the first simplifier: its colour.
            if (s > 0) {
                const uint32_t k0 = (*p.labels[0])[kept[k].extremum.vertex];
                if (k0 != 0 && (*p.labels[s])[p.kept[0][k0].extremum.vertex] == k) {
                    colours[s][k] = colours[0][k0];
                    continue;
                }
            }
            colours[s][k] = fresh();
        }
    }
    return colours;
}

std::vector<std::string> write_label_panels(const std::filesystem::path &dir, const StudyOutcome &study,
                                            const FigureOptions &options)
{
    const PanelMaps &p = study.panels;
    const Volume &volume = *p.volume;
    std::string why = "slice " + std::to_string(options.slice.value_or(0)) + " as asked";
    const int64_t index = options.slice ? *options.slice : chosen_slice(study, options.axis, why);
    const SliceGrid grid = slice_grid(volume.geometry(), options.axis, index);
    if (index < 0 || index >= grid.count)
        throw std::invalid_argument("--slice " + std::to_string(index) + ": the " + axis_name(options.axis) +
                                    " slices are 0.." + std::to_string(grid.count - 1));
    // Intensities windowed to the slice's 1st..99th percentile.
    std::vector<double> values;
    for (int64_t y = 0; y < grid.height; ++y)
        for (int64_t x = 0; x < grid.width; ++x)
            values.push_back(volume.value(grid.voxel(x, y)));
    std::vector<double> sorted = values;
    std::sort(sorted.begin(), sorted.end());
    const double lo = sorted[sorted.size() / 100], hi = sorted[sorted.size() * 99 / 100];
    const auto grey = [&](std::size_t i) { return std::clamp((values[i] - lo) / (hi > lo ? hi - lo : 1.0), 0.0, 1.0); };

    const auto colours = panel_colours(study);
    std::vector<std::pair<std::string, cv::Mat>> panels;
    cv::Mat intensity(static_cast<int>(grid.height), static_cast<int>(grid.width), CV_8UC3);
    for (int64_t y = 0; y < grid.height; ++y)
        for (int64_t x = 0; x < grid.width; ++x) {
            const auto b = static_cast<uint8_t>(255 * grey(static_cast<std::size_t>(y * grid.width + x)) + 0.5);
            intensity.at<cv::Vec3b>(static_cast<int>(y), static_cast<int>(x)) = {b, b, b};
        }
    panels.emplace_back("intensity", intensity);
    const auto tinted = [&](auto colour_of) {
        cv::Mat m(static_cast<int>(grid.height), static_cast<int>(grid.width), CV_8UC3);
        for (int64_t y = 0; y < grid.height; ++y)
            for (int64_t x = 0; x < grid.width; ++x) {
                const std::size_t i = static_cast<std::size_t>(y * grid.width + x);
                const std::optional<io::Rgb8> c = colour_of(grid.voxel(x, y));
                const double g = 255.0 * grey(i);
                cv::Vec3b px;
                for (int ch = 0; ch < 3; ++ch)
                    px[ch] = static_cast<uint8_t>(c ? 0.6 * (*c)[2 - ch] + 0.4 * g + 0.5 : g * 0.55 + 0.5);
                m.at<cv::Vec3b>(static_cast<int>(y), static_cast<int>(x)) = px;
            }
        return m;
    };
    if (study.truth_labels)
        panels.emplace_back("ground truth", tinted([&](std::size_t v) -> std::optional<io::Rgb8> {
                                const uint32_t t = study.truth_labels->index[v];
                                if (!t)
                                    return std::nullopt;
                                return study.truth[t - 1].colour;
                            }));
    for (std::size_t s = 0; s < p.labels.size(); ++s)
        panels.emplace_back(study.filters.front().simplifiers[s].simplifier.label + " (" +
                                std::to_string(p.kept[s].size()) + ")",
                            tinted([&](std::size_t v) -> std::optional<io::Rgb8> {
                                const uint32_t k = (*p.labels[s])[v];
                                if (k == 0)
                                    return std::nullopt;
                                return colours[s][k];
                            }));

    // Physical aspect: pixels as wide and high as the voxels are.
    const Geometry &g = volume.geometry();
    const double sx = options.axis == SliceAxis::Sagittal ? g.spacing[1] : g.spacing[0];
    const double sy = options.axis == SliceAxis::Axial ? g.spacing[1] : g.spacing[2];
    const double aspect = (grid.height * sy) / (grid.width * sx);
    const double pw = 150, ph = std::clamp(pw * aspect, 40.0, 400.0), gap = 8, top = 52;
    const std::size_t columns = std::min<std::size_t>(panels.size(), 4);
    const std::size_t rows_n = (panels.size() + columns - 1) / columns;
    const double width = gap + columns * (pw + gap), height = top + rows_n * (ph + 18 + gap) + 22;
    const std::string name = std::string("labels-") + axis_name(options.axis) + ".png";
    io::write_figure_with_svg(dir / name, width, height, options.dpi, [&](Canvas &cv) {
        cv.text(gap, 15,
                cv.fitted(std::string(axis_name(options.axis)) + " slice " + std::to_string(index) + " of " +
                              std::to_string(grid.count) + " (" + why + "), filter " +
                              study.filters.front().filter.label + ", " + cut_name(study.grid.cuts[p.cut]),
                          kTitleFont, width - 2 * gap, true),
                kTitleFont, kInk, io::TextAnchor::Start, true);
        cv.text(gap, 28,
                cv.fitted("A kept region matched one-to-one to a truth structure has its colour; the same structure "
                          "in several panels has one colour; grey: the root",
                          kFont - 1, width - 2 * gap),
                kFont - 1, kMuted);
        for (std::size_t i = 0; i < panels.size(); ++i) {
            const double x = gap + static_cast<double>(i % columns) * (pw + gap);
            const double y = top + static_cast<double>(i / columns) * (ph + 18 + gap);
            // Long labels (a simplifier with its parameters) break after ':'.
            const std::string &title = panels[i].first;
            const std::size_t colon = title.find(':');
            if (cv.text_width(title, kFont) <= pw || colon == std::string::npos) {
                cv.text(x, y + 9, cv.fitted(title, kFont, pw), kFont, kInk);
            } else {
                cv.text(x, y, cv.fitted(title.substr(0, colon + 1), kFont, pw), kFont, kInk);
                cv.text(x, y + 9, cv.fitted(title.substr(colon + 1), kFont, pw), kFont, kInk);
            }
            cv.image(panels[i].second, x, y + 13, pw, ph);
        }
        // The truth's legend.
        double lx = gap;
        const double ly = height - 8;
        for (const TruthStructure &t : study.truth) {
            if (lx > width - 60)
                break;
            cv.rectangle(lx, ly - 7, 8, 8, from_rgb8(t.colour));
            const std::string label = cv.fitted(t.name, kFont - 1, 110);
            cv.text(lx + 11, ly, label, kFont - 1, kInk);
            lx += 11 + cv.text_width(label, kFont - 1) + 10;
        }
    });
    std::filesystem::path svg = name;
    return {name, svg.replace_extension(".svg").string()};
}

} // namespace

std::vector<std::string> write_study_figures(const std::filesystem::path &dir, const StudyOutcome &study,
                                             const FigureOptions &options)
{
    std::vector<std::string> files;
    const auto add = [&](const std::string &png) {
        files.push_back(png);
        files.push_back(std::filesystem::path(png).replace_extension(".svg").string());
    };
    for (std::size_t f = 0; f < study.filters.size(); ++f) {
        const std::string name =
            f == 0 ? "priority-lines.png" : "priority-lines-" + file_label(study.filters[f].filter.label) + ".png";
        write_priority_lines(dir / name, study, study.filters[f], options);
        add(name);
    }
    for (const std::string &file : write_label_panels(dir, study, options))
        files.push_back(file);
    if (!study.truth.empty())
        for (std::size_t t = 0; t < study.truth.size(); ++t) {
            const std::string name =
                "dice-" + std::to_string(study.truth[t].label) + "-" + file_label(study.truth[t].name) + ".png";
            write_dice_plot(dir / name, study, t, options);
            add(name);
        }
    return files;
}

} // namespace arbor::cli
