// plugin_flags.hpp - command-line flags generated from plugin parameter
// descriptions, so no plugin needs CLI code of its own.
//
// Parameter `dims` of plugin `org.arbor.importer.raw` becomes the flag
// `--raw.dims` (the prefix is the last part of the plugin id, or the whole id
// when two plugins of the kind share it).  A given flag writes its text into
// the parameters of the setting of that plugin; the pipeline checks the
// value against the description when the setting is resolved.
#pragma once

#include "pipeline/document.hpp"

#include "host/plugin_registry.hpp"

#include <CLI/CLI.hpp>

#include <map>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

namespace arbor::cli {

class PluginFlags {
public:
    // Adds the flags of every plugin of `kind` to `command`, under `group`
    // ("Simplifier options").
    void add(CLI::App &command, const PluginRegistry &registry, std::string_view kind, const std::string &group);

    // Writes the flags given for setting.id (a full id) into its parameters.
    // Flags given for other plugins of the kind are reported as ignored,
    // unless `quiet` (a sweep applies one set of flags to several plugins).
    void apply(pipeline::PluginSetting &setting, bool quiet = false) const;
    // True when a flag was given for `plugin_id`.
    bool given_for(const std::string &plugin_id) const;
    // The plugins flags were given for.
    std::vector<std::string> given_plugins() const;

    // "--raw.dims", or "" for a parameter without a flag.
    std::string flag_of(const std::string &plugin_id, const std::string &param_id) const;

private:
    struct Flag {
        std::string plugin_id, param_id, name;
        std::shared_ptr<std::string> value;
        CLI::Option *option = nullptr;
    };
    std::vector<Flag> flags_;
};

// The flag every plugin parameter of any kind has on this command line, for
// messages (a pipeline refusal names the parameter; the user typed a flag).
class FlagNames {
public:
    void add(const PluginFlags &flags) { sets_.push_back(&flags); }
    // A flag that sets a parameter of whichever plugin is chosen (--series).
    void add(const std::string &param_id, const std::string &flag) { named_[param_id] = flag; }
    std::string flag_of(const std::string &plugin_id, const std::string &param_id) const;

private:
    std::vector<const PluginFlags *> sets_;
    std::map<std::string, std::string> named_;
};

} // namespace arbor::cli
