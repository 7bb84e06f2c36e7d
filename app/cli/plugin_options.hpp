// plugin_options.hpp - command-line flags generated from plugin parameter
// descriptions, so no plugin needs CLI code of its own.
//
// Parameter `dims` of plugin `org.arbor.importer.raw` becomes the flag
// `--raw.dims` (the prefix is the last part of the plugin id, or the whole id
// when two plugins of the set share it).  Values are parsed and checked
// against the description (param_text.hpp) when they are applied.
#pragma once

#include "host/plugin_instance.hpp"

#include <CLI/CLI.hpp>

#include <map>
#include <memory>
#include <string>
#include <vector>

namespace arbor::cli {

class PluginOptions {
public:
    // Adds the flags of every instance to `command`; instances must outlive
    // this object.  `group` titles the section in --help ("Importer options").
    void add(CLI::App &command, const std::string &group, std::vector<PluginInstance *> instances);

    // Sets the parameters given on the command line on `instance`; warns about
    // flags given for other plugins of the set (they are ignored).  Throws
    // std::invalid_argument for a value its description refuses and for a
    // REQUIRED parameter whose flag is missing.
    void apply(PluginInstance &instance) const;

    // The flag prefix of a plugin ("raw" for org.arbor.importer.raw).
    std::string prefix_of(const std::string &plugin_id) const;

private:
    struct Flag {
        std::string plugin_id;
        std::string param_id;
        std::string flag;
        std::shared_ptr<std::string> value;
        CLI::Option *option = nullptr;
    };
    std::vector<Flag> flags_;
    std::map<std::string, std::string> prefixes_;
};

} // namespace arbor::cli
