#include "plugin_options.hpp"

#include "host/param_text.hpp"

namespace arbor::cli {

namespace {

std::string last_part(const std::string &id)
{
    const auto dot = id.rfind('.');
    return dot == std::string::npos ? id : id.substr(dot + 1);
}

std::string help_text(const arbor_param_desc &d)
{
    std::string h = d.hint && *d.hint ? d.hint : d.name;
    if (d.unit && *d.unit)
        h += " [" + std::string(d.unit) + "]";
    h += "; " + describe_param_domain(d);
    if (d.flags & ARBOR_PARAM_FLAG_REQUIRED)
        h += "; required";
    else if (d.type != ARBOR_PARAM_STRING && d.type != ARBOR_PARAM_PATH)
        h += "; default " + format_param_default(d);
    else if (d.default_text && *d.default_text)
        h += "; default " + std::string(d.default_text);
    return h;
}

} // namespace

void PluginOptions::add(CLI::App &command, const std::string &group,
                        std::vector<PluginInstance *> instances)
{
    std::map<std::string, int> uses;
    for (const PluginInstance *p : instances)
        ++uses[last_part(p->id())];
    for (PluginInstance *p : instances) {
        const std::string id = p->id();
        const std::string prefix = uses[last_part(id)] > 1 ? id : last_part(id);
        prefixes_[id] = prefix;
        for (const arbor_param_desc *d : p->param_descriptions()) {
            Flag f{id, d->id, "--" + prefix + "." + d->id, std::make_shared<std::string>(), nullptr};
            f.option = command.add_option(f.flag, *f.value, help_text(*d));
            f.option->group(group + " (" + id + ")");
            const std::string type = d->type == ARBOR_PARAM_CHOICE ? "CHOICE"
                                     : d->type == ARBOR_PARAM_BOOL ? "BOOL"
                                     : d->type == ARBOR_PARAM_STRING ? "TEXT"
                                     : d->type == ARBOR_PARAM_PATH ? "PATH"
                                     : d->components > 1 ? "N,N,..." : "NUMBER";
            f.option->type_name(type);
            flags_.push_back(std::move(f));
        }
    }
}

void PluginOptions::apply(PluginInstance &instance) const
{
    const std::string id = instance.id();
    for (const Flag &f : flags_) {
        if (f.option->count() == 0)
            continue;
        if (f.plugin_id != id) {
            log_message(ARBOR_LOG_WARNING, "",
                        f.flag + " is for " + f.plugin_id + ", not " + id + "; ignored");
            continue;
        }
        const arbor_param_desc *d = instance.find_param(f.param_id);
        ParamText value = parse_param_value(*d, *f.value);
        instance.set_param(f.param_id, value.value);
    }
    // A required parameter nobody gave: name the flag, not the parameter.
    for (const Flag &f : flags_) {
        if (f.plugin_id != id || f.option->count() > 0)
            continue;
        const arbor_param_desc *d = instance.find_param(f.param_id);
        if (d && (d->flags & ARBOR_PARAM_FLAG_REQUIRED))
            throw std::invalid_argument(id + " needs " + f.flag + " (" + help_text(*d) + ")");
    }
}

std::string PluginOptions::prefix_of(const std::string &plugin_id) const
{
    const auto it = prefixes_.find(plugin_id);
    return it == prefixes_.end() ? last_part(plugin_id) : it->second;
}

} // namespace arbor::cli
