// bench_isolation.cpp - what plugin isolation costs (host/isolated_library.hpp),
// against the same work with every plugin in-process, in the same run:
//
//   1. whole `arbor run` commands (import, contour tree, ITri, depiction,
//      transfer functions, rendering, writing) with --isolate none and
//      --isolate all (every plugin in its own process), fastest of --runs;
//   2. frames of the CPU ray caster, in-process and isolated: the first
//      frame (the volume and labels copied into shared memory) and the
//      fastest of five after it (one image copied out per frame).
//
// Prints a table with the overhead as a ratio (isolated / in-process); the
// goal is at most 1.05.  Not a pass/fail test.
#include "fastest_run.hpp"
#include "global_ramp.hpp"
#include "plugin_fixture.hpp"
#include "process_run.hpp"


#include <CLI/CLI.hpp>

#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <filesystem>

using namespace arbor;
namespace fs = std::filesystem;

namespace {

double fastest_command(const std::vector<std::string> &argv, int runs)
{
    double best = 1e30;
    for (int r = 0; r < runs; ++r) {
        const bench::ProcessRun run = bench::run_process(argv);
        if (!run.ok)
            throw std::runtime_error(run.error);
        best = std::min(best, run.seconds);
    }
    return best;
}

std::unique_ptr<PluginRegistry> isolated_plugins()
{
    auto r = std::make_unique<PluginRegistry>();
    r->set_isolation(default_isolation(fs::read_symlink("/proc/self/exe"), IsolationMode::All, 60));
    r->load_directories({test::plugin_dir()});
    return r;
}

} // namespace

int main(int argc, char **argv)
{
    CLI::App app{"Plugin isolation's overhead: arbor run and frames, in-process against isolated"};
    int runs = 3;
    app.add_option("--runs", runs, "Runs of each command (the fastest counts)")->check(CLI::PositiveNumber);
    CLI11_PARSE(app, argc, argv);

    const fs::path scratch = fs::temp_directory_path() / ("arbor-bench-isolation-" + std::to_string(getpid()));
    fs::create_directories(scratch);
    std::printf("arbor_bench_isolation: ratio = isolated / in-process (1.00: no cost; goal <= 1.05)\n\n");
    std::printf("%-44s %12s %12s %8s\n", "arbor run (fastest of runs)", "in-process s", "isolated s", "ratio");
    const std::vector<std::vector<std::string>> inputs = {
        {test::shared_data("ct_chest_lidc2/LIDC2.mha").string()},
        {test::shared_data("mr_brain_tumor_pyradiomics/brain1_image.nrrd").string()},
        {"--phantom", "head"}};
    for (const auto &input : inputs) try {
        double seconds[2];
        for (int isolated = 0; isolated < 2; ++isolated) {
            std::vector<std::string> command = {ARBOR_EXECUTABLE, "--isolate", isolated ? "all" : "none", "-q", "run"};
            command.insert(command.end(), input.begin(), input.end());
            for (const char *a : {"-o", "", "--no-cache"})
                command.push_back(a);
            command[command.size() - 2] = (scratch / (isolated ? "iso.png" : "in.png")).string();
            seconds[isolated] = fastest_command(command, runs);
        }
        std::printf("%-44s %12.2f %12.2f %7.3fx\n", fs::path(input.front()).filename().c_str(), seconds[0], seconds[1],
                    seconds[1] / seconds[0]);
        std::fflush(stdout);
    } catch (const std::exception &e) {
        std::printf("%-44s skipped: %s\n", input.front().c_str(), e.what());
    }

    std::printf("\n%-44s %12s %12s %8s\n", "CPU ray caster, 512x512", "in-process s", "isolated s", "ratio");
    const auto isolated = isolated_plugins();
    for (const char *path : {"ct_chest_lidc2/LIDC2.mha", "mr_brain_tumor_pyradiomics/brain1_image.nrrd"}) try {
        const Volume v = test::import(test::shared_data(path));
        const test::RampScene scene(v);
        const arbor_render_request &r = scene.request;
        double first[2], steady[2];
        for (int iso = 0; iso < 2; ++iso) {
            PluginInstance renderer = (iso ? *isolated : test::built_plugins()).create("org.arbor.renderer.cpu-raycast");
            first[iso] = bench::fastest_seconds([&] { render_image(renderer, r, 512, 512); }, 1);
            steady[iso] = bench::fastest_seconds([&] { render_image(renderer, r, 512, 512); }, 5);
        }
        std::printf("%-44s %12.3f %12.3f %7.3fx\n", (std::string(path) + " first frame").c_str(), first[0], first[1],
                    first[1] / first[0]);
        std::printf("%-44s %12.3f %12.3f %7.3fx\n", (std::string(path) + " next frames").c_str(), steady[0],
                    steady[1], steady[1] / steady[0]);
        std::fflush(stdout);
    } catch (const std::exception &e) {
        std::printf("%-44s skipped: %s\n", path, e.what());
    }
    std::error_code ec;
    fs::remove_all(scratch, ec);
    return 0;
}
