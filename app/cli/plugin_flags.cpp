#include "plugin_flags.hpp"

#include "usage_error.hpp"

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

// What a flag written with a short name that several plugins share says.
std::string shared_short_name_message(const std::string &short_name, const std::string &param_id,
                                      const std::vector<const PluginInfo *> &sharing,
                                      const std::map<std::string, std::vector<std::string>> &params_of)
{
    std::string ids, flags;
    for (std::size_t i = 0; i < sharing.size(); ++i) {
        const std::string id = sharing[i]->descriptor->id;
        ids += (i == 0 ? "" : i + 1 == sharing.size() ? " and " : ", ") + id;
        const auto it = params_of.find(id);
        if (it != params_of.end() && std::count(it->second.begin(), it->second.end(), param_id))
            flags += (flags.empty() ? "" : " or ") + ("--" + id + "." + param_id);
    }
    return "'" + short_name + "' is the short name of " + ids + "; write the full id" +
           (flags.empty() ? "" : ": " + flags);
}

} // namespace

bool PluginFlags::Flag::given() const
{
    return (short_option && short_option->count() > 0) || full_option->count() > 0;
}

const std::string &PluginFlags::Flag::value() const
{
    if (short_option && short_option->count() > 0 && full_option->count() > 0)
        throw UsageError(name + " and --" + plugin_id + "." + param_id + " set the same parameter: give one");
    return full_option->count() > 0 ? *full_value : *short_value;
}

void PluginFlags::add(CLI::App &command, const PluginRegistry &registry, std::string_view kind,
                      const std::string &group)
{
    struct Described {
        std::string param_id, help, type;
    };
    // An instance of each plugin only to read its descriptions (the strings
    // are copied); also of every plugin that shares a short name with one of
    // this kind, for the message a flag written with that name gives.
    std::map<std::string, std::vector<Described>> described;
    std::map<std::string, std::vector<std::string>> params_of;
    const auto describe = [&](const std::string &id) {
        if (params_of.count(id))
            return;
        std::vector<std::string> &ids = params_of[id];
        try {
            const PluginInstance instance = registry.create(id);
            for (const arbor_param_desc *d : instance.param_descriptions()) {
                ids.push_back(d->id);
                described[id].push_back({d->id, help_text(*d), type_name(*d)});
            }
        } catch (const PluginError &e) {
            log_message(ARBOR_LOG_WARNING, "", e.what());
        }
    };
    for (const PluginInfo *p : registry.plugins_of_kind(kind)) {
        const std::string id = p->descriptor->id, short_name = plugin_short_name(id);
        const std::vector<const PluginInfo *> sharing = registry.sharing_short_name(short_name);
        for (const PluginInfo *other : sharing)
            describe(other->descriptor->id);
        for (const Described &d : described[id]) {
            const std::string full = "--" + id + "." + d.param_id, brief = "--" + short_name + "." + d.param_id;
            Flag f{id, d.param_id, full, std::make_shared<std::string>(), std::make_shared<std::string>(), nullptr,
                   nullptr};
            f.full_option = command.add_option(full, *f.full_value, d.help);
            f.full_option->type_name(d.type);
            if (sharing.size() == 1) {
                f.name = brief;
                f.short_option = command.add_option(brief, *f.short_value, d.help);
                f.short_option->group(group + " (" + id + ")");
                f.short_option->type_name(d.type);
                f.full_option->group(""); // accepted, not listed
            } else {
                f.full_option->group(group + " (" + id + ")");
                if (!command.get_option_no_throw(brief)) {
                    // Listed nowhere; refused, with the way out, when given.
                    const std::string refusal = shared_short_name_message(short_name, d.param_id, sharing, params_of);
                    command
                        .add_option_function<std::string>(
                            brief, [brief, refusal](const std::string &) { throw CLI::ValidationError(brief, refusal); })
                        ->group("");
                }
            }
            flags_.push_back(std::move(f));
        }
    }
}

void PluginFlags::apply(pipeline::PluginSetting &setting, bool quiet) const
{
    for (const Flag &f : flags_) {
        if (!f.given())
            continue;
        if (f.plugin_id == setting.id)
            setting.params[f.param_id] = f.value();
        else if (!quiet)
            log_message(ARBOR_LOG_WARNING, "", f.name + " is for " + f.plugin_id + ", not " + setting.id + "; ignored");
    }
}

bool PluginFlags::given_for(const std::string &plugin_id) const
{
    for (const Flag &f : flags_)
        if (f.plugin_id == plugin_id && f.given())
            return true;
    return false;
}

std::vector<std::string> PluginFlags::given_plugins() const
{
    std::vector<std::string> out;
    for (const Flag &f : flags_)
        if (f.given() && std::find(out.begin(), out.end(), f.plugin_id) == out.end())
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

std::string plugin_names(const PluginRegistry &registry, std::string_view kind)
{
    const std::vector<const PluginInfo *> plugins = registry.plugins_of_kind(kind);
    std::map<std::string, int> uses;
    for (const PluginInfo *p : plugins)
        ++uses[plugin_short_name(p->descriptor->id)];
    std::vector<std::string> names;
    for (const PluginInfo *p : plugins) {
        const std::string id = p->descriptor->id, short_name = plugin_short_name(id);
        names.push_back(uses[short_name] == 1 ? short_name : id);
    }
    std::sort(names.begin(), names.end());
    std::string text;
    for (const std::string &n : names)
        text += (text.empty() ? "" : ", ") + n;
    return text.empty() ? "none installed" : text;
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
