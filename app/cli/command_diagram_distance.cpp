// `arbor diagram-distance A B`: the exact bottleneck or Wasserstein distance
// between two persistence diagrams read from files (`arbor pairs` text or
// CSV, TTK's reference pair files, gzip'd or not), per homology dimension.
#include "commands.hpp"
#include "provenance.hpp"

#include "core/stopwatch.hpp"
#include "io/persistence_diagram_files.hpp"
#include "topology/diagram_distance.hpp"

#include <nlohmann/json.hpp>

#include <cmath>
#include <cstdio>
#include <iostream>
#include <limits>
#include <memory>
#include <optional>

namespace arbor::cli {

namespace {

struct DistanceArgs {
    std::string a, b;
    std::string metric = "wasserstein";
    double p = 2.0;
    int dimension = -1;
    bool json = false;
};

nlohmann::json number_or_null(double v)
{
    return std::isfinite(v) ? nlohmann::json(v) : nlohmann::json(nullptr);
}

} // namespace

void add_diagram_distance_command(CLI::App &app, Context &context)
{
    CLI::App *sub = app.add_subcommand(
        "diagram-distance",
        "Exact distance between two persistence diagrams, per homology dimension.\n"
        "Reads `arbor pairs` files (text or CSV) and TTK's pair files, gzip'd or not.\n"
        "Ground distance L-infinity; a point may go to the diagonal at (death - birth) / 2;\n"
        "points match only within their dimension; essential points (the global minimum -\n"
        "maximum pair) only to essential points, and the distance is infinite when their\n"
        "numbers differ. Total: the largest per-dimension distance (bottleneck) or\n"
        "(sum of W_p^p)^(1/p) (Wasserstein).");
    auto a = std::make_shared<DistanceArgs>();
    sub->add_option("A", a->a, "First diagram")->required()->check(CLI::ExistingFile);
    sub->add_option("B", a->b, "Second diagram")->required()->check(CLI::ExistingFile);
    sub->add_option("--metric", a->metric, "bottleneck or wasserstein")
        ->check(CLI::IsMember({"bottleneck", "wasserstein"}))
        ->capture_default_str();
    sub->add_option("--p", a->p, "Wasserstein exponent (>= 1)")
        ->check(CLI::Range(1.0, std::numeric_limits<double>::max()))
        ->capture_default_str();
    sub->add_option("--dimension", a->dimension, "Only this homology dimension (0 to 3)")->check(CLI::Range(0, 3));
    sub->add_flag("--json", a->json, "Print the result as JSON");
    context.add_command(sub, [a, &context]() {
        Stopwatch clock;
        const topology::PersistenceDiagram da = io::read_persistence_diagram(a->a);
        const topology::PersistenceDiagram db = io::read_persistence_diagram(a->b);
        const double read_seconds = clock.lap();
        topology::DiagramDistanceOptions options;
        options.metric = a->metric == "bottleneck" ? topology::DiagramMetric::Bottleneck
                                                   : topology::DiagramMetric::Wasserstein;
        options.p = a->p;
        if (a->dimension >= 0)
            options.dimension = a->dimension;
        const topology::DiagramDistance d = topology::diagram_distance(da, db, options);
        const double seconds = clock.lap();
        const bool bottleneck = options.metric == topology::DiagramMetric::Bottleneck;

        if (a->json) {
            nlohmann::json out;
            out["format"] = "arbor-diagram-distance/1";
            out["a"] = a->a;
            out["b"] = a->b;
            out["metric"] = a->metric;
            if (!bottleneck)
                out["p"] = a->p;
            out["ground_distance"] = "linf";
            out["total"] = number_or_null(d.total);
            out["infinite"] = std::isinf(d.total);
            out["exact"] = d.exact;
            nlohmann::json dims = nlohmann::json::array();
            for (const topology::DimensionDistance &x : d.dimensions) {
                nlohmann::json j;
                j["dimension"] = x.dimension;
                j["distance"] = number_or_null(x.distance);
                j["points_a"] = x.points_a;
                j["points_b"] = x.points_b;
                j["essential_a"] = x.essential_a;
                j["essential_b"] = x.essential_b;
                j["matched_pairs"] = x.matched_pairs;
                j["exact"] = x.exact;
                if (!x.exact)
                    j["error_bound"] = x.error_bound;
                j["seconds"] = x.seconds;
                dims.push_back(j);
            }
            out["dimensions"] = dims;
            // What reproduces it: the code and the command (the inputs are
            // the files named above).
            out["provenance"] = {{"arbor", {{"version", arbor_version()}, {"commit", arbor_commit()}}},
                                 {"command_line", context.command_line}};
            out["seconds"] = {{"read", read_seconds}, {"distance", seconds}};
            std::cout << out.dump(2) << "\n";
            return 0;
        }

        char p_text[64];
        std::snprintf(p_text, sizeof p_text, " (p = %g)", a->p);
        std::printf("%s distance%s, L-infinity ground distance%s\n", bottleneck ? "bottleneck" : "Wasserstein",
                    bottleneck ? "" : p_text, d.exact ? ", exact" : "");
        std::printf("  A: %s\n  B: %s\n", a->a.c_str(), a->b.c_str());
        std::printf("%9s %10s %10s %9s %9s %18s %9s\n", "dimension", "points A", "points B", "essential", "matched",
                    "distance", "seconds");
        for (const topology::DimensionDistance &x : d.dimensions) {
            const std::string essential = std::to_string(x.essential_a) + "/" + std::to_string(x.essential_b);
            std::printf("%9d %10zu %10zu %9s %9zu %18.10g %9.3f\n", x.dimension, x.points_a, x.points_b,
                        essential.c_str(), x.matched_pairs, x.distance, x.seconds);
        }
        std::printf("%9s %10s %10s %9s %9s %18.10g %9.3f\n", "total", "", "", "", "", d.total, seconds);
        for (const topology::DimensionDistance &x : d.dimensions) {
            if (std::isinf(x.distance))
                std::printf("dimension %d: infinite, the diagrams have %zu and %zu essential points\n", x.dimension,
                            x.essential_a, x.essential_b);
            if (!x.exact)
                std::printf("dimension %d: costs rounded to integers; the exact distance is at most %.3g lower\n",
                            x.dimension, x.error_bound);
        }
        std::printf("matched: finite points paired with a point of the other diagram (the rest went to the "
                    "diagonal); read in %.3f s\n",
                    read_seconds);
        return 0;
    });
}

} // namespace arbor::cli
