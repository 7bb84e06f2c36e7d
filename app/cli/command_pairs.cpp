// `arbor pairs <volume> -o pairs.txt`: the saddle-extremum pairs of the
// persistence branch decomposition, in the columns of the TTK reference files.
#include "command_pipeline.hpp"
#include "commands.hpp"
#include "input_flags.hpp"
#include "stage_timings.hpp"

#include "core/atomic_file.hpp"
#include "topology/persistence_pairs.hpp"

#include <cstdio>
#include <memory>
#include <sstream>

namespace arbor::cli {

namespace {

using pipeline::Stage;

struct PairsArgs {
    InputFlags input;
    FilterFlags filter;
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
        CommandPipeline p(context, !a->input.no_cache());
        pipeline::Document d = pipeline::default_document();
        a->input.apply(d.input, p->catalog());
        d.auto_denoise = false; // analysis sees the data as it is, unless a filter is asked for
        a->filter.apply(d.filters, d.auto_denoise, p->catalog());
        d.simplifier = {"persistence", "", {}};
        p->set_document(d);
        const auto filtered = p.run<Stage::Filter>();
        const auto tree = p.run<Stage::ContourTree>();
        const auto decomposition = p.run<Stage::Decomposition>();
        const Volume &volume = *filtered->volume;
        const topology::FieldView field{volume.type(), volume.data(), static_cast<uint32_t>(volume.voxel_count()),
                                        &volume.geometry()};
        const auto pairs = topology::persistence_pairs(tree->tree, decomposition->branches, field);
        std::ostringstream text;
        topology::write_persistence_pairs(text, pairs, volume.geometry(), volume.type(), filtered->source);
        if (a->output == "-") {
            std::fputs(text.str().c_str(), stdout);
        } else {
            AtomicFile out(a->output);
            out.write(text.str());
            out.commit();
        }
        if (a->timings)
            print_timings(*tree, decomposition.get(), volume);
        return 0;
    });
}

} // namespace arbor::cli
