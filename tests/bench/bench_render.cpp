// bench_render.cpp - frames per second of Arbor's CPU ray caster against
// VTK 9.1's vtkFixedPointVolumeRayCastMapper (the VTK reference renderer
// plugin) on the shared volumes: 512x512, the same camera, sample distance
// (0.5 voxel), global transfer function and shading on or off, measured in
// the same run.  Needs X for VTK: run under xvfb-run.  Prints a table; not a
// pass/fail test.
#include "global_ramp.hpp"
#include "plugin_fixture.hpp"

#include "host/rendering.hpp"
#include "host/tf_generation.hpp"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>

using namespace arbor;

namespace {

double frames_per_second(PluginInstance &renderer, const arbor_render_request &r, int frames)
{
    render_image(renderer, r, 512, 512); // caches built outside the clock
    const auto t0 = std::chrono::steady_clock::now();
    for (int f = 0; f < frames; ++f)
        render_image(renderer, r, 512, 512);
    return frames / std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

} // namespace

int main()
{
    const char *display = std::getenv("DISPLAY");
    if (!display || !*display) {
        std::fprintf(stderr, "arbor_bench_render: VTK needs an X display; run under xvfb-run -a\n");
        return 2;
    }
    const char *volumes[] = {"neghip/neghip.nhdr",        "tooth/tooth.nhdr",
                             "walnut/walnut.nhdr",        "mr_brain_tumor_pyradiomics/brain1_image.nrrd",
                             "ct_chest_lidc2/LIDC2.mha",  "engine/engine.vti",
                             "bonsai/bonsai.vti",         "aneurism/aneurism.vti"};
    std::printf("arbor_bench_render: 512x512, sample distance 0.5 voxel, global ramp TF, 4 frames after a warm-up\n");
    std::printf("fps = frames per second; ratio = Arbor / VTK (> 1: Arbor faster)\n\n");
    std::printf("%-46s %14s | %9s %9s %7s | %9s %9s %7s\n", "volume", "dims", "arbor", "vtk", "ratio",
                "arbor sh", "vtk sh", "ratio");
    for (const char *path : volumes) try {
        const Volume v = test::import(test::shared_data(path));
        const test::RampScene scene(v);
        const arbor_render_request &r = scene.request;
        double fps[2][2];
        for (int shading = 0; shading < 2; ++shading) {
            PluginInstance cpu = test::built_plugins().create("org.arbor.renderer.cpu-raycast");
            PluginInstance vtk = test::built_plugins().create("org.arbor.renderer.vtk-reference");
            for (PluginInstance *p : {&cpu, &vtk})
                test::set_shading(*p, shading);
            test::plain_opacity(cpu);
            fps[shading][0] = frames_per_second(cpu, r, 4);
            fps[shading][1] = frames_per_second(vtk, r, 4);
        }
        const auto &g = v.geometry();
        char dims[32];
        std::snprintf(dims, sizeof dims, "%lldx%lldx%lld", static_cast<long long>(g.dims[0]),
                      static_cast<long long>(g.dims[1]), static_cast<long long>(g.dims[2]));
        std::printf("%-46s %14s | %9.2f %9.2f %6.2fx | %9.2f %9.2f %6.2fx\n", path, dims, fps[0][0], fps[0][1],
                    fps[0][0] / fps[0][1], fps[1][0], fps[1][1], fps[1][0] / fps[1][1]);
        std::fflush(stdout);
    } catch (const std::exception &e) {
        std::printf("%-46s skipped: %s\n", path, e.what());
    }
    return 0;
}
