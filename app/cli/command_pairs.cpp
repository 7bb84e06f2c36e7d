// `arbor pairs <volume> -o pairs.txt`: the saddle-extremum pairs of the
// persistence branch decomposition, in the columns of the TTK reference files.
#include "commands.hpp"
#include "topology_run.hpp"
#include "filter_input.hpp"
#include "volume_input.hpp"

#include "core/atomic_file.hpp"
#include "topology/persistence_pairs.hpp"

#include <cstdio>
#include <memory>
#include <sstream>

namespace arbor::cli {

namespace {

struct PairsArgs {
    VolumeInput input;
    FilterInput filter;
    std::string output;
    bool timings = false;
};

} // namespace

void add_pairs_command(CLI::App &app, Context &context)
{
    CLI::App *sub = app.add_subcommand(
        "pairs", "Write the persistence pairs of the contour tree (TTK's columns)");
    auto a = std::make_shared<PairsArgs>();
    a->input.add_to(*sub, context);
    a->filter.add_to(*sub, context);
    sub->add_option("-o,--output", a->output, "Output text file ('-' for standard output)")->required();
    sub->add_flag("--timings", a->timings, "Print per-stage seconds and peak memory on stderr");
    context.add_command(sub, [a, &context]() {
        LoadedVolume in = a->input.load();
        a->filter.apply(in, context);
        const topology::TopologyResult topo = run_topology(in.volume, topology::persistence_importance(), context);
        const topology::FieldView field{in.volume.type(), in.volume.data(),
                                        static_cast<uint32_t>(in.volume.voxel_count()),
                                        &in.volume.geometry()};
        const auto pairs = topology::persistence_pairs(topo.tree, topo.branches, field);
        std::ostringstream text;
        topology::write_persistence_pairs(text, pairs, in.volume.geometry(), in.volume.type(), in.source);
        if (a->output == "-") {
            std::fputs(text.str().c_str(), stdout);
        } else {
            AtomicFile out(a->output);
            out.write(text.str());
            out.commit();
        }
        if (a->timings)
            print_timings(topo, in.volume);
        return 0;
    });
}

} // namespace arbor::cli
