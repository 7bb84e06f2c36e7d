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
};

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
    for (const BenchInput &in : inputs) {
        const fs::path file = files[in.name];
        const VolumeLoader load = [&in, file, &o] { return load_input(in, file, o.plugins); };
        TableRow row{in.name, run_in_child(load, o.repeat), choose_ttk_anchor(timings, in.name)};
        print_row(std::cout, row);
        rows.push_back(std::move(row));
    }
    print_anchor_notes(std::cout, rows);
    print_summary(std::cout, rows);
    const bool all_ok = std::all_of(rows.begin(), rows.end(), [](const TableRow &r) { return r.run.ok; });
    return all_ok ? 0 : 1;
}
