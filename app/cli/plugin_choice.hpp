// plugin_choice.hpp - the plugins of one kind a command can use (simplifiers,
// depictors, transfer-function generators), named on the command line by id
// ("org.arbor.simplifier.itri") or by the id's last part ("itri"), with
// their parameters as flags (--n-measure.measures ...).
#pragma once

#include "cli_context.hpp"
#include "plugin_options.hpp"

#include <string>
#include <vector>

namespace arbor::cli {

class PluginChoice {
public:
    // kind: ARBOR_KIND_*; noun: how messages call one ("simplifier").
    PluginChoice(std::string kind, std::string noun) : kind_(std::move(kind)), noun_(std::move(noun)) {}

    // Creates an instance of every plugin of the kind and adds their flags
    // under `group` ("Simplifier options").
    void add_to(CLI::App &command, Context &context, const std::string &group);
    // The instance `name` stands for, with its flags applied; throws
    // std::invalid_argument listing the plugins of the kind there are.
    PluginInstance &resolve(const std::string &name);

private:
    std::string kind_, noun_;
    std::vector<PluginInstance> plugins_;
    PluginOptions options_;
};

// "a,b , c" -> {"a", "b", "c"}.
std::vector<std::string> split_names(const std::string &list);

} // namespace arbor::cli
