// bench_render.cpp - frames per second of Arbor's CPU ray caster against
// VTK 9.1's vtkFixedPointVolumeRayCastMapper (the VTK reference renderer
// plugin) on the shared volumes and on two scans of clinical size (the CT
// head DICOM, 512x512x108, and the same CT with three times the slices,
// 512x512x322): 512x512, the same camera, sample distance (0.5 voxel),
// global transfer function and shading on or off, the renderers compared
// timed in alternation (rounds of frames, each one's fastest round).
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
#include <optional>
#include <string>
#include <vector>

using namespace arbor;

namespace {

void set(PluginInstance &plugin, const std::string &param, const std::string &text)
{
    plugin.set_param(param, parse_param_value(*plugin.find_param(param), text).value);
}

// The renderers' frames per second, timed in alternation: `rounds` rounds
// of `frames` frames, one renderer after the other within each round, and
// each renderer's fastest round counted. The VM's speed drifts by +-20 %
// over minutes; alternating puts the renderers compared in the same minutes,
// and the fastest round drops the moments the VM was paused.
std::vector<double> interleaved_fps(const std::vector<PluginInstance *> &renderers, const arbor_render_request &r,
                                    int frames, int rounds)
{
    for (PluginInstance *renderer : renderers)
        render_image(*renderer, r, 512, 512); // caches built outside the clock
    std::vector<double> fastest(renderers.size(), 1e30);
    for (int round = 0; round < rounds; ++round)
        for (std::size_t i = 0; i < renderers.size(); ++i) {
            const auto t0 = std::chrono::steady_clock::now();
            for (int f = 0; f < frames; ++f)
                render_image(*renderers[i], r, 512, 512);
            fastest[i] = std::min(fastest[i], std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
        }
    std::vector<double> fps;
    for (double seconds : fastest)
        fps.push_back(frames / seconds);
    return fps;
}

// Arbor's CPU ray caster as the comparison sets it up, `settings` on top;
// nullopt when the renderer has no such settings (an older build).
std::optional<PluginInstance> arbor_renderer(bool shading,
                                             const std::vector<std::pair<std::string, std::string>> &settings)
{
    PluginInstance cpu = test::built_plugins().create("org.arbor.renderer.cpu-raycast");
    test::set_shading(cpu, shading);
    test::plain_opacity(cpu);
    for (const auto &[param, value] : settings) {
        if (!cpu.find_param(param))
            return std::nullopt;
        set(cpu, param, value);
    }
    return cpu;
}

PluginInstance vtk_renderer(bool shading)
{
    PluginInstance vtk = test::built_plugins().create("org.arbor.renderer.vtk-reference");
    test::set_shading(vtk, shading);
    return vtk;
}

// The reference renderer takes axis-aligned grids only. A grid whose axes
// are flipped (brain1's second axis runs against LPS, the LIDC chest CT's
// second and third) is given to both renderers with its axes as they are
// stored: the same voxels, camera and work, the picture mirrored. An
// oblique grid stays as it is (and VTK's row says skipped).
void store_order(Volume &v)
{
    auto &direction = v.geometry().direction;
    for (double &c : direction)
        if (std::fabs(c) < 1e-6)
            c = 0;
    for (int r = 0; r < 3; ++r)
        for (int c = 0; c < 3; ++c)
            if (std::fabs(direction[3 * r + c]) != (r == c ? 1.0 : 0.0))
                return;
    direction = {1, 0, 0, 0, 1, 0, 0, 0, 1};
}

} // namespace

int main(int argc, char **argv)
{
    // Arguments: substrings of the volumes to time (all when none; "tall"
    // for the resampled CT head, "chest" for the resampled LIDC chest CT).
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
    std::printf("arbor_bench_render: 512x512, sample distance 0.5 voxel, global ramp TF; fps of the fastest of 3 "
                "rounds of 3 frames (2 on the large CTs), the renderers compared timed in alternation\n");
    std::printf("fps = frames per second; ratio = Arbor / VTK (> 1: Arbor faster); shaded, Arbor also with each "
                "voxel's gradient (voxel g) and with local ambient occlusion 1 (LAO)\n\n");
    std::printf("%-46s %14s | %8s %8s %6s | %8s %8s %6s | %8s %7s | %8s %7s\n", "volume", "dims", "arbor", "vtk",
                "ratio", "arbor sh", "vtk sh", "ratio", "voxel g", "cost", "LAO", "cost");
    const auto row = [](const std::filesystem::path &path) {
        Volume v = test::import(path);
        store_order(v);
        const test::RampScene scene(v);
        const arbor_render_request &r = scene.request;
        const auto &g = v.geometry();
        const int frames = g.dims[0] * g.dims[1] * g.dims[2] > (int64_t{1} << 24) ? 2 : 3, rounds = 3;
        std::optional<PluginInstance> plain_cpu = arbor_renderer(false, {}), shaded_cpu = arbor_renderer(true, {});
        std::optional<PluginInstance> voxel_cpu = arbor_renderer(true, {{"sample-gradients", "false"}});
        std::optional<PluginInstance> occluded_cpu = arbor_renderer(true, {{"ambient-occlusion", "1"}});
        PluginInstance plain_ref = vtk_renderer(false), shaded_ref = vtk_renderer(true);
        const std::vector<double> plain = interleaved_fps({&*plain_cpu, &plain_ref}, r, frames, rounds);
        std::vector<PluginInstance *> shaded_group{&*shaded_cpu, &shaded_ref};
        if (voxel_cpu)
            shaded_group.push_back(&*voxel_cpu);
        const std::vector<double> shaded = interleaved_fps(shaded_group, r, frames, rounds);
        const double voxel = voxel_cpu ? shaded[2] : NAN;
        const double occluded = occluded_cpu ? interleaved_fps({&*occluded_cpu}, r, frames, 2)[0] : NAN;
        char dims[32];
        std::snprintf(dims, sizeof dims, "%lldx%lldx%lld", static_cast<long long>(g.dims[0]),
                      static_cast<long long>(g.dims[1]), static_cast<long long>(g.dims[2]));
        const std::string name = path.parent_path().filename().string() + "/" + path.filename().string();
        std::printf("%-46s %14s | %8.2f %8.2f %5.2fx | %8.2f %8.2f %5.2fx | %8.2f %6.2fx | %8.2f %6.2fx\n",
                    name.c_str(), dims, plain[0], plain[1], plain[0] / plain[1], shaded[0], shaded[1],
                    shaded[0] / shaded[1], voxel, voxel / shaded[0], occluded, shaded[0] / occluded);
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
    try { // a clinical chest CT's size (512 x 512 x 275 in the blind comparison)
        if (wanted("chest"))
            row(bench::upsampled(test::shared_data("ct_chest_lidc2/LIDC2.mha"), {2, 2, 2},
                                 scratch / "lidc2_chest_x2.nrrd"));
    } catch (const std::exception &e) {
        std::printf("%-46s skipped: %s\n", "chest CT x2", e.what());
    }
    return 0;
}
