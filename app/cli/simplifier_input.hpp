// simplifier_input.hpp - the simplifier plugins a command can use, named on
// the command line by id ("org.arbor.simplifier.itri") or by the id's last
// part ("itri"), with their parameters as flags (--n-measure.measures ...).
#pragma once

#include "cli_context.hpp"
#include "plugin_options.hpp"

#include <string>
#include <vector>

namespace arbor::cli {

class SimplifierInput {
public:
    // Creates an instance of every simplifier plugin and adds their flags.
    void add_to(CLI::App &command, Context &context);
    // The instance `name` stands for, with its flags applied; throws
    // std::invalid_argument listing the simplifiers there are.
    PluginInstance &resolve(const std::string &name);

private:
    std::vector<PluginInstance> simplifiers_;
    PluginOptions options_;
};

// "a,b , c" -> {"a", "b", "c"}.
std::vector<std::string> split_names(const std::string &list);

} // namespace arbor::cli
