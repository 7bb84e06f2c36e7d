// input_flags.hpp - the flags that choose what a command works on: a file or
// folder read by an importer (chosen by probing, by --importer, or by the
// importer whose flags were given), or the built-in phantom; the filter
// chain applied before anything else; --no-cache.  Only the flags given
// change the document, so they override a session's choices.
#pragma once

#include "cli_context.hpp"
#include "plugin_flags.hpp"

#include "pipeline/document.hpp"
#include "pipeline/plugin_catalog.hpp"

#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace arbor::cli {

class InputFlags {
public:
    // Adds the positional <volume>, --phantom*, --importer, --series, the
    // importer flags and --no-cache.
    void add_to(CLI::App &command, Context &context);
    bool given() const;
    // Throws std::invalid_argument naming the flag.
    void apply(pipeline::InputChoice &input, const pipeline::PluginCatalog &catalog) const;
    bool no_cache() const { return no_cache_; }

private:
    std::string path_, phantom_, importer_, series_;
    int64_t phantom_size_ = 128;
    double phantom_noise_ = 0.0;
    int phantom_blobs_ = 0;
    uint64_t phantom_seed_ = 1;
    CLI::Option *path_option_ = nullptr, *phantom_option_ = nullptr, *size_option_ = nullptr,
                *noise_option_ = nullptr, *blobs_option_ = nullptr, *seed_option_ = nullptr,
                *importer_option_ = nullptr, *series_option_ = nullptr;
    bool no_cache_ = false;
    PluginFlags importer_flags_;
    const PluginRegistry *registry_ = nullptr;
};

// --filter NAME[:key=value,...] (repeatable: a chain, applied in order), or
// --filter none; each filter's parameters also as flags (--gaussian.sigma).
// Without --filter the pipeline denoises automatically when noise dominates.
class FilterFlags {
public:
    // `help`: the --filter text when the command reads it otherwise (a
    // study's settings, sweep_chains()).
    void add_to(CLI::App &command, Context &context, const std::string &help = {});
    bool given() const { return !specs_.empty(); }
    // With --filter: the chain given (and no automatic denoising).  Without:
    // the filter flags apply to the filters of the chain there is (a session's).
    void apply(std::vector<pipeline::PluginSetting> &chain, bool &auto_denoise,
               const pipeline::PluginCatalog &catalog) const;

    // A study's reading: each --filter is one setting of the sweep, its
    // filters joined by '+' ("median:size=3+gaussian:sigma=1"), "none" the
    // unfiltered data; the filter flags apply to every chain.  One empty
    // chain without --filter.  Each with its text as given ("none" for none).
    std::vector<std::pair<std::string, std::vector<pipeline::PluginSetting>>>
    sweep_chains(const pipeline::PluginCatalog &catalog) const;

private:
    void apply_flags(std::vector<pipeline::PluginSetting> &chain, bool given) const;
    std::vector<std::string> specs_;
    PluginFlags flags_;
};

// "median:size=3+gaussian:sigma=1e+3" -> {"median:size=3", "gaussian:sigma=1e+3"}:
// a '+' joins filters where a plugin name (a letter) follows it.
std::vector<std::string> split_filter_chain(const std::string &spec);

using pipeline::parse_plugin_spec; // "gaussian:sigma=1.5,radius=2" -> the setting (id as given)

// "a,b , c" -> {"a", "b", "c"}.
std::vector<std::string> split_list(const std::string &list);

} // namespace arbor::cli
