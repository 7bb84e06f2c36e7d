#include "plugin_flags.hpp"

#include "host/param_text.hpp"
#include "pipeline/plugin_catalog.hpp"

#include <algorithm>
#include <optional>

namespace arbor::cli {

namespace {

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

const char *type_name(const arbor_param_desc &d)
{
    switch (d.type) {
    case ARBOR_PARAM_CHOICE: return "CHOICE";
    case ARBOR_PARAM_BOOL: return "BOOL";
    case ARBOR_PARAM_STRING: return "TEXT";
    case ARBOR_PARAM_PATH: return "PATH";
    default: return d.components > 1 ? "N,N,..." : "NUMBER";
    }
}

} // namespace

void PluginFlags::add(CLI::App &command, const PluginRegistry &registry, std::string_view kind,
                      const std::string &group)
{
    const std::vector<const PluginInfo *> plugins = registry.plugins_of_kind(kind);
    std::map<std::string, int> uses;
    for (const PluginInfo *p : plugins)
        ++uses[pipeline::short_name(p->descriptor->id)];
    for (const PluginInfo *p : plugins) {
        const std::string id = p->descriptor->id;
        const std::string prefix = uses[pipeline::short_name(id)] > 1 ? id : pipeline::short_name(id);
        // An instance only to read the descriptions; the strings are copied.
        std::optional<PluginInstance> instance;
        try {
            instance.emplace(registry.create(id));
        } catch (const PluginError &e) {
            log_message(ARBOR_LOG_WARNING, "", e.what());
            continue;
        }
        for (const arbor_param_desc *d : instance->param_descriptions()) {
            Flag f{id, d->id, "--" + prefix + "." + d->id, std::make_shared<std::string>(), nullptr};
            f.option = command.add_option(f.name, *f.value, help_text(*d));
            f.option->group(group + " (" + id + ")");
            f.option->type_name(type_name(*d));
            flags_.push_back(std::move(f));
        }
    }
}

void PluginFlags::apply(pipeline::PluginSetting &setting, bool quiet) const
{
    for (const Flag &f : flags_) {
        if (f.option->count() == 0)
            continue;
        if (f.plugin_id == setting.id)
            setting.params[f.param_id] = *f.value;
        else if (!quiet)
            log_message(ARBOR_LOG_WARNING, "", f.name + " is for " + f.plugin_id + ", not " + setting.id + "; ignored");
    }
}

bool PluginFlags::given_for(const std::string &plugin_id) const
{
    for (const Flag &f : flags_)
        if (f.plugin_id == plugin_id && f.option->count() > 0)
            return true;
    return false;
}

std::vector<std::string> PluginFlags::given_plugins() const
{
    std::vector<std::string> out;
    for (const Flag &f : flags_)
        if (f.option->count() > 0 && std::find(out.begin(), out.end(), f.plugin_id) == out.end())
            out.push_back(f.plugin_id);
    return out;
}

std::string PluginFlags::flag_of(const std::string &plugin_id, const std::string &param_id) const
{
    for (const Flag &f : flags_)
        if (f.plugin_id == plugin_id && f.param_id == param_id)
            return f.name;
    return {};
}

std::string FlagNames::flag_of(const std::string &plugin_id, const std::string &param_id) const
{
    if (const auto it = named_.find(param_id); it != named_.end())
        return it->second;
    for (const PluginFlags *s : sets_)
        if (std::string f = s->flag_of(plugin_id, param_id); !f.empty())
            return f;
    return {};
}

} // namespace arbor::cli
