#include "plugin_catalog.hpp"

#include "host/param_text.hpp"

#include <stdexcept>

namespace arbor::pipeline {

std::string kind_noun(std::string_view kind)
{
    if (kind == ARBOR_KIND_TF_GENERATOR)
        return "transfer-function generator";
    return std::string(kind);
}

std::string short_name(const std::string &id)
{
    return plugin_short_name(id);
}

std::string PluginCatalog::find(std::string_view kind, const std::string &name) const
{
    if (kind == ARBOR_KIND_RENDERER && name == "auto")
        return renderer_choice().id;
    const std::vector<const PluginInfo *> plugins = registry_.plugins_of_kind(kind);
    std::vector<std::string> sharing;
    for (const PluginInfo *p : plugins) {
        const std::string id = p->descriptor->id;
        if (id == name)
            return id;
        if (short_name(id) == name)
            sharing.push_back(id);
    }
    if (sharing.size() == 1)
        return sharing.front();
    const auto listed = [](const std::vector<std::string> &ids, const char *last) {
        std::string text;
        for (std::size_t i = 0; i < ids.size(); ++i)
            text += (i == 0 ? "" : i + 1 == ids.size() ? last : ", ") + ids[i];
        return text;
    };
    if (sharing.size() > 1)
        throw PluginNameError(kind_noun(kind) + " '" + name + "' is ambiguous: " + listed(sharing, " and ") +
                              (sharing.size() == 2 ? " both" : " all") + " have the short name '" + name + "'; write the full id (" +
                              listed(sharing, " or ") + ")");
    std::vector<std::string> known;
    for (const PluginInfo *p : plugins)
        known.push_back(p->descriptor->id);
    throw PluginNameError("no " + kind_noun(kind) + " '" + name + "' (there are: " +
                          (known.empty() ? "none - see `arbor plugins`" : listed(known, ", ")) + ")");
}

PluginInstance PluginCatalog::create(const std::string &id) const
{
    std::lock_guard lock(mutex_);
    return registry_.create(id);
}

const PluginInstance &PluginCatalog::prototype(const std::string &id) const
{
    auto it = prototypes_.find(id);
    if (it == prototypes_.end())
        it = prototypes_.emplace(id, std::make_unique<PluginInstance>(registry_.create(id))).first;
    return *it->second;
}

std::vector<const arbor_param_desc *> PluginCatalog::descriptions(const std::string &id) const
{
    std::lock_guard lock(mutex_);
    return prototype(id).param_descriptions();
}

PluginSetting PluginCatalog::resolve(std::string_view kind, const PluginSetting &setting) const
{
    PluginSetting out;
    out.id = find(kind, setting.id);
    // A fresh instance: the plugin's own set() checks what the description
    // cannot (and its defaults are the values nobody set).
    PluginInstance instance = create(out.id);
    out.version = instance.descriptor().version;
    apply_setting(instance, setting);
    require_parameters(instance, setting);
    out.params = read_params(instance);
    return out;
}

void apply_setting(PluginInstance &instance, const PluginSetting &setting)
{
    for (const auto &[key, text] : setting.params) {
        const arbor_param_desc *d = instance.find_param(key);
        if (!d) {
            std::string known;
            for (const arbor_param_desc *p : instance.param_descriptions())
                known += (known.empty() ? "" : ", ") + std::string(p->id);
            throw SettingError(SettingError::Problem::Unknown, instance.id(), key,
                               instance.id() + " has no parameter '" + key + "' (it has: " +
                                   (known.empty() ? "none" : known) + ")");
        }
        try {
            const ParamText value = parse_param_value(*d, text);
            instance.set_param(key, value.value);
        } catch (const std::exception &e) {
            throw SettingError(SettingError::Problem::Invalid, instance.id(), key, instance.id() + ": " + e.what());
        }
    }
}

void require_parameters(const PluginInstance &instance, const PluginSetting &setting)
{
    for (const arbor_param_desc *d : instance.param_descriptions())
        if ((d->flags & ARBOR_PARAM_FLAG_REQUIRED) && !setting.params.count(d->id))
            throw SettingError(SettingError::Problem::Missing, instance.id(), d->id,
                               instance.id() + " needs parameter '" + std::string(d->id) + "' (" +
                                   (d->hint && *d->hint ? std::string(d->hint) + "; " : "") +
                                   describe_param_domain(*d) + ")");
}

std::map<std::string, std::string> read_params(const PluginInstance &instance)
{
    std::map<std::string, std::string> out;
    for (const arbor_param_desc *d : instance.param_descriptions())
        out[d->id] = format_param_value(*d, instance.get_param(d->id));
    return out;
}

std::string describe_setting(const PluginSetting &setting, const std::vector<const arbor_param_desc *> &descriptions)
{
    std::string text = short_name(setting.id), sep = ":";
    for (const arbor_param_desc *d : descriptions) {
        const auto it = setting.params.find(d->id);
        if (it == setting.params.end() || it->second == format_param_default(*d))
            continue;
        text += sep + d->id + "=" + it->second;
        sep = ",";
    }
    return text;
}

} // namespace arbor::pipeline
