// look_flags.hpp - the flags that decide which structures are kept and how
// they look: the simplifier and the cut (--simplifier, --keep, --threshold)
// and the appearance (--relation, --select, --generator, --flow-rate,
// --shape, --hues, --lut-size), with every depictor's, generator's and
// simplifier's parameters as flags.  Only the flags given change the
// document.  --simplifier, --keep, --flow-rate, --shape and --hues take comma
// lists (sweeps, sweep.hpp); a SweepPoint picks one value of each.
#pragma once

#include "cli_context.hpp"
#include "plugin_flags.hpp"
#include "sweep.hpp"

#include "pipeline/document.hpp"
#include "pipeline/plugin_catalog.hpp"

#include <optional>
#include <string>
#include <vector>

namespace arbor::cli {

class SimplifierFlags {
public:
    // `choice`: also --simplifier (compare names its simplifiers otherwise).
    void add_to(CLI::App &command, Context &context, bool choice = true);
    std::vector<std::string> names() const { return split(name_); }
    // Sets the simplifier `name` (nullopt: the document's stays) and applies
    // its flags.
    void apply(pipeline::PluginSetting &simplifier, const std::optional<std::string> &name,
               const pipeline::PluginCatalog &catalog) const;
    // Flags for simplifiers of several the command uses are not "ignored".
    void used_with_several() { several_ = true; }

private:
    static std::vector<std::string> split(const std::string &list);
    std::string name_;
    bool several_ = false; // flags may be meant for another of several simplifiers
    PluginFlags flags_;
};

class CutFlags {
public:
    void add_to(CLI::App &command, const std::string &threshold_help);
    bool given() const { return !keep_.empty() || !threshold_.empty(); }
    // The --keep list, each checked to be a whole number >= 1.
    std::vector<std::string> keeps() const;
    // The --threshold list, each checked to lie in [0, 1].
    std::vector<double> thresholds() const;
    // Sets the cut to `keep`, or else to the one --threshold (a list is
    // refused: only a study sweeps thresholds).
    void apply(pipeline::CutChoice &cut, const std::optional<std::string> &keep) const;
    // A study's cuts: one per --keep or --threshold value.
    std::vector<pipeline::CutChoice> cuts() const;

private:
    std::string keep_, threshold_;
    bool keep_background_ = false;
};

class AppearanceFlags {
public:
    void add_to(CLI::App &command, Context &context);
    std::vector<std::string> flow_rates() const;
    std::vector<std::string> shapes() const;
    std::vector<std::string> hues() const;
    bool relation_given() const { return relation_option_->count() > 0; }
    void apply(pipeline::Appearance &look, const SweepPoint &point, const pipeline::PluginCatalog &catalog) const;

private:
    std::string generator_, relation_, flow_rate_, shape_, hues_;
    std::optional<int32_t> select_;
    uint32_t lut_size_ = 256;
    std::string balance_;
    CLI::Option *balance_option_ = nullptr;
    CLI::Option *generator_option_ = nullptr, *relation_option_ = nullptr, *lut_option_ = nullptr;
    PluginFlags depictor_flags_, generator_flags_;
};

} // namespace arbor::cli
