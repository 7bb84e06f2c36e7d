#include "look_flags.hpp"

#include "input_flags.hpp"
#include "usage_error.hpp"

#include <cmath>
#include <stdexcept>

namespace arbor::cli {

std::vector<std::string> SimplifierFlags::split(const std::string &list)
{
    return split_list(list);
}

void SimplifierFlags::add_to(CLI::App &command, Context &context, bool choice)
{
    if (choice)
        command
            .add_option("--simplifier", name_,
                        "Simplifier plugin, by short name or id (loaded: " +
                            plugin_names(context.registry, ARBOR_KIND_SIMPLIFIER) +
                            "); default itri; `arbor run` sweeps a comma list")
            ->type_name("NAME[,NAME...]");
    flags_.add(command, context.registry, ARBOR_KIND_SIMPLIFIER, "Simplifier options");
    context.flag_names.add(flags_);
}

void SimplifierFlags::apply(pipeline::PluginSetting &simplifier, const std::optional<std::string> &name,
                            const pipeline::PluginCatalog &catalog) const
{
    if (name)
        simplifier = {catalog.find(ARBOR_KIND_SIMPLIFIER, *name), "", {}};
    else if (!simplifier.id.empty())
        simplifier.id = catalog.find(ARBOR_KIND_SIMPLIFIER, simplifier.id);
    flags_.apply(simplifier, several_ || names().size() > 1);
}

void CutFlags::add_to(CLI::App &command, const std::string &threshold_help)
{
    auto *keep = command
                     .add_option("--keep", keep_,
                                 "Keep the N most important branches (root included); `arbor run` and `arbor compare` sweep a comma list")
                     ->type_name("N[,N...]");
    auto *threshold = command.add_option("--threshold", threshold_, threshold_help)->type_name("T");
    keep->excludes(threshold);
    command.add_flag("--keep-background", keep_background_,
                     "Also keep basins and bumps that lie wholly in the background's values (the noise in the "
                     "air), which are left out by default");
}

std::vector<std::string> CutFlags::keeps() const
{
    std::vector<std::string> out = split_list(keep_);
    for (const std::string &k : out) {
        char *end = nullptr;
        const double n = std::strtod(k.c_str(), &end);
        if (*end || !(n >= 1) || n != std::floor(n) || n > 1e9)
            throw UsageError("--keep " + k + ": a number of branches, 1 or more");
    }
    return out;
}

std::vector<double> CutFlags::thresholds() const
{
    std::vector<double> out;
    for (const std::string &t : split_list(threshold_)) {
        char *end = nullptr;
        const double x = std::strtod(t.c_str(), &end);
        if (*end || !(x >= 0 && x <= 1))
            throw UsageError("--threshold " + t + ": a relative importance in [0, 1]");
        out.push_back(x);
    }
    return out;
}

void CutFlags::apply(pipeline::CutChoice &cut, const std::optional<std::string> &keep) const
{
    const std::vector<double> levels = thresholds();
    if (levels.size() > 1)
        throw UsageError("--threshold takes one value here (`arbor compare` sweeps a list)");
    if (keep) {
        cut.keep = std::stoull(*keep);
        cut.threshold.reset();
    } else if (!levels.empty()) {
        cut.threshold = levels[0];
        cut.keep.reset();
    }
    if (keep_background_)
        cut.keep_background = true;
}

std::vector<pipeline::CutChoice> CutFlags::cuts() const
{
    std::vector<pipeline::CutChoice> out;
    for (const std::string &k : keeps()) {
        pipeline::CutChoice c;
        c.keep = std::stoull(k);
        out.push_back(c);
    }
    for (const double t : thresholds()) {
        pipeline::CutChoice c;
        c.threshold = t;
        out.push_back(c);
    }
    for (pipeline::CutChoice &c : out)
        c.keep_background = keep_background_;
    for (std::size_t i = 0; i < out.size(); ++i)
        for (std::size_t j = 0; j < i; ++j)
            if (out[i] == out[j])
                throw UsageError("the cut " + out[i].describe() + " is given twice");
    return out;
}

void AppearanceFlags::add_to(CLI::App &command, Context &context)
{
    generator_option_ =
        command.add_option("--generator", generator_,
                           "Transfer-function generator, by short name or id (loaded: " +
                               plugin_names(context.registry, ARBOR_KIND_TF_GENERATOR) + "); default residue-flow")
            ->group("Transfer functions");
    command.add_option("--flow-rate", flow_rate_, "Flow rate Q (the generator's parameter flow-rate); `arbor run` sweeps a comma list")
        ->type_name("Q[,Q...]")
        ->group("Transfer functions");
    command.add_option("--shape", shape_, "Opacity shape: ramp, inverse-ramp, hat, box, peak; `arbor run` sweeps a comma list")
        ->type_name("SHAPE[,SHAPE...]")
        ->group("Transfer functions");
    command.add_option("--hues", hues_, "Hue template: auto (by tissue on a CT, else full), full, or i, V, L, I, T, Y, X with :rotation (X:30); `arbor run` sweeps a comma list")
        ->type_name("HUES[,HUES...]")
        ->group("Transfer functions");
    command.add_option("--select", select_, "Selected branch (a label of the simplified tree)")
        ->check(CLI::NonNegativeNumber)
        ->group("Transfer functions");
    relation_option_ = command.add_option("--relation", relation_,
                                          "Relationship to depict: a depictor by short name or id (loaded: " +
                                              plugin_names(context.registry, ARBOR_KIND_DEPICTOR) +
                                              "), or none; default inclusion")
                           ->group("Transfer functions");
    lut_option_ = command.add_option("--lut-size", lut_size_, "Entries of each baked lookup table (default 256)")
                      ->check(CLI::Range(2, 65536))
                      ->group("Transfer functions");
    balance_option_ = command.add_option("--balance", balance_,
                                         "on: scale each structure's opacity until the picture gives every one its "
                                         "share (default); off: the generator's opacities as they are")
                          ->check(CLI::IsMember({"on", "off"}))
                          ->group("Transfer functions");
    depictor_flags_.add(command, context.registry, ARBOR_KIND_DEPICTOR, "Depictor options");
    generator_flags_.add(command, context.registry, ARBOR_KIND_TF_GENERATOR, "Generator options");
    context.flag_names.add(depictor_flags_);
    context.flag_names.add(generator_flags_);
}

std::vector<std::string> AppearanceFlags::flow_rates() const
{
    return split_list(flow_rate_);
}

std::vector<std::string> AppearanceFlags::shapes() const
{
    return split_list(shape_);
}

std::vector<std::string> AppearanceFlags::hues() const
{
    return split_list(hues_);
}

void AppearanceFlags::apply(pipeline::Appearance &look, const SweepPoint &point,
                            const pipeline::PluginCatalog &catalog) const
{
    if (relation_option_->count()) {
        look.depictor = relation_ == "none" ? pipeline::PluginSetting{}
                                            : pipeline::PluginSetting{catalog.find(ARBOR_KIND_DEPICTOR, relation_), "", {}};
    } else if (!look.depictor.id.empty()) {
        look.depictor.id = catalog.find(ARBOR_KIND_DEPICTOR, look.depictor.id);
    }
    if (!look.depictor.empty())
        depictor_flags_.apply(look.depictor);
    if (select_)
        look.selected = *select_;
    if (look.depictor.empty() && look.selected && relation_option_->count() && relation_ == "none")
        throw UsageError("--select needs a relationship to depict (--relation inclusion or neighbour)");
    if (!look.depictor.empty() && pipeline::short_name(look.depictor.id) == "neighbour" && !look.selected)
        throw UsageError("--relation neighbour needs --select BRANCH");

    if (generator_option_->count())
        look.generator = {catalog.find(ARBOR_KIND_TF_GENERATOR, generator_), "", {}};
    else if (!look.generator.id.empty())
        look.generator.id = catalog.find(ARBOR_KIND_TF_GENERATOR, look.generator.id);
    generator_flags_.apply(look.generator);
    // --flow-rate, --shape and --hues are the generator's parameters of those names.
    if (point.flow_rate)
        look.generator.params["flow-rate"] = *point.flow_rate;
    if (point.shape)
        look.generator.params["shape"] = *point.shape;
    if (point.hues)
        look.generator.params["hues"] = *point.hues;
    if (lut_option_->count())
        look.lut_size = lut_size_;
    if (balance_option_->count())
        look.balance_visibility = balance_ == "on";
}

} // namespace arbor::cli
