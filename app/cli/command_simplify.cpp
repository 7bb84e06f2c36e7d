// `arbor simplify <volume> --simplifier ID (--threshold T | --keep N)
// --json out.json [--labels labels.nrrd]`: the contour tree simplified by
// one simplifier plugin, its kept branches with measures and importance,
// and the voxel -> branch label map.
#include "command_pipeline.hpp"
#include "commands.hpp"
#include "provenance.hpp"
#include "input_flags.hpp"
#include "look_flags.hpp"
#include "stage_timings.hpp"
#include "usage_error.hpp"

#include "io/json_writer.hpp"
#include "io/label_map_output.hpp"
#include "io/topology_json.hpp"

#include <cstdio>
#include <functional>
#include <memory>

namespace arbor::cli {

namespace {

using pipeline::Stage;

struct SimplifyArgs {
    InputFlags input;
    FilterFlags filter;
    SimplifierFlags simplifier;
    CutFlags cut;
    std::string json, labels;
    bool timings = false;
};

void write_json(const std::string &path, const pipeline::FilterResult &in, const pipeline::ContourTreeResult &tree,
                const pipeline::CutResult &cut, const std::function<void(io::JsonWriter &)> &provenance)
{
    const pipeline::DecompositionResult &d = *cut.decomposition;
    io::write_json_file(path, io::JsonLayout::indented, [&](io::JsonWriter &j) {
        j.field("format", "arbor-simplified-tree/1");
        provenance(j);
        io::write_volume_summary(j, in.source, in.volume->geometry());
        {
            const io::JsonWriter::Scope simplifier = j.object("simplifier");
            j.field("id", d.simplifier.id);
            j.field("name", d.simplifier_name);
            j.field("version", d.simplifier.version);
        }
        {
            const io::JsonWriter::Scope c = j.object("cut");
            if (cut.requested.keep)
                j.field("keep", *cut.requested.keep);
            else
                j.field("threshold", cut.requested.threshold.value_or(0.0));
        }
        io::write_contour_tree_summary(j, tree.tree, tree.seconds, d.branches.branches.size());
        io::write_kept_branches(j, "kept_branches", tree.tree, *in.volume, d.branches, cut.cut);
        const io::JsonWriter::Scope seconds = j.object("seconds");
        j.field("contour_tree", tree.seconds);
        j.field("simplification", d.seconds + cut.seconds);
    });
}

} // namespace

void add_simplify_command(CLI::App &app, Context &context)
{
    CLI::App *sub = app.add_subcommand(
        "simplify", "Simplify the contour tree with a simplifier plugin; write the kept branches and labels");
    auto a = std::make_shared<SimplifyArgs>();
    a->input.add_to(*sub, context);
    a->filter.add_to(*sub, context);
    a->simplifier.add_to(*sub, context);
    a->cut.add_to(*sub, "Keep branches whose relative importance exceeds T (ITri and n-measure importances are "
                        "products of relative measures: small numbers)");
    sub->add_option("--json", a->json, "Write the kept branches with measures and importance as JSON")->required();
    sub->add_option("--labels", a->labels,
                    "Write the voxel -> branch label map as NRRD, with a 3D Slicer colour table (.ctbl) beside it");
    sub->add_flag("--timings", a->timings, "Print per-stage seconds and peak memory on stderr");
    context.add_command(sub, [a, &context]() {
        if (!a->cut.given())
            throw UsageError("give --keep N or --threshold T");
        refuse_lists({a->simplifier.names(), a->cut.keeps(), {}, {}, {}}, "simplify");
        CommandPipeline p(context, !a->input.no_cache());
        pipeline::Document d = pipeline::default_document();
        a->input.apply(d.input, p->catalog());
        d.auto_denoise = false; // analysis sees the data as it is, unless a filter is asked for
        a->filter.apply(d.filters, d.auto_denoise, p->catalog());
        const std::vector<std::string> names = a->simplifier.names(), keeps = a->cut.keeps();
        a->simplifier.apply(d.simplifier, names.empty() ? std::nullopt : std::optional(names[0]), p->catalog());
        a->cut.apply(d.cut, keeps.empty() ? std::nullopt : std::optional(keeps[0]));
        p->set_document(d);
        const auto filtered = p.run<Stage::Filter>();
        const auto tree = p.run<Stage::ContourTree>();
        const auto cut = p.run<Stage::Cut>();
        write_json(a->json, *filtered, *tree, *cut, [&](io::JsonWriter &j) {
            write_provenance(j, context, p->catalog(),
                             provenance_of(p->document(), p.run<Stage::Import>().get(), filtered->filters));
        });
        if (!a->labels.empty()) {
            const auto labels = p.run<Stage::Labels>();
            io::write_label_map(a->labels, filtered->volume->geometry(),
                                "arbor " + cut->decomposition->simplifier.id + " labels of " + filtered->source,
                                labels->labels, labels->names);
        }
        std::printf("%s: %zu branches, %zu kept by %s (%s) -> %s\n", filtered->source.c_str(),
                    cut->decomposition->branches.branches.size(), cut->kept(),
                    cut->decomposition->simplifier.id.c_str(), cut->requested.describe().c_str(), a->json.c_str());
        if (a->timings)
            print_timings(*tree, cut->decomposition.get(), *filtered->volume);
        return 0;
    });
}

} // namespace arbor::cli
