// `arbor tree <volume> --json out.json`: the contour tree (nodes, arcs) and
// its persistence branch decomposition with every branch's measures; with
// --keep/--threshold also the simplified hierarchy and its voxel labels.
#include "command_pipeline.hpp"
#include "commands.hpp"
#include "provenance.hpp"

#include "io/json_writer.hpp"
#include "input_flags.hpp"
#include "look_flags.hpp"
#include "stage_timings.hpp"
#include "usage_error.hpp"

#include "io/contour_tree_json.hpp"
#include "io/label_map_output.hpp"

#include <cstdio>
#include <memory>
#include <string>

namespace arbor::cli {

namespace {

using pipeline::Stage;

struct TreeArgs {
    InputFlags input;
    FilterFlags filter;
    CutFlags cut; // optional here: without one, the whole hierarchy
    std::string json, labels;
    bool timings = false;
};

} // namespace

void add_tree_command(CLI::App &app, Context &context)
{
    CLI::App *sub = app.add_subcommand(
        "tree", "Compute the contour tree and its branch decomposition (persistence) with measures");
    auto a = std::make_shared<TreeArgs>();
    a->input.add_to(*sub, context);
    a->filter.add_to(*sub, context);
    sub->add_option("--json", a->json, "Write nodes, arcs and branches with measures as JSON")->required();
    a->cut.add_to(*sub, "Also cut the hierarchy at this relative persistence, in [0, 1]");
    sub->add_option("--labels", a->labels, "With --keep/--threshold: write the voxel -> branch labels (NRRD)");
    sub->add_flag("--timings", a->timings, "Print per-stage seconds and peak memory on stderr");
    context.add_command(sub, [a, &context]() {
        if (!a->labels.empty() && !a->cut.given())
            throw UsageError("--labels needs --keep or --threshold");
        const std::vector<std::string> keeps = a->cut.keeps();
        if (keeps.size() > 1)
            throw UsageError("--keep takes one value in `arbor tree`");
        CommandPipeline p(context, !a->input.no_cache());
        pipeline::Document d = pipeline::default_document();
        a->input.apply(d.input, p->catalog());
        d.auto_denoise = false; // analysis sees the data as it is, unless a filter is asked for
        a->filter.apply(d.filters, d.auto_denoise, p->catalog());
        d.simplifier = {"org.arbor.simplifier.persistence", "", {}};
        a->cut.apply(d.cut, keeps.empty() ? std::nullopt : std::optional<std::string>(keeps[0]));
        p->set_document(d);
        const auto filtered = p.run<Stage::Filter>();
        const auto tree = p.run<Stage::ContourTree>();
        const auto decomposition = p.run<Stage::Decomposition>();
        std::shared_ptr<const pipeline::CutResult> cut;
        if (a->cut.given())
            cut = p.run<Stage::Cut>();
        io::ContourTreeFile file;
        file.source = filtered->source;
        file.volume = filtered->volume.get();
        file.tree = &tree->tree;
        file.branches = &decomposition->branches;
        std::vector<topology::StageTiming> timings = tree->timings;
        timings.push_back({"branches+measures", decomposition->seconds});
        file.timings = &timings;
        file.cut = cut ? &cut->cut : nullptr;
        file.annotate = [&](io::JsonWriter &j) {
            write_provenance(j, context, p->catalog(),
                             provenance_of(p->document(), p.run<Stage::Import>().get(), filtered->filters));
        };
        io::write_contour_tree_json(a->json, file);
        if (cut && !a->labels.empty()) {
            const auto labels = p.run<Stage::Labels>();
            io::write_label_map(a->labels, filtered->volume->geometry(), "arbor branch labels of " + filtered->source,
                                labels->labels, labels->names);
        }
        std::printf("%s: %zu nodes, %zu arcs, %zu branches%s -> %s\n", filtered->source.c_str(),
                    tree->tree.node_count(), tree->tree.arc_count(), decomposition->branches.branches.size(),
                    cut ? (", " + std::to_string(cut->kept()) + " kept").c_str() : "", a->json.c_str());
        if (a->timings)
            print_timings(*tree, decomposition.get(), *filtered->volume);
        return 0;
    });
}

} // namespace arbor::cli
