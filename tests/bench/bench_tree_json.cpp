// arbor_bench_tree_json: what `arbor tree --json` costs next to `arbor pairs`
// on the same input.  Both commands import the volume, build the contour
// tree and decompose it by persistence; then pairs writes TTK's text columns
// and tree the arbor-contour-tree/2 file.  The goal: tree at most 1.3 times
// pairs.  It runs the real `arbor` executable, the two commands alternating,
// fastest of R runs each, and checks that every tree file parses, counting
// its nodes.  Twice: building the tree (--no-cache), and with the tree read
// from the on-disk cache (warm, in a cache folder of its own), where the
// file writing weighs most.  Prints a table; ctest does not run it.
// See README.md in this folder.
#include "process_run.hpp"

#include <CLI/CLI.hpp>
#include <rapidjson/document.h>

#include <algorithm>
#include <array>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <limits>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

namespace fs = std::filesystem;
using namespace arbor::bench;

namespace {

struct Input {
    const char *name;
    const char *path; // under <shared>/data
};

constexpr std::array<Input, 4> kInputs = {{{"mr_brain_colin27", "mr_brain_colin27/ch2.nii.gz"},
                                           {"ct_chest_lidc2", "ct_chest_lidc2/LIDC2.mha"},
                                           {"engine", "engine/engine.vti"},
                                           {"tooth", "tooth/tooth.nhdr"}}};

constexpr double kGoal = 1.3; // tree / pairs

struct TreeFile {
    long long voxels = 0;
    long long nodes = 0;
};

// Parses the file `arbor tree` wrote, an arbor-contour-tree/2 document (or
// /1, from an older build given with --arbor); returns its voxel and node
// counts.
TreeFile read_tree_file(const fs::path &path)
{
    std::ifstream in(path, std::ios::binary);
    std::stringstream text;
    text << in.rdbuf();
    rapidjson::Document d;
    d.Parse(text.str().c_str());
    const auto is = [&](const char *format) {
        return !d.HasParseError() && d.IsObject() && d.HasMember("format") && d["format"].IsString() &&
               std::string(d["format"].GetString()) == format;
    };
    if (!is("arbor-contour-tree/2") && !is("arbor-contour-tree/1"))
        throw std::runtime_error(path.string() + " is not an arbor-contour-tree/2 (or /1) file");
    TreeFile f;
    f.voxels = 1;
    for (const auto &n : d["volume"]["dims"].GetArray())
        f.voxels *= n.GetInt64();
    f.nodes = is("arbor-contour-tree/2") ? d["nodes"]["vertex"].Size() : d["nodes"].Size();
    return f;
}

} // namespace

int main(int argc, char **argv)
{
    int repeat = 3;
    std::vector<std::string> only;
    fs::path arbor = ARBOR_EXECUTABLE, shared = ARBOR_SHARED_DIR;
    fs::path out = fs::path(ARBOR_BINARY_DIR) / "bench-tree-json";
    CLI::App app("arbor tree --json against arbor pairs on the same inputs");
    app.add_option("--repeat", repeat, "Runs of each command per input; the fastest counts")
        ->check(CLI::PositiveNumber);
    app.add_option("--only", only, "Only inputs whose name contains this (repeatable)");
    app.add_option("--arbor", arbor, "The arbor executable");
    app.add_option("--shared", shared, "Folder with data/");
    app.add_option("--out", out, "Where the outputs go (overwritten)");
    CLI11_PARSE(app, argc, argv);
    fs::create_directories(out);
    // The warm runs' cache, apart from the user's.
    fs::remove_all(out / "cache");
    setenv("ARBOR_CACHE_DIR", (out / "cache").c_str(), 1);

    std::printf("arbor_bench_tree_json: %s, fastest of %d runs of each command (alternating);\n"
                "ratio = tree / pairs, goal <= %.1f; B/node = output bytes per contour-tree node\n\n",
                arbor.c_str(), repeat, kGoal);
    std::printf("%-18s %10s %8s %9s %9s %7s %9s %9s %7s %9s %9s %9s\n", "input", "voxels", "nodes", "pairs s",
                "tree s", "ratio", "warm p s", "warm t s", "warm", "pairs B/n", "tree B/n", "tree MB");
    double worst = 0.0, worst_warm = 0.0;
    int failed = 0;
    for (const Input &input : kInputs) {
        if (!only.empty() && std::none_of(only.begin(), only.end(), [&](const std::string &o) {
                return std::string(input.name).find(o) != std::string::npos;
            }))
            continue;
        const std::string source = (shared / "data" / input.path).string();
        const fs::path pairs_out = out / (std::string(input.name) + ".pairs.txt");
        const fs::path tree_out = out / (std::string(input.name) + ".tree.json");
        double pairs = std::numeric_limits<double>::infinity(), tree = pairs, warm_pairs = pairs, warm_tree = pairs;
        std::string error;
        const auto time_both = [&](bool cached, double &p_best, double &t_best) {
            std::vector<std::string> p_args{arbor.string(), "pairs", source, "-o", pairs_out.string()};
            std::vector<std::string> t_args{arbor.string(), "tree", source, "--json", tree_out.string()};
            if (!cached) {
                p_args.push_back("--no-cache");
                t_args.push_back("--no-cache");
            } else {
                run_process(p_args); // fills the cache
            }
            for (int r = 0; r < repeat && error.empty(); ++r) {
                const ProcessRun p = run_process(p_args);
                const ProcessRun t = run_process(t_args);
                error = !p.ok ? p.error : t.error;
                p_best = std::min(p_best, p.seconds);
                t_best = std::min(t_best, t.seconds);
            }
        };
        time_both(false, pairs, tree);
        time_both(true, warm_pairs, warm_tree);
        TreeFile f;
        try {
            if (error.empty())
                f = read_tree_file(tree_out);
        } catch (const std::exception &e) {
            error = e.what();
        }
        if (!error.empty()) {
            std::printf("%-18s FAILED: %s\n", input.name, error.c_str());
            ++failed;
            continue;
        }
        const double ratio = tree / pairs, warm_ratio = warm_tree / warm_pairs;
        worst = std::max(worst, ratio);
        worst_warm = std::max(worst_warm, warm_ratio);
        const auto per_node = [&](const fs::path &p) {
            return static_cast<double>(fs::file_size(p)) / static_cast<double>(f.nodes);
        };
        std::printf("%-18s %10lld %8lld %9.3f %9.3f %6.2fx %9.3f %9.3f %6.2fx %9.1f %9.1f %9.2f\n", input.name,
                    f.voxels, f.nodes, pairs, tree, ratio, warm_pairs, warm_tree, warm_ratio, per_node(pairs_out),
                    per_node(tree_out), static_cast<double>(fs::file_size(tree_out)) / 1e6);
        std::fflush(stdout);
    }
    std::printf("\nworst ratio %.2fx building the tree, %.2fx with the tree cached: goal (<= %.1f) %s\n", worst,
                worst_warm, kGoal, std::max(worst, worst_warm) <= kGoal ? "met" : "NOT met");
    return failed ? 1 : 0;
}
