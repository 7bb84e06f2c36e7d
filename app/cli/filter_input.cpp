#include "filter_input.hpp"

#include "host/filter_run.hpp"
#include "host/param_text.hpp"

namespace arbor::cli {

void FilterInput::add_to(CLI::App &command, Context &context)
{
    command
        .add_option("--filter", spec_,
                    "Denoise first: NAME[:key=value,...], e.g. gaussian:sigma=1.5, median:size=3, "
                    "bilateral, nlmeans:h=0.05")
        ->group("Input");
    filters_.add_to(command, context, "Filter options");
}

PluginInstance *FilterInput::apply(LoadedVolume &in, Context &context)
{
    if (spec_.empty())
        return nullptr;
    const std::size_t colon = spec_.find(':');
    PluginInstance &filter = filters_.resolve(spec_.substr(0, colon));
    if (colon != std::string::npos)
        for (const std::string &pair : split_names(spec_.substr(colon + 1))) {
            const std::size_t eq = pair.find('=');
            if (eq == std::string::npos)
                throw std::invalid_argument("--filter " + spec_ + ": '" + pair + "' is not key=value");
            const std::string key = pair.substr(0, eq);
            const arbor_param_desc *d = filter.find_param(key);
            if (!d) {
                std::string known;
                for (const arbor_param_desc *p : filter.param_descriptions())
                    known += (known.empty() ? "" : ", ") + std::string(p->id);
                throw std::invalid_argument("--filter " + spec_ + ": " + filter.id() + " has no parameter '" + key +
                                            "' (it has: " + known + ")");
            }
            filter.set_param(key, parse_param_value(*d, pair.substr(eq + 1)).value);
        }
    in.volume = run_filter(filter, in.volume, &context.progress, context.max_volume_bytes, context.stop.get_token());
    in.source += " | " + spec_;
    return &filter;
}

} // namespace arbor::cli
