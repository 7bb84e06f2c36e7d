// filter_input.hpp - `--filter NAME[:key=value,...]`: a filter plugin (by id
// or the id's last part) applied to the volume before anything else, with
// its parameters inline (`--filter gaussian:sigma=1.5`) or as the generated
// flags (`--gaussian.sigma 1.5`).
#pragma once

#include "plugin_choice.hpp"
#include "volume_input.hpp"

#include <string>

namespace arbor::cli {

class FilterInput {
public:
    void add_to(CLI::App &command, Context &context);
    bool empty() const { return spec_.empty(); }
    const std::string &spec() const { return spec_; }
    // Replaces in.volume by its filtered copy (nothing without --filter);
    // returns the filter's instance or nullptr.  Throws
    // std::invalid_argument for an unknown filter or parameter.
    PluginInstance *apply(LoadedVolume &in, Context &context);

private:
    PluginChoice filters_{ARBOR_KIND_FILTER, "filter"};
    std::string spec_;
};

} // namespace arbor::cli
