// plugin_flags.hpp - command-line flags generated from plugin parameter
// descriptions, so no plugin needs CLI code of its own.
//
// Parameter `dims` of plugin `org.arbor.importer.raw` becomes the flag
// `--raw.dims`: the prefix is the plugin's short name, the last part of its
// id, whatever else is installed.  The full id always works too
// (`--org.arbor.importer.raw.dims`, not listed by --help).  When two loaded
// plugins, of any kind, share a short name, only the full-id flags are
// listed, and a flag written with the short name is refused (exit 2) with a
// message naming both plugins and the flags to write instead.  A given flag
// writes its text into the parameters of the setting of that plugin; the
// pipeline checks the value against the description when the setting is
// resolved.
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

    // The flag --help lists ("--raw.dims", or "--org.arbor.importer.raw.dims"
    // when the short name is shared), or "" for a parameter without a flag.
    std::string flag_of(const std::string &plugin_id, const std::string &param_id) const;

private:
    struct Flag {
        std::string plugin_id, param_id, name;
        // The short form (when the short name is the plugin's alone) and the
        // full-id form; value() throws UsageError when both are given.
        std::shared_ptr<std::string> short_value, full_value;
        CLI::Option *short_option = nullptr, *full_option = nullptr;
        bool given() const;
        const std::string &value() const;
    };
    std::vector<Flag> flags_;
};

// The names a plugin flag (--simplifier) takes, for its --help: the short
// names of the plugins of `kind` loaded now, third parties' included, and
// the full ids of those whose short name another plugin of the kind shares
// ("itri, n-measure, persistence, ...").
std::string plugin_names(const PluginRegistry &registry, std::string_view kind);

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
