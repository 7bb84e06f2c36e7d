// bench_render.cpp - frames per second of Arbor's CPU ray caster against
// VTK 9.1's vtkFixedPointVolumeRayCastMapper (the VTK reference renderer
// plugin) on the shared volumes and on two scans of clinical size (the CT
// head DICOM, 512x512x108, and the same CT with three times the slices,
// 512x512x322): 512x512, the same camera, sample distance (0.5 voxel),
// global transfer function and shading on or off, measured in the same run.
// Shaded, Arbor's frame is also timed with each voxel's gradient instead of
// the sample's (what a sample's gradient costs) and with local ambient
// occlusion at full strength (what it costs).  Needs X for VTK: run under
// xvfb-run.  Prints a table; not a pass/fail test.
#include "global_ramp.hpp"
#include "plugin_fixture.hpp"
#include "tall_ct.hpp"

#include "host/param_text.hpp"
#include "host/rendering.hpp"
#include "host/tf_generation.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <string>
#include <vector>

using namespace arbor;

namespace {

void set(PluginInstance &plugin, const std::string &param, const std::string &text)
{
    plugin.set_param(param, parse_param_value(*plugin.find_param(param), text).value);
}

double frames_per_second(PluginInstance &renderer, const arbor_render_request &r, int frames)
{
    render_image(renderer, r, 512, 512); // caches built outside the clock
    const auto t0 = std::chrono::steady_clock::now();
    for (int f = 0; f < frames; ++f)
        render_image(renderer, r, 512, 512);
    return frames / std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

// Arbor's CPU ray caster as the comparison sets it up, `settings` on top.
// NaN when the renderer has no such settings (an older build).
double arbor_fps(const arbor_render_request &r, bool shading,
                 const std::vector<std::pair<std::string, std::string>> &settings, int frames)
{
    PluginInstance cpu = test::built_plugins().create("org.arbor.renderer.cpu-raycast");
    test::set_shading(cpu, shading);
    test::plain_opacity(cpu);
    for (const auto &[param, value] : settings) {
        if (!cpu.find_param(param))
            return NAN;
        set(cpu, param, value);
    }
    return frames_per_second(cpu, r, frames);
}

double vtk_fps(const arbor_render_request &r, bool shading, int frames)
{
    PluginInstance vtk = test::built_plugins().create("org.arbor.renderer.vtk-reference");
    test::set_shading(vtk, shading);
    return frames_per_second(vtk, r, frames);
}

} // namespace

int main(int argc, char **argv)
{
    // Arguments: substrings of the volumes to time (all when none; "tall"
    // for the resampled CT).
    const std::vector<std::string> only(argv + 1, argv + argc);
    const auto wanted = [&](const std::string &name) {
        return only.empty() || std::any_of(only.begin(), only.end(),
                                           [&](const std::string &o) { return name.find(o) != std::string::npos; });
    };
    const char *display = std::getenv("DISPLAY");
    if (!display || !*display) {
        std::fprintf(stderr, "arbor_bench_render: VTK needs an X display; run under xvfb-run -a\n");
        return 2;
    }
    const std::filesystem::path scratch = std::filesystem::temp_directory_path() / "arbor-bench-render";
    std::filesystem::create_directories(scratch);
    const std::filesystem::path head = test::shared_data("dicom_ct_head_0051");
    std::vector<std::filesystem::path> volumes;
    for (const char *path : {"neghip/neghip.nhdr", "tooth/tooth.nhdr", "walnut/walnut.nhdr",
                             "mr_brain_tumor_pyradiomics/brain1_image.nrrd", "ct_chest_lidc2/LIDC2.mha",
                             "engine/engine.vti", "bonsai/bonsai.vti", "aneurism/aneurism.vti"})
        volumes.push_back(test::shared_data(path));
    volumes.push_back(head);
    std::printf("arbor_bench_render: 512x512, sample distance 0.5 voxel, global ramp TF, 4 frames after a warm-up\n");
    std::printf("fps = frames per second; ratio = Arbor / VTK (> 1: Arbor faster); shaded, Arbor also with each "
                "voxel's gradient (voxel g) and with local ambient occlusion 1 (LAO)\n\n");
    std::printf("%-46s %14s | %8s %8s %6s | %8s %8s %6s | %8s %7s | %8s %7s\n", "volume", "dims", "arbor", "vtk",
                "ratio", "arbor sh", "vtk sh", "ratio", "voxel g", "cost", "LAO", "cost");
    const auto row = [](const std::filesystem::path &path) {
        const Volume v = test::import(path);
        const test::RampScene scene(v);
        const arbor_render_request &r = scene.request;
        const auto &g = v.geometry();
        const int frames = g.dims[0] * g.dims[1] * g.dims[2] > (int64_t{1} << 24) ? 3 : 4;
        const double plain = arbor_fps(r, false, {}, frames), plain_vtk = vtk_fps(r, false, frames);
        const double shaded = arbor_fps(r, true, {}, frames), shaded_vtk = vtk_fps(r, true, frames);
        const double voxel = arbor_fps(r, true, {{"sample-gradients", "false"}}, frames);
        const double occluded = arbor_fps(r, true, {{"ambient-occlusion", "1"}}, frames);
        char dims[32];
        std::snprintf(dims, sizeof dims, "%lldx%lldx%lld", static_cast<long long>(g.dims[0]),
                      static_cast<long long>(g.dims[1]), static_cast<long long>(g.dims[2]));
        const std::string name = path.parent_path().filename().string() + "/" + path.filename().string();
        std::printf("%-46s %14s | %8.2f %8.2f %5.2fx | %8.2f %8.2f %5.2fx | %8.2f %6.2fx | %8.2f %6.2fx\n",
                    name.c_str(), dims, plain, plain_vtk, plain / plain_vtk, shaded, shaded_vtk, shaded / shaded_vtk,
                    voxel, voxel / shaded, occluded, shaded / occluded);
        std::fflush(stdout);
    };
    for (const std::filesystem::path &path : volumes) try {
        if (wanted(path.string()))
            row(path);
    } catch (const std::exception &e) {
        std::printf("%-46s skipped: %s\n", path.string().c_str(), e.what());
    }
    try { // the tall CT last: made from the head once that has been timed
        if (wanted("tall"))
            row(bench::tall_ct(head, 3, scratch / "ct_head_x3.nrrd"));
    } catch (const std::exception &e) {
        std::printf("%-46s skipped: %s\n", "tall CT", e.what());
    }
    return 0;
}
