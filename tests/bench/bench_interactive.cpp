// bench_interactive.cpp - the interactive path (issue 14): what a dragged
// slider or an orbiting mouse costs with the CPU ray caster's
// arbor.renderer/2 passes, against VTK 9.1's vtkFixedPointVolumeRayCastMapper
// in its own interactive mode (automatic image sample distance at a desired
// update rate), in the same run.
//
// On the shared CT head DICOM (512x512x108) and the same CT resampled to
// three times as many slices (512x512x322, built here from it), 20 branches
// kept (balancing off: it runs once a drag ends), 512x512:
//   1. flow-rate step -> first coarse image: regenerate the transfer
//      functions through the pipeline, then a COARSE pass, ms;
//   2. coarse frames per second while orbiting (3 degrees per frame);
//   3. the refinement: the FULL pass that replaces the coarse image, ms;
//   4. PSNR of the coarse image against the full one;
//   5. one global transfer function for both renderers: Arbor's coarse fps
//      and VTK's interactive fps (desired update rate 20/s) while orbiting,
//      each one's PSNR against its own full-quality image (squared errors
//      pooled over every 4th frame of the orbit: both adapt their sampling
//      to their own timings, so a single frame's PSNR moves by 2-3 dB).
// Needs X for VTK: xvfb-run -a build/bin/arbor_bench_interactive.  Prints a
// table; not a pass/fail test.
#include "global_ramp.hpp"
#include "image_psnr.hpp"
#include "plugin_fixture.hpp"
#include "tall_ct.hpp"

#include "core/volume_statistics.hpp"
#include "host/param_text.hpp"
#include "host/plugin_instance.hpp"
#include "host/plugin_registry.hpp"
#include "host/rendering.hpp"
#include "pipeline/pipeline.hpp"
#include "pipeline/render_scene.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <string>
#include <utility>
#include <vector>

using namespace arbor;
namespace fs = std::filesystem;

namespace {

constexpr uint32_t kSize = 512;
// The update rate both renderers are asked for in the comparison (item 5):
// VTK's desired update rate, the CPU ray caster's coarse rate.
constexpr const char *kDesiredRate = "20";

void set(PluginInstance &plugin, const std::string &param, const std::string &text)
{
    plugin.set_param(param, parse_param_value(*plugin.find_param(param), text).value);
}
using Clock = std::chrono::steady_clock;

double ms_since(Clock::time_point t0)
{
    return std::chrono::duration<double, std::milli>(Clock::now() - t0).count();
}

double median(std::vector<double> v)
{
    std::sort(v.begin(), v.end());
    return v[v.size() / 2];
}

struct Orbiting {
    double fps = 0, psnr = 0;
    // Against the refined image (the full one and kRefinements supersample
    // passes, what the workstation shows once idle), and the full image's
    // own distance from it; NaN for a renderer without supersampling.
    double psnr_refined = NAN, full_floor = NAN;
};

constexpr uint32_t kRefinements = 4;

// Frames per second of `pass` while the camera turns 3 degrees a frame, and
// the PSNR of every kPsnrEvery-th frame against the FULL pass from the same
// camera, their squared errors pooled: an adaptive renderer's quality moves
// from frame to frame with its own timings, so one frame says little.
constexpr int kPsnrEvery = 4;

Orbiting orbit(PluginInstance &renderer, arbor_render_request r, const Geometry &g, arbor_render_pass pass,
               uint64_t tf_revision, int frames)
{
    Orbit o;
    o.elevation = 20;
    arbor_camera camera{};
    r.camera = &camera;
    const auto frame = [&](int f, arbor_render_pass p) {
        o.azimuth = 30 + 3 * f;
        camera = orbit_camera(g, o);
        return render_image(renderer, r, kSize, kSize, nullptr, {}, {p, 0, tf_revision});
    };
    for (int f = -5; f < 0; ++f) // warm-up: caches, and VTK's adaptation to the update rate
        frame(f, pass);
    const auto t0 = Clock::now();
    std::vector<std::pair<int, RenderedImage>> kept; // (frame, image), the last one included
    for (int f = 0; f < frames; ++f) {
        RenderedImage image = frame(f, pass);
        if ((frames - 1 - f) % kPsnrEvery == 0)
            kept.emplace_back(f, std::move(image));
    }
    Orbiting out;
    out.fps = frames / (ms_since(t0) / 1000.0);
    double mse = 0;
    RenderedImage full; // the last frame's, kept for the refinement below
    for (const auto &[f, image] : kept) {
        full = frame(f, ARBOR_RENDER_PASS_FULL);
        mse += test::mean_squared_error(image, full) / static_cast<double>(kept.size());
    }
    out.psnr = test::psnr_of_mse(mse);
    const RenderedImage &last = kept.back().second;
    if (renders_passes(renderer)) {
        RenderedImage refined = full;
        try {
            for (uint32_t i = 1; i <= kRefinements; ++i)
                render_region(renderer, r, refined, {}, {ARBOR_RENDER_PASS_SUPERSAMPLE, i, tf_revision});
            out.psnr_refined = test::psnr(last, refined);
            out.full_floor = test::psnr(full, refined);
        } catch (const PluginError &e) { // a renderer without a supersample pass; anything else is a failure
            if (e.status() != ARBOR_ERROR_UNSUPPORTED)
                throw;
        }
    }
    return out;
}

// Pre-integration (Engel, Kraus and Ertl 2001) integrates each step's
// segment of the transfer function as a finer step would.  So what the
// coarse image gains when its step is the full pass's (coarse pass at a
// fixed 3 x 3 pixels a ray, against the FULL image) bounds what
// pre-integration at the coarse step could gain, and its time what it may
// cost.
struct StepBound {
    double psnr_coarse_step = 0, psnr_full_step = 0, ms_coarse_step = 0, ms_full_step = 0;
};

StepBound coarse_step_bound(PluginRegistry &registry, const arbor_render_request &r, uint64_t revision)
{
    StepBound b;
    PluginInstance full = registry.create("org.arbor.renderer.cpu-raycast");
    const RenderedImage reference = render_image(full, r, kSize, kSize, nullptr, {}, {ARBOR_RENDER_PASS_FULL, 0, revision});
    for (const bool finer : {false, true}) {
        PluginInstance cpu = registry.create("org.arbor.renderer.cpu-raycast");
        set(cpu, "coarse-pixels", "3");
        if (finer) // its coarse step (twice the sample distance) is the default full step
            set(cpu, "sample-distance", "0.25");
        RenderedImage coarse = render_image(cpu, r, kSize, kSize, nullptr, {}, {ARBOR_RENDER_PASS_COARSE, 0, revision});
        std::vector<double> ms;
        for (int i = 0; i < 3; ++i) {
            const auto t0 = Clock::now();
            coarse = render_image(cpu, r, kSize, kSize, nullptr, {}, {ARBOR_RENDER_PASS_COARSE, 0, revision});
            ms.push_back(ms_since(t0));
        }
        (finer ? b.psnr_full_step : b.psnr_coarse_step) = test::psnr(coarse, reference);
        (finer ? b.ms_full_step : b.ms_coarse_step) = median(ms);
    }
    return b;
}

} // namespace

int main()
{
    const char *display = std::getenv("DISPLAY");
    if (!display || !*display) {
        std::fprintf(stderr, "arbor_bench_interactive: VTK needs an X display; run under xvfb-run -a\n");
        return 2;
    }
    PluginRegistry registry;
    registry.load_directories({test::plugin_dir()});
    const fs::path head = test::shared_data("dicom_ct_head_0051");
    const fs::path scratch = fs::temp_directory_path() / "arbor-bench-interactive";
    fs::create_directories(scratch);
    const fs::path tall = bench::tall_ct(head, 3, scratch / "ct_head_x3.nrrd");

    std::printf("arbor_bench_interactive: %ux%u, 2 cores here, CPU ray caster's arbor.renderer/2 passes; "
                "VTK's vtkFixedPointVolumeRayCastMapper; both asked for %s frames/s in the comparison\n\n",
                kSize, kSize, kDesiredRate);
    std::printf("%-24s %6s | %10s %10s %9s %9s %8s | %10s %9s %9s %9s %7s\n", "volume", "labels", "Q->coarse",
                "coarse/s", "full ms", "1st ms", "PSNR", "arbor c/s", "PSNR", "vtk i/s", "PSNR", "ratio");
    std::vector<std::string> gl_rows; // the OpenGL ray caster, printed after the main table
    for (const fs::path &input : {head, tall}) try {
        pipeline::Pipeline p(registry);
        pipeline::Document d = pipeline::default_document();
        d.input.path = input;
        d.cut.keep = 20;
        d.appearance.balance_visibility = false;
        d.view.width = d.view.height = kSize;
        p.set_document(d);
        const auto filtered = p.run<pipeline::Stage::Filter>();
        const auto labelled = p.run<pipeline::Stage::Labels>();
        auto functions = p.run<pipeline::Stage::TransferFunctions>();
        const Volume &volume = *filtered->volume;
        const arbor_volume view = volume.view();
        Orbit o;
        o.azimuth = 30;
        o.elevation = 20;
        arbor_camera camera = orbit_camera(volume.geometry(), o);
        PluginInstance cpu = registry.create("org.arbor.renderer.cpu-raycast");
        // The request as the render stage makes it.
        pipeline::RenderScene scene(*filtered, *labelled, functions->functions->branch_count(), d.view.background);
        arbor_render_request r = scene.request;
        r.transfer_functions = &functions->functions->record();
        r.camera = &camera;
        uint64_t revision = 1;
        // The first frame on a new volume: the grid, gradients, block
        // statistics (once per volume and labels).
        auto t0 = Clock::now();
        render_image(cpu, r, kSize, kSize, nullptr, {}, {ARBOR_RENDER_PASS_COARSE, 0, revision});
        const double first = ms_since(t0);
        // 1. Flow-rate steps: the pipeline regenerates the functions, the
        // renderer shows the coarse pass.
        std::vector<double> step_ms;
        for (int s = 1; s <= 6; ++s) {
            pipeline::Appearance a = p.document().appearance;
            a.generator.params["flow-rate"] = std::to_string(60 + 15 * s);
            t0 = Clock::now();
            p.set_appearance(a);
            functions = p.run<pipeline::Stage::TransferFunctions>();
            r.transfer_functions = &functions->functions->record();
            render_image(cpu, r, kSize, kSize, nullptr, {}, {ARBOR_RENDER_PASS_COARSE, 0, ++revision});
            step_ms.push_back(ms_since(t0));
        }
        // 2-4. Orbiting coarse; the refinement (a FULL pass) and its PSNR.
        const Orbiting coarse = orbit(cpu, r, volume.geometry(), ARBOR_RENDER_PASS_COARSE, revision, 20);
        std::vector<double> full_ms;
        for (int i = 0; i < 3; ++i) {
            t0 = Clock::now();
            render_image(cpu, r, kSize, kSize, nullptr, {}, {ARBOR_RENDER_PASS_FULL, 0, revision});
            full_ms.push_back(ms_since(t0));
        }
        // 5. One global function for both renderers.
        const VolumeStatistics stats = compute_statistics(volume);
        TransferFunctions global(1, 256, 4.0 * std::min({volume.geometry().spacing[0], volume.geometry().spacing[1],
                                                        volume.geometry().spacing[2]}));
        test::global_ramp(global, stats.min, stats.max);
        const arbor_render_request g = test::global_request(view, global, camera);
        PluginInstance cpu_global = registry.create("org.arbor.renderer.cpu-raycast");
        PluginInstance vtk = registry.create("org.arbor.renderer.vtk-reference");
        set(cpu_global, "coarse-rate", kDesiredRate);
        set(vtk, "interactive-update-rate", kDesiredRate);
        const Orbiting arbor_global = orbit(cpu_global, g, volume.geometry(), ARBOR_RENDER_PASS_COARSE, 1, 20);
        const Orbiting vtk_global = orbit(vtk, g, volume.geometry(), ARBOR_RENDER_PASS_COARSE, 1, 20);
        char dims[32];
        std::snprintf(dims, sizeof dims, "%lldx%lldx%lld", static_cast<long long>(volume.geometry().dims[0]),
                      static_cast<long long>(volume.geometry().dims[1]),
                      static_cast<long long>(volume.geometry().dims[2]));
        std::printf("%-24s %6u | %10.1f %10.1f %9.0f %9.0f %8.1f | %10.1f %9.1f %9.1f %9.1f %7.2f\n", dims,
                    functions->functions->branch_count(), median(step_ms), coarse.fps, median(full_ms), first,
                    coarse.psnr, arbor_global.fps, arbor_global.psnr, vtk_global.fps, vtk_global.psnr,
                    arbor_global.fps / vtk_global.fps);
        std::printf("%-24s %6s   against the refined image (full + %u supersamples): coarse %.1f dB (full %.1f dB); "
                    "global: Arbor coarse %.1f dB (full %.1f dB)\n",
                    "", "", kRefinements, coarse.psnr_refined, coarse.full_floor, arbor_global.psnr_refined,
                    arbor_global.full_floor);
        const StepBound bound = coarse_step_bound(registry, r, revision);
        std::printf("%-24s %6s   coarse at 3x3 pixels a ray: its own step %.1f dB (%.0f ms), the full pass's step "
                    "%.1f dB (%.0f ms): pre-integration could gain at most %.1f dB\n",
                    "", "", bound.psnr_coarse_step, bound.ms_coarse_step, bound.psnr_full_step, bound.ms_full_step,
                    bound.psnr_full_step - bound.psnr_coarse_step);
        // The OpenGL ray caster on the same request: its first frame (the
        // uploads), the full pass, the coarse orbit, and how close its full
        // image is to the CPU ray caster's.
        try {
            PluginInstance gl = registry.create("org.arbor.renderer.gl-raycast");
            t0 = Clock::now();
            render_image(gl, r, kSize, kSize, nullptr, {}, {ARBOR_RENDER_PASS_COARSE, 0, revision});
            const double gl_first = ms_since(t0);
            std::vector<double> gl_full_ms;
            RenderedImage gl_full;
            for (int i = 0; i < 3; ++i) {
                t0 = Clock::now();
                gl_full = render_image(gl, r, kSize, kSize, nullptr, {}, {ARBOR_RENDER_PASS_FULL, 0, revision});
                gl_full_ms.push_back(ms_since(t0));
            }
            const RenderedImage cpu_full = render_image(cpu, r, kSize, kSize, nullptr, {}, {ARBOR_RENDER_PASS_FULL, 0, revision});
            const Orbiting gl_coarse = orbit(gl, r, volume.geometry(), ARBOR_RENDER_PASS_COARSE, revision, 10);
            char row[256];
            std::snprintf(row, sizeof row, "%-24s | %9.0f %9.0f %10.1f %8.1f | %12.1f  %s", dims, gl_first,
                          median(gl_full_ms), gl_coarse.fps, gl_coarse.psnr, test::psnr(gl_full, cpu_full),
                          render_device(gl).name.c_str());
            gl_rows.push_back(row);
        } catch (const std::exception &e) {
            gl_rows.push_back(std::string(dims) + " OpenGL ray caster skipped: " + e.what());
        }
    } catch (const std::exception &e) {
        std::printf("%-24s skipped: %s\n", input.filename().c_str(), e.what());
    }
    std::printf("\nQ->coarse: median of 6 flow-rate steps, from the new parameter to the coarse image (ms); "
                "coarse/s: coarse frames per second orbiting; full ms: the refining FULL pass; 1st ms: the first "
                "coarse frame on a new volume (grid, gradients, block statistics); PSNR (dB) of the coarse image "
                "against the full one.  Global function: frames per second orbiting and PSNR against each "
                "renderer's own full image; ratio = Arbor / VTK.\n");
    std::printf("\nOpenGL ray caster, same requests\n%-24s | %9s %9s %10s %8s | %12s  %s\n", "volume", "1st ms",
                "full ms", "coarse/s", "PSNR", "PSNR vs CPU", "device");
    for (const std::string &row : gl_rows)
        std::printf("%s\n", row.c_str());
    std::printf("1st ms: the first frame (textures uploaded); PSNR vs CPU: its full image against the CPU ray "
                "caster's (dB).\n");
    return 0;
}
