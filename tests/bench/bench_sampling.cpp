// bench_sampling.cpp - what the CPU ray caster's per-sample labels and
// gradients ("sample-labels", "sample-gradients"; issue "Smooth
// structures") do to the picture, in one run:
//
//   1. Anisotropic fidelity.  Analytic fields in mm (a thin spherical
//      shell, two Gaussian blobs of different heights, a thin tilted
//      torus) sampled on anisotropic grids (1 x 1 x 6 mm, 0.5 x 0.5 x 3 mm)
//      go through the product's pipeline (contour tree, ITri, the knee's
//      cut, labels, residue-flow transfer functions, visibility balance).
//      The same grid upsampled trilinearly to isotropic voxels at its finest
//      spacing holds the same continuous field: its voxels' values are what
//      a sample of the anisotropic grid reads there, their labels what such
//      a sample resolves (raycast::Cell and LabelTree, the ray caster's own
//      code).  Both are rendered with the same hierarchy, transfer functions
//      and cameras; a renderer that renders the field and not its voxels
//      draws the same picture from both.  PSNR and SSIM of the anisotropic
//      image against the isotropic one, with the two parameters off
//      (before), each alone, and both on (after); the goal is at
//      least 35 dB after.  Then before and after again unshaded and
//      without boundary emphasis: what is left without gradients.
//   2. Rings and stripes.  The product's default image of the head phantom
//      and two tumour MRs with the parameters off and on, against
//      references: the same scene with them on at 4x the resolution per
//      axis, box-filtered down, at a quarter of the default sample distance
//      and at the default one; and per label the opacity it gave the image.
//
// Images go to --out as PNG.  Prints markdown tables; not a pass/fail test.
#include "image_psnr.hpp"
#include "plugin_fixture.hpp"

#include "block_statistics.hpp"
#include "cell_sample.hpp"
#include "classification.hpp"
#include "label_tree.hpp"
#include "voxel_grid.hpp"

#include "host/param_text.hpp"
#include "host/plugin_instance.hpp"
#include "host/plugin_registry.hpp"
#include "host/rendering.hpp"
#include "io/image_output.hpp"
#include "io/nrrd_writer.hpp"
#include "pipeline/pipeline.hpp"
#include "pipeline/render_scene.hpp"

#include <CLI/CLI.hpp>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <functional>
#include <map>
#include <memory>
#include <string>
#include <vector>

using namespace arbor;
namespace fs = std::filesystem;

namespace {

constexpr const char *kCpuRayCaster = "org.arbor.renderer.cpu-raycast";

using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point t0)
{
    return std::chrono::duration<double>(Clock::now() - t0).count();
}

std::string format(const char *pattern, double value)
{
    char text[64];
    std::snprintf(text, sizeof text, pattern, value);
    return text;
}

void set_param(PluginInstance &plugin, const std::string &name, const std::string &text)
{
    const arbor_param_desc *param = plugin.find_param(name);
    if (!param)
        throw std::runtime_error(std::string(kCpuRayCaster) + " has no parameter " + name);
    plugin.set_param(name, parse_param_value(*param, text).value);
}

// The plugins, and the renderer parameters every ray caster here gets
// besides the two under test (--set NAME=VALUE, to see what a difference
// comes from, e.g. boundary-emphasis=0; none by default).
struct Plugins {
    const PluginRegistry &registry;
    std::map<std::string, std::string> renderer_settings;

    PluginInstance ray_caster() const
    {
        PluginInstance r = registry.create(kCpuRayCaster);
        for (const auto &[name, value] : renderer_settings)
            set_param(r, name, value);
        return r;
    }
};

// The two parameters under test, as a row of the tables calls them.  An
// unlit mode also turns shading and boundary emphasis off, so that only
// classification (values and labels) is left: where the gradients are not
// the difference.
struct Mode {
    const char *name;
    bool labels, gradients;
    bool lit = true;
};
constexpr Mode kBefore{"before", false, false}, kLabelsOnly{"labels", true, false},
    kGradientsOnly{"gradients", false, true}, kAfter{"after", true, true},
    kBeforeUnlit{"before_unlit", false, false, false}, kAfterUnlit{"after_unlit", true, true, false};
// Part 1's columns: the first four lit, then the two unlit.
constexpr std::array<Mode, 6> kModes{kBefore, kLabelsOnly, kGradientsOnly, kAfter, kBeforeUnlit, kAfterUnlit};
constexpr std::size_t kLitModes = 4;

void set_mode(PluginInstance &renderer, const Mode &mode)
{
    set_param(renderer, "sample-labels", mode.labels ? "true" : "false");
    set_param(renderer, "sample-gradients", mode.gradients ? "true" : "false");
}

// Renders in `mode`; an unlit mode's shading and boundary emphasis are put
// back as they were afterwards.
RenderedImage render_in(PluginInstance &renderer, const Mode &mode, const arbor_render_request &request,
                        uint32_t width, uint32_t height)
{
    set_mode(renderer, mode);
    if (mode.lit)
        return render_image(renderer, request, width, height);
    const arbor_param_value shading = renderer.get_param("shading"),
                            emphasis = renderer.get_param("boundary-emphasis");
    set_param(renderer, "shading", "false");
    set_param(renderer, "boundary-emphasis", "0");
    RenderedImage image = render_image(renderer, request, width, height);
    renderer.set_param("shading", shading);
    renderer.set_param("boundary-emphasis", emphasis);
    return image;
}

// ---------------------------------------------------------------------------
// Image measures

// SSIM (Wang, Bovik, Sheikh, Simoncelli 2004) on luma: Rec. 601 weights
// over the display-encoded RGB the renderer writes (composited over the
// background), 11 x 11 Gaussian windows of sigma 1.5 px, K1 = 0.01,
// K2 = 0.03, dynamic range 1; the mean over every window wholly inside the
// image (the reference implementation's "valid" windows).
class Ssim {
public:
    static double of(const RenderedImage &a, const RenderedImage &b)
    {
        const Ssim s(a.width, a.height);
        return s.mean(luma(a), luma(b));
    }

private:
    static constexpr int kRadius = 5;
    static constexpr double kSigma = 1.5, kC1 = 0.01 * 0.01, kC2 = 0.03 * 0.03;

    Ssim(uint32_t width, uint32_t height) : w_(width), h_(height)
    {
        double sum = 0;
        for (int d = -kRadius; d <= kRadius; ++d)
            sum += weight_[static_cast<std::size_t>(d + kRadius)] = std::exp(-d * d / (2 * kSigma * kSigma));
        for (double &x : weight_)
            x /= sum;
    }

    static std::vector<double> luma(const RenderedImage &im)
    {
        std::vector<double> y(std::size_t{im.width} * im.height);
        for (std::size_t p = 0; p < y.size(); ++p)
            y[p] = 0.299 * im.rgba[4 * p] + 0.587 * im.rgba[4 * p + 1] + 0.114 * im.rgba[4 * p + 2];
        return y;
    }

    // The Gaussian-weighted mean of `x` around every valid window centre,
    // (w - 10) x (h - 10), separably.
    std::vector<double> blur(const std::vector<double> &x) const
    {
        const std::size_t w = w_, h = h_, vw = w - 2 * kRadius, vh = h - 2 * kRadius;
        std::vector<double> rows(vw * h), out(vw * vh);
        for (std::size_t y = 0; y < h; ++y)
            for (std::size_t c = 0; c < vw; ++c) {
                double s = 0;
                for (std::size_t d = 0; d < weight_.size(); ++d)
                    s += weight_[d] * x[y * w + c + d];
                rows[y * vw + c] = s;
            }
        for (std::size_t r = 0; r < vh; ++r)
            for (std::size_t c = 0; c < vw; ++c) {
                double s = 0;
                for (std::size_t d = 0; d < weight_.size(); ++d)
                    s += weight_[d] * rows[(r + d) * vw + c];
                out[r * vw + c] = s;
            }
        return out;
    }

    double mean(const std::vector<double> &x, const std::vector<double> &y) const
    {
        std::vector<double> xx(x.size()), yy(x.size()), xy(x.size());
        for (std::size_t p = 0; p < x.size(); ++p) {
            xx[p] = x[p] * x[p];
            yy[p] = y[p] * y[p];
            xy[p] = x[p] * y[p];
        }
        const std::vector<double> mx = blur(x), my = blur(y), sxx = blur(xx), syy = blur(yy), sxy = blur(xy);
        double sum = 0;
        for (std::size_t p = 0; p < mx.size(); ++p) {
            const double vx = sxx[p] - mx[p] * mx[p], vy = syy[p] - my[p] * my[p], cxy = sxy[p] - mx[p] * my[p];
            sum += (2 * mx[p] * my[p] + kC1) * (2 * cxy + kC2) /
                   ((mx[p] * mx[p] + my[p] * my[p] + kC1) * (vx + vy + kC2));
        }
        return sum / static_cast<double>(mx.size());
    }

    uint32_t w_, h_;
    std::array<double, 2 * kRadius + 1> weight_{};
};

// Root mean squared error over RGB on the 8-bit scale (0..255).
double rmse_8bit(const RenderedImage &a, const RenderedImage &b)
{
    return 255.0 * std::sqrt(test::mean_squared_error(a, b));
}

// Each factor x factor block of `fine` averaged into one pixel (RGBA; the
// depth is left out: nothing here reads it).
RenderedImage box_down(const RenderedImage &fine, uint32_t factor)
{
    RenderedImage out;
    out.width = fine.width / factor;
    out.height = fine.height / factor;
    out.rgba.assign(std::size_t{out.width} * out.height * 4, 0.0f);
    const float share = 1.0f / static_cast<float>(factor * factor);
    for (uint32_t y = 0; y < out.height * factor; ++y)
        for (uint32_t x = 0; x < out.width * factor; ++x)
            for (int c = 0; c < 4; ++c)
                out.rgba[(std::size_t{y / factor} * out.width + x / factor) * 4 + c] +=
                    share * fine.rgba[(std::size_t{y} * fine.width + x) * 4 + c];
    return out;
}

// ---------------------------------------------------------------------------
// The product's pipeline on a volume file or the phantom

// The default document (`arbor run`), rendered by the CPU ray caster at
// size x size: the knee's cut, residue-flow functions, balanced, framed.
pipeline::Document default_run(const pipeline::InputChoice &input, uint32_t size)
{
    pipeline::Document d = pipeline::default_document();
    d.input = input;
    d.view.renderer.id = kCpuRayCaster;
    d.view.width = d.view.height = size;
    return d;
}

// What the render stage rendered (balanced functions, framed camera) and
// everything the request points into.
std::unique_ptr<pipeline::PassScene> product_scene(pipeline::Pipeline &p, const pipeline::Document &d)
{
    p.set_document(d);
    p.run<pipeline::Stage::Render>();
    return p.pass_scene();
}

std::string dims_text(const Geometry &g)
{
    char text[96];
    std::snprintf(text, sizeof text, "%lldx%lldx%lld @ %gx%gx%g", static_cast<long long>(g.dims[0]),
                  static_cast<long long>(g.dims[1]), static_cast<long long>(g.dims[2]), g.spacing[0], g.spacing[1],
                  g.spacing[2]);
    return text;
}

// ---------------------------------------------------------------------------
// Part 1: analytic fields on anisotropic grids

// A scalar field over LPS mm, centred on the origin, values 0..1000.
struct Field {
    const char *name;
    std::function<double(double, double, double)> at;
};

double gaussian(double d2, double sigma) { return std::exp(-d2 / (2 * sigma * sigma)); }

// A shell of radius 30 mm, 3.5 mm thick at half height: thinner than a
// 6 mm slice, so the slices cut it into rings near its poles.
double shell(double x, double y, double z)
{
    const double r = std::sqrt(x * x + y * y + z * z) - 30.0;
    return 1000.0 * gaussian(r * r, 1.5);
}

// Two bumps of heights 1000 and 600, apart along all three axes: two
// peaks joined at a saddle.
double blobs(double x, double y, double z)
{
    const auto d2 = [&](double cx, double cy, double cz) {
        return (x - cx) * (x - cx) + (y - cy) * (y - cy) + (z - cz) * (z - cz);
    };
    return 1000.0 * gaussian(d2(-15, -10, -12), 9.0) + 600.0 * gaussian(d2(18, 12, 15), 7.0);
}

// A tube 4.7 mm thick at half height around a circle of radius 28 mm, its
// plane tilted 35 degrees about x: it crosses the slices obliquely.
double torus(double x, double y, double z)
{
    const double tilt = 35.0 * M_PI / 180.0;
    const double v = std::cos(tilt) * y + std::sin(tilt) * z, n = -std::sin(tilt) * y + std::cos(tilt) * z;
    const double ring = std::sqrt(x * x + v * v) - 28.0;
    return 1000.0 * gaussian(ring * ring + n * n, 2.0);
}

// In-plane and through-plane spacing; the grid covers the same box
// (voxel centres from -47.5 to 47.5 mm in x and y, -45 to 45 in z) at each.
struct Sampling {
    const char *name;
    double in_plane, through;
};
constexpr double kHalfWidth = 47.5, kHalfDepth = 45.0;

int64_t samples_over(double half, double spacing)
{
    return static_cast<int64_t>(std::lround(2 * half / spacing)) + 1;
}

Volume sample_field(const Field &field, const Sampling &s)
{
    Geometry g;
    g.dims = {samples_over(kHalfWidth, s.in_plane), samples_over(kHalfWidth, s.in_plane),
              samples_over(kHalfDepth, s.through)};
    g.spacing = {s.in_plane, s.in_plane, s.through};
    g.origin = {-kHalfWidth, -kHalfWidth, -kHalfDepth};
    Volume v = Volume::allocate(ARBOR_VOXEL_F32, g, {}, uint64_t{1} << 32);
    float *out = v.as<float>();
    for (int64_t k = 0; k < g.dims[2]; ++k)
        for (int64_t j = 0; j < g.dims[1]; ++j)
            for (int64_t i = 0; i < g.dims[0]; ++i) {
                const auto p = g.position(static_cast<double>(i), static_cast<double>(j), static_cast<double>(k));
                *out++ = static_cast<float>(field.at(p[0], p[1], p[2]));
            }
    return v;
}

// The anisotropic grid as the ray caster samples it: values and labels
// (with their mixed-cell flags) and how the labels nest.
raycast::VoxelGrid sampled_grid(const Volume &v, const arbor_label_map &map)
{
    if (v.type() != ARBOR_VOXEL_F32)
        throw std::runtime_error("the pipeline's volume is expected as float");
    raycast::VoxelGrid g;
    const auto &d = v.geometry().dims;
    g.nx = d[0], g.ny = d[1], g.nz = d[2];
    const std::size_t n = static_cast<std::size_t>(v.geometry().voxel_count());
    g.value.resize(n);
    std::copy(v.as<float>(), v.as<float>() + n, g.value.data());
    g.max_label = *std::max_element(map.labels, map.labels + n);
    g.label.assign(map.labels, {d[0], d[1], d[2]}, g.max_label);
    g.tree.assign(&map);
    return g;
}

// The grid at isotropic spacing: each voxel's value and label what a
// ray-caster sample of the anisotropic grid at its centre reads and
// resolves (cell_sample.hpp), so both hold one continuous field.
struct Upsampled {
    Volume volume;
    std::vector<uint32_t> labels;
    double resolved_share = 0; // of the voxels, those in mixed cells (labels resolved by value)
    double changed_share = 0;  // of the voxels, those whose label is not their nearest coarse voxel's
};

Upsampled upsample(const Volume &coarse, const arbor_label_map &map)
{
    const raycast::VoxelGrid g = sampled_grid(coarse, map);
    if (g.tree.empty())
        throw std::runtime_error("the label map has no hierarchy (parent, saddle_value)");
    const Geometry &cg = coarse.geometry();
    const double fine = std::min({cg.spacing[0], cg.spacing[1], cg.spacing[2]});
    Geometry fg = cg;
    std::array<double, 3> step{}; // coarse voxels per fine voxel
    for (int a = 0; a < 3; ++a) {
        fg.dims[a] = static_cast<int64_t>(std::lround((cg.dims[a] - 1) * cg.spacing[a] / fine)) + 1;
        fg.spacing[a] = fine;
        step[a] = fine / cg.spacing[a];
    }
    Upsampled out{Volume::allocate(ARBOR_VOXEL_F32, fg, coarse.mapping(), uint64_t{1} << 34), {}};
    out.labels.resize(static_cast<std::size_t>(fg.voxel_count()));
    const raycast::VoxelGrid::Strides corners = g.strides();
    float *value = out.volume.as<float>();
    std::size_t resolved = 0, changed = 0, at = 0;
    for (int64_t k = 0; k < fg.dims[2]; ++k)
        for (int64_t j = 0; j < fg.dims[1]; ++j)
            for (int64_t i = 0; i < fg.dims[0]; ++i, ++at) {
                // Where the ray caster puts a sample's cell, as it does.
                const double px = i * step[0], py = j * step[1], pz = k * step[2];
                const int64_t ci = std::min(static_cast<int64_t>(px), g.nx - 2),
                              cj = std::min(static_cast<int64_t>(py), g.ny - 2),
                              ck = std::min(static_cast<int64_t>(pz), g.nz - 2);
                const std::size_t base = g.index(ci, cj, ck);
                const raycast::Cell cell(g, base, corners, static_cast<float>(px - ci), static_cast<float>(py - cj),
                                         static_cast<float>(pz - ck));
                value[at] = cell.value();
                const uint32_t word = g.label.word(base);
                const bool mixed = word & 1u;
                out.labels[at] = mixed ? raycast::Cell::resolved_label(g, base, corners, value[at]) : word >> 1;
                const std::size_t nearest =
                    g.index(ci + (cell.fx >= 0.5f), cj + (cell.fy >= 0.5f), ck + (cell.fz >= 0.5f));
                resolved += mixed;
                changed += out.labels[at] != g.label[nearest];
            }
    out.resolved_share = static_cast<double>(resolved) / static_cast<double>(at);
    out.changed_share = static_cast<double>(changed) / static_cast<double>(at);
    return out;
}

// A renderer with its own copy of one grid, and the request it renders.
struct GridRenderer {
    PluginInstance renderer;
    arbor_render_request request;

    RenderedImage render(const Mode &mode, const arbor_camera &camera, uint32_t size)
    {
        request.camera = &camera;
        return render_in(renderer, mode, request, size, size);
    }
};

struct View {
    const char *name;
    double azimuth, elevation;
};
// Oblique; from the front (across the thick axis); from above (along it).
// Zoom 1 fits the box's bounding sphere (radius 82 mm); every field lies
// within 45 mm of the centre.
constexpr double kFieldZoom = 1.8;
constexpr std::array<View, 3> kViews{{{"az30 el20", 30, 20}, {"side", 0, 0}, {"top", 0, 90}}};

struct FidelityRow {
    std::string field, sampling, view;
    std::array<double, kModes.size()> psnr{}, ssim{}; // per mode
};

struct FidelityCase {
    std::string field, sampling, grid, labels, denoised;
    double resolved_share = 0, changed_share = 0, seconds = 0;
    std::vector<FidelityRow> rows;
};

std::string png_name(const std::string &field, const std::string &sampling, const View &view, const char *grid,
                     const Mode &mode)
{
    std::string name = field + "_" + sampling + "_" + view.name + "_" + grid + "_" + mode.name + ".png";
    std::replace(name.begin(), name.end(), ' ', '_');
    return name;
}

FidelityCase fidelity(const Plugins &plugins, const Field &field, const Sampling &sampling, uint32_t size,
                      const fs::path &out)
{
    const auto t0 = Clock::now();
    FidelityCase result{field.name, sampling.name, "", "", "", 0, 0, 0, {}};
    const fs::path file = out / "volumes" / (std::string(field.name) + "_" + sampling.name + ".nrrd");
    fs::create_directories(file.parent_path());
    io::NrrdWriteOptions raw;
    raw.gzip = false; // read back at once: no point compressing
    io::write_nrrd(sample_field(field, sampling), file, raw);

    pipeline::Pipeline p(plugins.registry);
    pipeline::InputChoice input;
    input.path = file;
    const auto scene = product_scene(p, default_run(input, size));
    const Volume &coarse = *scene->filtered->volume;
    result.grid = dims_text(coarse.geometry());
    result.labels = std::to_string(scene->functions->branch_count());
    result.denoised = scene->filtered->filters.empty() ? "no" : scene->filtered->source;
    const Upsampled fine = upsample(coarse, scene->scene->map);
    result.resolved_share = fine.resolved_share;
    result.changed_share = fine.changed_share;

    GridRenderer anisotropic{plugins.ray_caster(), scene->scene->request};
    arbor_label_map fine_map = scene->scene->map;
    for (int a = 0; a < 3; ++a)
        fine_map.dims[a] = fine.volume.geometry().dims[a];
    fine_map.labels = fine.labels.data();
    const arbor_volume fine_view = fine.volume.view();
    GridRenderer isotropic{plugins.ray_caster(), scene->scene->request};
    isotropic.request.volume = &fine_view;
    isotropic.request.labels = &fine_map;

    for (const View &view : kViews) {
        Orbit orbit;
        orbit.azimuth = view.azimuth;
        orbit.elevation = view.elevation;
        orbit.zoom = kFieldZoom;
        // One camera for both: the grids share their box of voxel centres.
        const arbor_camera camera = orbit_camera(coarse.geometry(), orbit);
        FidelityRow row{field.name, sampling.name, view.name, {}, {}};
        for (std::size_t m = 0; m < kModes.size(); ++m) {
            const RenderedImage a = anisotropic.render(kModes[m], camera, size);
            const RenderedImage b = isotropic.render(kModes[m], camera, size);
            row.psnr[m] = test::psnr(a, b);
            row.ssim[m] = Ssim::of(a, b);
            io::write_image(out / png_name(field.name, sampling.name, view, "aniso", kModes[m]), a);
            io::write_image(out / png_name(field.name, sampling.name, view, "iso", kModes[m]), b);
        }
        result.rows.push_back(row);
    }
    result.seconds = seconds_since(t0);
    return result;
}

// The PSNR and SSIM columns of modes [first, last).
void print_fidelity_modes(const std::vector<FidelityCase> &cases, std::size_t first, std::size_t last)
{
    std::string header = "| field | sampling | view |", rule = "|---|---|---|";
    for (const char *measure : {"PSNR", "SSIM"})
        for (std::size_t m = first; m < last; ++m) {
            header += std::string(" ") + measure + " " + kModes[m].name + " |";
            rule += "---:|";
        }
    std::printf("%s\n%s\n", header.c_str(), rule.c_str());
    for (const FidelityCase &c : cases)
        for (const FidelityRow &r : c.rows) {
            std::printf("| %s | %s | %s |", r.field.c_str(), r.sampling.c_str(), r.view.c_str());
            for (std::size_t m = first; m < last; ++m)
                std::printf(" %.2f |", r.psnr[m]);
            for (std::size_t m = first; m < last; ++m)
                std::printf(" %.4f |", r.ssim[m]);
            std::printf("\n");
        }
}

void print_fidelity(const std::vector<FidelityCase> &cases, uint32_t size)
{
    std::printf("## Anisotropic fidelity: PSNR (dB) and SSIM of the anisotropic grid's image against its "
                "isotropic trilinear upsampling's, %ux%u, CPU ray caster\n\n",
                size, size);
    std::printf("| field | sampling | grid | labels | denoised | in mixed cells | relabelled | s |\n"
                "|---|---|---|---:|---|---:|---:|---:|\n");
    for (const FidelityCase &c : cases)
        std::printf("| %s | %s | %s | %s | %s | %.1f%% | %.2f%% | %.0f |\n", c.field.c_str(), c.sampling.c_str(),
                    c.grid.c_str(), c.labels.c_str(), c.denoised.c_str(), 100 * c.resolved_share,
                    100 * c.changed_share, c.seconds);
    std::printf("\n");
    print_fidelity_modes(cases, 0, kLitModes);
    std::printf("\nlabels / gradients: only \"sample-labels\" / only \"sample-gradients\" on; before: both off; "
                "after: both on (the default).  In mixed cells: upsampled voxels whose anisotropic cell has "
                "corners of different labels; relabelled: those whose resolved label is not their nearest "
                "anisotropic voxel's.\n\n");
    std::printf("### The same, unshaded and without boundary emphasis: classification alone, no gradients\n\n");
    print_fidelity_modes(cases, kLitModes, kModes.size());
    std::printf("\n");
}
// ---------------------------------------------------------------------------
// Part 2: the product's default image against a supersampled reference

// A reference: the default scene with both parameters on, rendered at
// kReferenceFactor times the resolution per axis and box-filtered down, at
// a sample distance.  The brief's reference takes a quarter of the default
// step; the second keeps the default step, so that it differs from "after"
// only in the pixels (what a difference the step size makes by itself,
// the empty-space skipping's threshold included, is then visible apart).
struct Reference {
    const char *name;
    const char *sample_distance;
};
constexpr uint32_t kReferenceFactor = 4;
constexpr std::array<Reference, 2> kReferences{{{"4x, sample distance 0.125", "0.125"},
                                                {"4x, sample distance 0.5", "0.5"}}};

// Per label, the opacity its samples gave the picture (T * alpha summed over
// rays) per pixel of the frame: which structure a difference is in.
std::vector<double> visibility_per_pixel(const RenderedImage &image)
{
    std::vector<double> v = image.label_visibility;
    for (double &x : v)
        x /= static_cast<double>(image.width) * image.height;
    return v;
}

struct Rendered {
    RenderedImage image;
    std::vector<double> visibility;
    double seconds = 0;
};

Rendered timed_render(PluginInstance &renderer, const Mode &mode, const arbor_render_request &request,
                      uint32_t size, uint32_t factor = 1)
{
    const auto t0 = Clock::now();
    const RenderedImage full = render_in(renderer, mode, request, size * factor, size * factor);
    Rendered r{factor == 1 ? full : box_down(full, factor), visibility_per_pixel(full), 0};
    r.seconds = seconds_since(t0);
    return r;
}

// The share of 8^3 blocks the ray caster's empty-space skipping leaves
// out as transparent at each sample distance, by its own code (Occupancy
// over BlockStatistics and the step's ClassTable): its threshold is an
// opacity per step, so a finer step may skip more of a faint structure.
std::vector<double> skipped_shares(const arbor_render_request &r, const std::array<Reference, 2> &references)
{
    const sdk::Task no_task(nullptr);
    raycast::VoxelGridCache cache;
    const raycast::VoxelGrid &g = cache.update(*r.volume, 0, r.labels, 0, no_task);
    raycast::BlockStatistics blocks;
    blocks.build(g, no_task);
    std::vector<double> out;
    for (const Reference &ref : references) {
        raycast::ClassTable table;
        table.build(*r.transfer_functions, std::stod(ref.sample_distance) * g.min_spacing);
        raycast::Occupancy occupancy;
        occupancy.build(blocks, table, {g.nx, g.ny, g.nz}, g.min_spacing);
        const std::vector<uint8_t> &empty = occupancy.flags();
        out.push_back(static_cast<double>(std::count(empty.begin(), empty.end(), 1)) /
                      static_cast<double>(empty.size()));
    }
    return out;
}

struct RingsCase {
    std::string input, grid, labels, filters;
    std::vector<double> skipped; // per reference: the share of blocks skipped as empty at its sample distance
    double pipeline_psnr = 0;          // the render stage's own image against "after": the same scene?
    Rendered before, after;
    std::vector<Rendered> references;  // as kReferences
};

RingsCase rings(const Plugins &plugins, const std::string &name, const pipeline::InputChoice &input, uint32_t size,
                const fs::path &out)
{
    pipeline::Pipeline p(plugins.registry);
    const auto scene = product_scene(p, default_run(input, size));
    RingsCase c;
    c.input = name;
    c.grid = dims_text(scene->filtered->volume->geometry());
    c.labels = std::to_string(scene->functions->branch_count());
    c.filters = scene->filtered->filters.empty() ? "none" : scene->filtered->source.substr(
                                                                scene->filtered->source.find('|') + 2);

    PluginInstance renderer = plugins.ray_caster();
    const arbor_render_request &request = scene->scene->request;
    c.before = timed_render(renderer, kBefore, request, size); // also builds the renderer's grid
    c.after = timed_render(renderer, kAfter, request, size);
    c.pipeline_psnr = test::psnr(p.latest<pipeline::Stage::Render>()->image, c.after.image);
    const arbor_param_value distance = renderer.get_param("sample-distance");
    for (const Reference &r : kReferences) {
        set_param(renderer, "sample-distance", r.sample_distance);
        c.references.push_back(timed_render(renderer, kAfter, request, size, kReferenceFactor));
    }
    renderer.set_param("sample-distance", distance);
    c.skipped = skipped_shares(request, kReferences);
    io::write_image(out / (name + "_before.png"), c.before.image);
    io::write_image(out / (name + "_after.png"), c.after.image);
    for (std::size_t r = 0; r < kReferences.size(); ++r)
        io::write_image(out / (name + "_reference_" + kReferences[r].sample_distance + ".png"),
                        c.references[r].image);
    return c;
}

// The markdown rule of `columns` right-aligned columns.
std::string right_aligned(std::size_t columns)
{
    std::string rule;
    for (std::size_t c = 0; c < columns; ++c)
        rule += "---:|";
    return rule;
}

void print_rings(const std::vector<RingsCase> &cases, uint32_t size)
{
    std::printf("## Rings and stripes: RMSE (0-255) and PSNR (dB) of the default image (%ux%u, default camera, "
                "CPU ray caster) against references with both parameters on, rendered at %ux the resolution per "
                "axis and box-filtered down\n\n",
                size, size, kReferenceFactor);
    std::printf("| input | reference | RMSE before | RMSE after | PSNR before | PSNR after |\n"
                "|---|---|---:|---:|---:|---:|\n");
    for (const RingsCase &c : cases)
        for (std::size_t r = 0; r < kReferences.size(); ++r) {
            const RenderedImage &ref = c.references[r].image;
            std::printf("| %s | %s | %.2f | %.2f | %.2f | %.2f |\n", c.input.c_str(), kReferences[r].name,
                        rmse_8bit(c.before.image, ref), rmse_8bit(c.after.image, ref), test::psnr(c.before.image, ref),
                        test::psnr(c.after.image, ref));
        }
    std::printf("\nbefore: \"sample-labels\" and \"sample-gradients\" off; after: on (the default).\n\n");
    std::printf("| input | grid (filtered) | filter | labels | render stage = after | before s | after s |");
    for (const Reference &r : kReferences)
        std::printf(" %s s |", r.name);
    for (const Reference &r : kReferences)
        std::printf(" blocks skipped at %s |", r.sample_distance);
    std::printf("\n|---|---|---|---:|---|---:|---:|%s\n", right_aligned(2 * kReferences.size()).c_str());
    for (const RingsCase &c : cases) {
        std::printf("| %s | %s | %s | %s | %s | %.2f | %.2f |", c.input.c_str(), c.grid.c_str(), c.filters.c_str(),
                    c.labels.c_str(),
                    std::isinf(c.pipeline_psnr) ? "identical" : format("%.1f dB", c.pipeline_psnr).c_str(),
                    c.before.seconds, c.after.seconds);
        for (const Rendered &r : c.references)
            std::printf(" %.1f |", r.seconds);
        for (double share : c.skipped)
            std::printf(" %.1f%% |", 100 * share);
        std::printf("\n");
    }
    std::printf("\nrender stage = after: the pipeline's own image against this run's \"after\" (the same scene and "
                "parameters).  before s includes building the renderer's grid (values, gradients, labels).  Blocks "
                "skipped: the share of 8^3 blocks the ray caster's empty-space skipping leaves out at that sample "
                "distance (its Occupancy, rebuilt here).  Times on a shared 2-core machine.\n\n");
    std::printf("### Visibility per label: the opacity each label's samples gave the picture, per pixel\n\n"
                "| input | label | before | after |");
    for (const Reference &r : kReferences)
        std::printf(" %s |", r.name);
    std::printf("\n|---|---:|---:|---:|%s\n", right_aligned(kReferences.size()).c_str());
    for (const RingsCase &c : cases)
        for (std::size_t l = 0; l < c.after.visibility.size(); ++l) {
            std::printf("| %s | %zu | %.4f | %.4f |", c.input.c_str(), l, c.before.visibility[l],
                        c.after.visibility[l]);
            for (const Rendered &r : c.references)
                std::printf(" %.4f |", l < r.visibility.size() ? r.visibility[l] : NAN);
            std::printf("\n");
        }
    std::printf("\n");
}

std::vector<std::pair<std::string, pipeline::InputChoice>> rings_inputs()
{
    const fs::path data = test::shared_dir() / "data";
    pipeline::InputChoice phantom, pyradiomics, dicom;
    phantom.phantom = pipeline::PhantomInput{}; // `arbor run --phantom head`
    pyradiomics.path = data / "mr_brain_tumor_pyradiomics" / "brain1_image.nrrd";
    dicom.path = data / "dicom_mr_brain_vs_tumor";
    return {{"phantom_head", phantom}, {"mr_brain_tumor_pyradiomics", pyradiomics},
            {"dicom_mr_brain_vs_tumor", dicom}};
}

// "NAME=VALUE" texts as a map; throws CLI::ValidationError without '='.
std::map<std::string, std::string> renderer_settings(const std::vector<std::string> &texts)
{
    std::map<std::string, std::string> out;
    for (const std::string &t : texts) {
        const std::size_t eq = t.find('=');
        if (eq == std::string::npos || eq == 0)
            throw CLI::ValidationError("--set", "'" + t + "' is not NAME=VALUE");
        out[t.substr(0, eq)] = t.substr(eq + 1);
    }
    return out;
}

bool selected(const std::vector<std::string> &only, const std::string &name)
{
    return only.empty() || std::any_of(only.begin(), only.end(),
                                       [&](const std::string &o) { return name.find(o) != std::string::npos; });
}

} // namespace

int main(int argc, char **argv)
{
    CLI::App app{"Per-sample labels and gradients of the CPU ray caster: anisotropic fidelity, rings and stripes"};
    uint32_t fidelity_size = 384, rings_size = 512;
    fs::path out = "/tmp/bench_sampling";
    std::vector<std::string> only;
    std::vector<std::string> settings;
    bool skip_fidelity = false, skip_rings = false;
    app.add_option("--fidelity-size", fidelity_size, "Image size of part 1 (square)")->check(CLI::Range(16, 4096));
    app.add_option("--rings-size", rings_size, "Image size of part 2 (square; the reference is 4x)")
        ->check(CLI::Range(16, 2048));
    app.add_option("--out", out, "Folder for the images (PNG) and the fields' NRRD files");
    app.add_option("--only", only, "Only fields, samplings and inputs whose name contains this (repeatable)");
    app.add_option("--set", settings, "A renderer parameter for every ray caster here, NAME=VALUE (repeatable)");
    app.add_flag("--no-fidelity", skip_fidelity, "Skip part 1");
    app.add_flag("--no-rings", skip_rings, "Skip part 2");
    CLI11_PARSE(app, argc, argv);
    std::map<std::string, std::string> renderer_params;
    try {
        renderer_params = renderer_settings(settings);
    } catch (const CLI::Error &e) {
        return app.exit(e);
    }
    fs::create_directories(out);

    PluginRegistry registry;
    registry.load_directories({test::plugin_dir()});
    const Plugins plugins{registry, renderer_params};
    std::printf("# arbor_bench_sampling: the CPU ray caster's \"sample-labels\" and \"sample-gradients\", off "
                "(before) and on (after); images in %s\n",
                out.c_str());
    for (const auto &[name, value] : plugins.renderer_settings)
        std::printf("Every ray caster here also has %s = %s.\n", name.c_str(), value.c_str());
    std::printf("\n");
    const auto t0 = Clock::now();
    if (!skip_fidelity) {
        const std::array<Field, 3> fields{{{"shell", shell}, {"blobs", blobs}, {"torus", torus}}};
        const std::array<Sampling, 2> samplings{{{"1x1x6", 1.0, 6.0}, {"0.5x0.5x3", 0.5, 3.0}}};
        std::vector<FidelityCase> cases;
        for (const Sampling &s : samplings)
            for (const Field &f : fields)
                if (selected(only, f.name) || selected(only, s.name))
                    cases.push_back(fidelity(plugins, f, s, fidelity_size, out));
        print_fidelity(cases, fidelity_size);
        std::fflush(stdout); // before the pipeline's log lines on stderr
    }
    if (!skip_rings) {
        std::vector<RingsCase> rows;
        for (const auto &[name, input] : rings_inputs())
            if (selected(only, name)) {
                try {
                    rows.push_back(rings(plugins, name, input, rings_size, out));
                } catch (const std::exception &e) {
                    std::printf("%s skipped: %s\n", name.c_str(), e.what());
                }
            }
        print_rings(rows, rings_size);
    }
    std::printf("Total %.0f s.\n", seconds_since(t0));
    return 0;
}
