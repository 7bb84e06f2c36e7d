// `arbor tf <volume>`: per-branch transfer functions.  The volume's contour
// tree is simplified (--simplifier, --keep/--threshold), a depictor adds its
// relationship (inclusion by default; neighbour around --select), and a
// generator (residue flow by default) writes one transfer function per kept
// branch.  The generator sees the branch tree only.
#include "branch_json.hpp"
#include "commands.hpp"
#include "plugin_choice.hpp"
#include "png_output.hpp"
#include "simplification_run.hpp"
#include "topology_run.hpp"
#include "transfer_function_json.hpp"
#include "volume_input.hpp"

#include "host/branch_tree_record.hpp"
#include "host/param_text.hpp"
#include "host/tf_generation.hpp"

#include <opencv2/imgproc.hpp>

#include <chrono>
#include <cstdio>
#include <memory>
#include <optional>

namespace arbor::cli {

namespace {

struct TfArgs {
    VolumeInput input;
    PluginChoice simplifiers{ARBOR_KIND_SIMPLIFIER, "simplifier"};
    PluginChoice depictors{ARBOR_KIND_DEPICTOR, "depictor"};
    PluginChoice generators{ARBOR_KIND_TF_GENERATOR, "transfer-function generator"};
    std::string simplifier = "itri", generator = "residue-flow", relation = "inclusion";
    CutRequest cut;
    std::optional<double> flow_rate;
    std::optional<std::string> shape, hues;
    std::optional<int32_t> select;
    uint32_t lut_size = 256;
    std::string output, legend;
    int legend_size = 512;
    bool timings = false;
};

// --flow-rate, --shape and --hues are the generator's parameters of those names.
void set_named(PluginInstance &generator, const std::string &param, const std::string &text)
{
    const arbor_param_desc *d = generator.find_param(param);
    if (!d)
        throw std::invalid_argument(generator.id() + " has no parameter '" + param + "'");
    generator.set_param(param, parse_param_value(*d, text).value);
}

// The depictor's legend as an image, drawn before anything is written so
// that a depictor without one fails the command cleanly.
cv::Mat draw_legend(PluginInstance &depictor, const arbor_depiction_request &request, int size)
{
    const auto &table = depictor.interface<arbor_depictor_v1>(ARBOR_INTERFACE_DEPICTOR);
    std::vector<float> rgba(static_cast<std::size_t>(size) * size * 4, 0.0f);
    arbor_image image{};
    image.struct_size = sizeof image;
    image.width = image.height = static_cast<uint32_t>(size);
    image.row_stride = 4 * size;
    image.rgba = rgba.data();
    Task task;
    const arbor_status s = table.legend(depictor.get(), &request, &image, task.get());
    if (s == ARBOR_ERROR_UNSUPPORTED)
        throw std::invalid_argument(depictor.id() + " draws no legend (use --relation neighbour --select B)");
    depictor.check(s, "drawing the legend");
    cv::Mat bgr(size, size, CV_8UC3);
    for (int y = 0; y < size; ++y)
        for (int x = 0; x < size; ++x) {
            const float *p = &rgba[(static_cast<std::size_t>(y) * size + x) * 4];
            // Premultiplied over white.
            for (int c = 0; c < 3; ++c)
                bgr.at<cv::Vec3b>(y, x)[2 - c] =
                    static_cast<uint8_t>(std::clamp(p[c] + (1.0f - p[3]), 0.0f, 1.0f) * 255.0f + 0.5f);
        }
    return bgr;
}

} // namespace

void add_tf_command(CLI::App &app, Context &context)
{
    CLI::App *sub = app.add_subcommand(
        "tf", "Generate one transfer function per branch (residue-flow opacity, harmonic colours)");
    auto a = std::make_shared<TfArgs>();
    a->input.add_to(*sub, context);
    sub->add_option("--simplifier", a->simplifier, "Simplifier plugin (id or last part)")->default_val("itri");
    add_cut_options(*sub, a->cut, "Keep branches whose relative importance exceeds T (default: --keep 12)");
    sub->add_option("--generator", a->generator, "Transfer-function generator (residue-flow, histogram-ramp)")
        ->default_val("residue-flow");
    sub->add_option("--flow-rate", a->flow_rate, "Flow rate Q (generator parameter flow-rate)");
    sub->add_option("--shape", a->shape, "Opacity shape: ramp, inverse-ramp, hat, box, peak");
    sub->add_option("--hues", a->hues, "Hue template: full, or i, V, L, I, T, Y, X with :rotation (X:30)");
    sub->add_option("--select", a->select, "Selected branch (a label of the simplified tree)")
        ->check(CLI::NonNegativeNumber);
    sub->add_option("--relation", a->relation, "Relationship to depict: inclusion or neighbour")
        ->check(CLI::IsMember({"inclusion", "neighbour", "none"}))
        ->default_val("inclusion");
    sub->add_option("--lut-size", a->lut_size, "Entries of each baked lookup table")
        ->check(CLI::Range(2, 65536))
        ->default_val(256);
    sub->add_option("-o,--output", a->output, "Transfer functions (JSON, arbor-transfer-functions/1)")->required();
    sub->add_option("--legend", a->legend, "Write the depictor's legend (the relation wheel) as PNG");
    sub->add_option("--legend-size", a->legend_size, "Legend width and height in pixels")
        ->check(CLI::Range(64, 4096))
        ->default_val(512);
    sub->add_flag("--timings", a->timings, "Print per-stage seconds on stderr");
    a->simplifiers.add_to(*sub, context, "Simplifier options");
    a->depictors.add_to(*sub, context, "Depictor options");
    a->generators.add_to(*sub, context, "Generator options");
    context.add_command(sub, [a, &context]() {
        if (!a->cut.keep && !a->cut.threshold)
            a->cut.keep = 12;
        if (a->relation == "neighbour" && !a->select)
            throw std::invalid_argument("--relation neighbour needs --select BRANCH");
        if (!a->legend.empty() && a->relation == "none")
            throw std::invalid_argument("--legend needs a depictor (--relation neighbour --select BRANCH)");
        PluginInstance &simplifier = a->simplifiers.resolve(a->simplifier);
        PluginInstance &generator = a->generators.resolve(a->generator);
        PluginInstance *depictor = a->relation == "none" ? nullptr : &a->depictors.resolve(a->relation);
        if (a->flow_rate)
            set_named(generator, "flow-rate", std::to_string(*a->flow_rate));
        if (a->shape)
            set_named(generator, "shape", *a->shape);
        if (a->hues)
            set_named(generator, "hues", *a->hues);

        const LoadedVolume in = a->input.load();
        const topology::TopologyResult topo = run_contour_tree(in.volume, context);
        const SimplifiedTree s = simplify_tree(topo.tree, in.volume, simplifier, a->cut, context);
        const BranchTreeRecord tree(topo.tree, s.branches, s.cut, in.volume);
        if (a->select && static_cast<uint32_t>(*a->select) >= tree.size())
            throw std::invalid_argument("--select " + std::to_string(*a->select) + ": the simplified tree has " +
                                        std::to_string(tree.size()) + " branches (0.." +
                                        std::to_string(tree.size() - 1) + ")");

        const auto start = std::chrono::steady_clock::now();
        arbor_depiction_request request{};
        request.struct_size = sizeof request;
        request.selected_branch = a->select.value_or(-1);
        request.tree = &tree.record();
        DepictionRecord depiction(tree.size());
        if (depictor)
            depict(*depictor, request, depiction, &context.progress);

        const arbor_volume volume_record = in.volume.view();
        arbor_tf_request tf_request{};
        tf_request.struct_size = sizeof tf_request;
        tf_request.tree = &tree.record();
        tf_request.depiction = depictor ? &depiction.record() : nullptr;
        tf_request.volume = &volume_record;
        tf_request.value_range[0] = s.branches.global_min;
        tf_request.value_range[1] = s.branches.global_max;
        const auto &sp = in.volume.geometry().spacing;
        tf_request.min_spacing = std::min({sp[0], sp[1], sp[2]});
        TransferFunctions functions(tree.size(), a->lut_size, tf_request.min_spacing);
        generate_transfer_functions(generator, tf_request, functions, &context.progress);
        const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        const cv::Mat legend = a->legend.empty() ? cv::Mat() : draw_legend(*depictor, request, a->legend_size);

        TransferFunctionFile f;
        f.source = in.source;
        f.simplifier_id = s.id;
        f.cut = a->cut.describe();
        f.generator = &generator;
        f.depictor = depictor;
        f.selected_branch = request.selected_branch;
        f.value_range[0] = tf_request.value_range[0];
        f.value_range[1] = tf_request.value_range[1];
        f.tree = &tree.record();
        f.depiction = depictor ? &depiction.record() : nullptr;
        f.functions = &functions;
        write_transfer_functions(a->output, f);
        if (!a->legend.empty())
            write_png(a->legend, legend);
        std::printf("%s: %u branches kept by %s, transfer functions by %s -> %s\n", in.source.c_str(), tree.size(),
                    s.id.c_str(), generator.id().c_str(), a->output.c_str());
        if (a->timings)
            std::fprintf(stderr, "  %-20s %8.3f s\n  %-20s %8.3f s\n  %-20s %8.6f s\n", "contour tree",
                         topo.total_seconds, "simplification", s.seconds, "depiction + tf", seconds);
        return 0;
    });
}

} // namespace arbor::cli
