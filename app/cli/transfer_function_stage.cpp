#include "transfer_function_stage.hpp"

#include "host/param_text.hpp"

#include <chrono>

namespace arbor::cli {

namespace {

// --flow-rate, --shape and --hues are the generator's parameters of those names.
void set_named(PluginInstance &generator, const std::string &param, const std::string &text)
{
    const arbor_param_desc *d = generator.find_param(param);
    if (!d)
        throw std::invalid_argument(generator.id() + " has no parameter '" + param + "'");
    generator.set_param(param, parse_param_value(*d, text).value);
}

} // namespace

void TransferFunctionStage::add_to(CLI::App &command, Context &context)
{
    command.add_option("--generator", generator_, "Transfer-function generator (residue-flow, histogram-ramp)")
        ->default_val("residue-flow")
        ->group("Transfer functions");
    command.add_option("--flow-rate", flow_rate_, "Flow rate Q (generator parameter flow-rate)")
        ->group("Transfer functions");
    command.add_option("--shape", shape_, "Opacity shape: ramp, inverse-ramp, hat, box, peak")
        ->group("Transfer functions");
    command.add_option("--hues", hues_, "Hue template: full, or i, V, L, I, T, Y, X with :rotation (X:30)")
        ->group("Transfer functions");
    command.add_option("--select", select_, "Selected branch (a label of the simplified tree)")
        ->check(CLI::NonNegativeNumber)
        ->group("Transfer functions");
    command.add_option("--relation", relation_, "Relationship to depict: inclusion, neighbour or none")
        ->check(CLI::IsMember({"inclusion", "neighbour", "none"}))
        ->default_val("inclusion")
        ->group("Transfer functions");
    command.add_option("--lut-size", lut_size_, "Entries of each baked lookup table")
        ->check(CLI::Range(2, 65536))
        ->default_val(256)
        ->group("Transfer functions");
    depictors_.add_to(command, context, "Depictor options");
    generators_.add_to(command, context, "Generator options");
}

void TransferFunctionStage::validate(bool want_legend) const
{
    if (relation_ == "neighbour" && !select_)
        throw std::invalid_argument("--relation neighbour needs --select BRANCH");
    if (want_legend && relation_ == "none")
        throw std::invalid_argument("--legend needs a depictor (--relation neighbour --select BRANCH)");
}

TransferFunctionResult TransferFunctionStage::run(const BranchTreeRecord &tree, const Volume &volume,
                                                  const double value_range[2], Context &context)
{
    TransferFunctionResult r;
    r.generator = &generators_.resolve(generator_);
    r.depictor = relation_ == "none" ? nullptr : &depictors_.resolve(relation_);
    if (flow_rate_)
        set_named(*r.generator, "flow-rate", std::to_string(*flow_rate_));
    if (shape_)
        set_named(*r.generator, "shape", *shape_);
    if (hues_)
        set_named(*r.generator, "hues", *hues_);
    if (select_ && static_cast<uint32_t>(*select_) >= tree.size())
        throw std::invalid_argument("--select " + std::to_string(*select_) + ": the simplified tree has " +
                                    std::to_string(tree.size()) + " branches (0.." + std::to_string(tree.size() - 1) +
                                    ")");
    const auto start = std::chrono::steady_clock::now();
    r.request.struct_size = sizeof r.request;
    r.request.selected_branch = select_.value_or(-1);
    r.request.tree = &tree.record();
    r.depiction = std::make_unique<DepictionRecord>(tree.size());
    if (r.depictor)
        depict(*r.depictor, r.request, *r.depiction, &context.progress, context.stop.get_token());

    const arbor_volume view = volume.view();
    arbor_tf_request tf{};
    tf.struct_size = sizeof tf;
    tf.tree = &tree.record();
    tf.depiction = r.depictor ? &r.depiction->record() : nullptr;
    tf.volume = &view;
    tf.value_range[0] = r.value_range[0] = value_range[0];
    tf.value_range[1] = r.value_range[1] = value_range[1];
    const auto &sp = volume.geometry().spacing;
    tf.min_spacing = std::min({sp[0], sp[1], sp[2]});
    r.functions = std::make_unique<TransferFunctions>(tree.size(), lut_size_, tf.min_spacing);
    generate_transfer_functions(*r.generator, tf, *r.functions, &context.progress, context.stop.get_token());
    r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    return r;
}

cv::Mat TransferFunctionStage::legend(PluginInstance &depictor, const arbor_depiction_request &request,
                                      int size) const
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
            for (int c = 0; c < 3; ++c) // premultiplied, over white
                bgr.at<cv::Vec3b>(y, x)[2 - c] =
                    static_cast<uint8_t>(std::clamp(p[c] + (1.0f - p[3]), 0.0f, 1.0f) * 255.0f + 0.5f);
        }
    return bgr;
}

} // namespace arbor::cli
