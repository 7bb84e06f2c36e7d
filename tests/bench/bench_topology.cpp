// arbor_bench_topology: times the topology pipeline (contour tree, branch
// decomposition with persistence) on the phantom, the shared real volumes and
// the synthetic fields, and sets each against TTK FTM's time and memory on
// the same input (reference/ttk/TIMINGS.md).  Prints a table; it is not a
// test and ctest does not run it.  See README.md in this folder.
#include "bench_inputs.hpp"
#include "bench_table.hpp"
#include "child_run.hpp"
#include "synthetic_cache.hpp"
#include "ttk_anchor.hpp"
#include "volume_loading.hpp"

#include <CLI/CLI.hpp>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <map>

namespace fs = std::filesystem;
using namespace arbor::bench;

namespace {

struct Options {
    int repeat = 3;
    int64_t max_size = 512;
    std::vector<std::string> only;
    fs::path shared = ARBOR_SHARED_DIR;
    fs::path data_cache = fs::path(ARBOR_BINARY_DIR) / "bench-data";
    fs::path plugins = ARBOR_PLUGIN_DIR;
    std::string python = ARBOR_BENCH_PYTHON;
    double phantom_noise = 8.0;
    int phantom_blobs = 20;
    bool list = false;
    std::vector<int> cores; // empty: no pinning, one run per input
};

// Per input, the fastest total and stages at each core count, and the
// speed-up over the first count (normally 1).
void print_scaling(const std::vector<int> &cores, const std::vector<std::pair<std::string, std::vector<RunReport>>> &runs)
{
    std::cout << "\ncore scaling: seconds of the fastest run pinned to N cores (sched_setaffinity); speed-up = "
              << cores.front() << "-core time / N-core time, total and per stage (";
    for (std::size_t s = 0; s < kStageNames.size(); ++s)
        std::cout << (s ? ", " : "") << kStageNames[s];
    std::cout << ")\n";
    std::printf("%-22s", "input");
    for (const int c : cores)
        std::printf(" %8s", (std::to_string(c) + (c == 1 ? " core" : " cores")).c_str());
    for (std::size_t i = 1; i < cores.size(); ++i)
        std::printf("  speed-up %dc: total (stages)", cores[i]);
    std::printf("\n");
    for (const auto &[name, reports] : runs) {
        std::printf("%-22s", name.c_str());
        for (const RunReport &r : reports)
            r.ok ? std::printf(" %8.2f", r.total_seconds) : std::printf(" %8s", "failed");
        for (std::size_t i = 1; i < reports.size(); ++i) {
            const RunReport &a = reports.front(), &b = reports[i];
            if (!a.ok || !b.ok) {
                std::printf("  -");
                continue;
            }
            std::printf("  %.2fx (", a.total_seconds / b.total_seconds);
            for (std::size_t s = 0; s < kStageNames.size(); ++s)
                std::printf("%s%.2f", s ? " " : "", a.stage_seconds[s] / b.stage_seconds[s]);
            std::printf(")");
        }
        std::printf("\n");
    }
}

void print_preamble(const Options &o, const fs::path &timings, std::size_t inputs)
{
    std::cout << "arbor_bench_topology: compute_topology(persistence_importance()), " << inputs
              << " inputs, fastest of " << o.repeat << " run(s) each, one child process per input\n"
              << "times in seconds (stages of the fastest run; file reading not timed); peak = VmHWM of the child\n"
              << "during its first run; B/vx = peak / voxels, work = (peak - base) / voxels, in = input bytes/voxel;\n"
              << "TTK columns from " << timings.string() << " (same machine class, not re-run here);\n"
              << "speed-up = TTK s / our s, mem = TTK peak / our peak (both > 1: Arbor better)\n\n";
}

} // namespace

int main(int argc, char **argv)
{
    Options o;
    CLI::App app{"Benchmark of Arbor's topology core against TTK FTM (reference/ttk/TIMINGS.md)"};
    app.add_option("--repeat", o.repeat, "Runs per input; the fastest is reported")->check(CLI::Range(1, 100));
    app.add_option("--max-size", o.max_size, "Skip inputs with an axis longer than this")->check(CLI::PositiveNumber);
    app.add_option("--only", o.only, "Run only inputs whose name contains one of these (repeatable)");
    app.add_option("--shared", o.shared, "The shared folder (data/, reference/)");
    app.add_option("--data-cache", o.data_cache, "Where generated synthetic fields are kept");
    app.add_option("--plugins", o.plugins, "Folder of the importer plugins");
    app.add_option("--python", o.python, "Python 3 with numpy, to run gen_volumes.py");
    app.add_option("--phantom-noise", o.phantom_noise, "Noise sigma of the noisy phantoms");
    app.add_option("--phantom-blobs", o.phantom_blobs, "Blobs in the noisy phantoms");
    app.add_flag("--list", o.list, "List the selected inputs and exit");
    app.add_option("--cores", o.cores,
                   "Run every input pinned to each of these core counts (e.g. --cores 1 2) and print the "
                   "speed-up; the main table shows the last count")
        ->check(CLI::Range(1, 1024));
    CLI11_PARSE(app, argc, argv);

    CatalogueOptions catalogue;
    catalogue.data_dir = o.shared / "data";
    catalogue.phantom_noise = o.phantom_noise;
    catalogue.phantom_blobs = o.phantom_blobs;
    const std::vector<BenchInput> inputs = select_inputs(all_inputs(catalogue), o.max_size, o.only);
    if (o.list) {
        for (const BenchInput &in : inputs)
            std::cout << in.name << '\n';
        return 0;
    }
    if (inputs.empty()) {
        std::cerr << "no input selected\n";
        return 2;
    }

    const fs::path timings_file = o.shared / "reference" / "ttk" / "TIMINGS.md";
    std::vector<TtkRow> timings;
    try {
        timings = load_ttk_timings(timings_file);
    } catch (const std::exception &e) {
        std::cerr << "warning: no TTK anchor: " << e.what() << '\n';
    }

    // Generate the synthetic fields before measuring anything: the generator
    // takes minutes and gigabytes at 512^3 and must not overlap a run.
    const SyntheticSetup synthetic{.cache_dir = o.data_cache,
                                   .generator = o.shared / "reference" / "ttk" / "synthetic" / "gen_volumes.py",
                                   .python = o.python,
                                   .shipped_dir = o.shared / "reference" / "ttk" / "synthetic"};
    std::vector<SyntheticField> fields;
    for (const BenchInput &in : inputs)
        if (in.synthetic)
            fields.push_back(*in.synthetic);
    std::map<std::string, fs::path> files;
    try {
        prepare_synthetic(synthetic, fields);
        for (const BenchInput &in : inputs)
            files[in.name] = in.synthetic ? synthetic_header(synthetic, *in.synthetic) : in.file;
    } catch (const std::exception &e) {
        std::cerr << "cannot prepare the synthetic fields: " << e.what() << '\n';
        return 1;
    }

    print_preamble(o, timings_file, inputs.size());
    print_header(std::cout);
    std::vector<TableRow> rows;
    std::vector<std::pair<std::string, std::vector<RunReport>>> scaling;
    for (const BenchInput &in : inputs) {
        const fs::path file = files[in.name];
        const VolumeLoader load = [&in, file, &o] { return load_input(in, file, o.plugins); };
        std::vector<RunReport> reports;
        for (const int c : o.cores.empty() ? std::vector<int>{0} : o.cores)
            reports.push_back(run_in_child(load, o.repeat, c));
        TableRow row{in.name, reports.back(), choose_ttk_anchor(timings, in.name)};
        print_row(std::cout, row);
        rows.push_back(std::move(row));
        scaling.emplace_back(in.name, std::move(reports));
    }
    print_anchor_notes(std::cout, rows);
    if (o.cores.size() > 1)
        print_scaling(o.cores, scaling);
    print_summary(std::cout, rows);
    const bool all_ok = std::all_of(rows.begin(), rows.end(), [](const TableRow &r) { return r.run.ok; });
    return all_ok ? 0 : 1;
}
