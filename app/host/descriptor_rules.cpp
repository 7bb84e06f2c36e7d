#include "descriptor_rules.hpp"

#include <cmath>
#include <cstring>
#include <set>
#include <string_view>

namespace arbor {

namespace {

bool lower_alnum_or_dash(char c)
{
    return (c >= 'a' && c <= 'z') || (c >= '0' && c <= '9') || c == '-';
}

// A non-empty run of [a-z0-9-] whose first character is a letter (or, when
// digits_first, a letter or a digit).
bool id_part(std::string_view s, bool digits_first)
{
    if (s.empty())
        return false;
    const char c = s.front();
    if (!((c >= 'a' && c <= 'z') || (digits_first && c >= '0' && c <= '9')))
        return false;
    for (char ch : s)
        if (!lower_alnum_or_dash(ch))
            return false;
    return true;
}

// A decimal number without leading zeros.
bool semver_number(std::string_view s)
{
    if (s.empty() || (s.size() > 1 && s.front() == '0'))
        return false;
    for (char c : s)
        if (c < '0' || c > '9')
            return false;
    return true;
}

std::string quoted(const char *s)
{
    return s ? "'" + std::string(s) + "'" : "NULL";
}

} // namespace

std::string check_entry_record(const arbor_plugin_entry *entry)
{
    const arbor_version v = entry->abi_version;
    if (v.major != ARBOR_ABI_VERSION_MAJOR)
        return "was built for Arbor ABI " + std::to_string(v.major) + "." + std::to_string(v.minor) + "." +
               std::to_string(v.patch) + ", this host speaks ABI " + std::to_string(ARBOR_ABI_VERSION_MAJOR) +
               ".x; rebuild it against SDK " + std::to_string(ARBOR_ABI_VERSION_MAJOR) + ".x";
    if (entry->struct_size < ARBOR_MIN_SIZE(arbor_plugin_entry))
        return "entry struct_size " + std::to_string(entry->struct_size) + " is smaller than " +
               std::to_string(ARBOR_MIN_SIZE(arbor_plugin_entry));
    if (!entry->init || !entry->deinit || !entry->plugin_count || !entry->plugin_descriptor || !entry->create_plugin)
        return "entry has NULL functions";
    return "";
}

const std::vector<std::string> &known_plugin_kinds()
{
    static const std::vector<std::string> kinds = {
        ARBOR_KIND_IMPORTER,  ARBOR_KIND_FILTER,       ARBOR_KIND_SIMPLIFIER,
        ARBOR_KIND_DEPICTOR, ARBOR_KIND_TF_GENERATOR, ARBOR_KIND_RENDERER};
    return kinds;
}

const char *kind_interface_id(std::string_view kind)
{
    if (kind == ARBOR_KIND_IMPORTER) return ARBOR_INTERFACE_IMPORTER;
    if (kind == ARBOR_KIND_FILTER) return ARBOR_INTERFACE_FILTER;
    if (kind == ARBOR_KIND_SIMPLIFIER) return ARBOR_INTERFACE_SIMPLIFIER;
    if (kind == ARBOR_KIND_DEPICTOR) return ARBOR_INTERFACE_DEPICTOR;
    if (kind == ARBOR_KIND_TF_GENERATOR) return ARBOR_INTERFACE_TF_GENERATOR;
    if (kind == ARBOR_KIND_RENDERER) return ARBOR_INTERFACE_RENDERER;
    return nullptr;
}

std::string check_plugin_id(const char *id)
{
    if (!id)
        return "plugin id is NULL";
    if (std::strlen(id) > 200)
        return "plugin id is longer than 200 characters";
    std::string_view rest(id);
    int parts = 0;
    bool valid = true;
    for (;;) {
        const std::size_t dot = rest.find('.');
        valid = valid && id_part(rest.substr(0, dot), parts > 0);
        ++parts;
        if (dot == std::string_view::npos)
            break;
        rest.remove_prefix(dot + 1);
    }
    if (!valid || parts < 3)
        return "plugin id " + quoted(id) +
               " is not reverse-DNS (lowercase parts separated by dots, at least three, e.g. "
               "'org.example.filter.median')";
    return "";
}

std::string check_semver(const char *version)
{
    const std::string bad = "version " + quoted(version) + " is not MAJOR.MINOR.PATCH";
    if (!version)
        return bad;
    std::string_view v(version);
    const std::size_t dash = v.find('-');
    if (dash != std::string_view::npos) {
        const std::string_view suffix = v.substr(dash + 1);
        if (suffix.empty())
            return bad;
        for (char c : suffix)
            if (!((c >= '0' && c <= '9') || (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') ||
                  c == '.' || c == '-'))
                return bad;
        v = v.substr(0, dash);
    }
    const std::size_t a = v.find('.');
    const std::size_t b = a == std::string_view::npos ? a : v.find('.', a + 1);
    if (b == std::string_view::npos || !semver_number(v.substr(0, a)) ||
        !semver_number(v.substr(a + 1, b - a - 1)) || !semver_number(v.substr(b + 1)))
        return bad;
    return "";
}

std::string check_descriptor(const arbor_plugin_descriptor *d)
{
    if (!d)
        return "descriptor is NULL";
    if (d->struct_size < ARBOR_MIN_SIZE(arbor_plugin_descriptor))
        return "descriptor struct_size " + std::to_string(d->struct_size) + " is smaller than " +
               std::to_string(ARBOR_MIN_SIZE(arbor_plugin_descriptor));
    if (std::string e = check_plugin_id(d->id); !e.empty())
        return e;
    if (!d->kind)
        return "kind is NULL";
    if (!kind_interface_id(d->kind))
        return "kind '" + std::string(d->kind) + "' is not one this host knows";
    if (!d->name || !*d->name)
        return "name is missing";
    if (std::string e = check_semver(d->version); !e.empty())
        return e;
    if (!d->vendor || !*d->vendor)
        return "vendor is missing";
    if (!d->description)
        return "description is NULL";
    if (!d->url)
        return "url is NULL (use \"\" for none)";
    return "";
}

std::string check_param_id(const char *id)
{
    if (!id || !id_part(id, false))
        return "parameter id " + quoted(id) + " must be lowercase letters, digits and '-'";
    return "";
}

std::string check_param_desc(const arbor_param_desc *d)
{
    if (!d)
        return "parameter description is NULL";
    if (d->struct_size < ARBOR_MIN_SIZE(arbor_param_desc))
        return "parameter description struct_size " + std::to_string(d->struct_size) +
               " is smaller than " + std::to_string(ARBOR_MIN_SIZE(arbor_param_desc));
    if (std::string e = check_param_id(d->id); !e.empty())
        return e;
    const std::string who = "parameter '" + std::string(d->id) + "'";
    if (!d->name || !*d->name)
        return who + ": name is missing";
    if (!d->group || !d->unit || !d->hint)
        return who + ": group, unit and hint must not be NULL (use \"\")";
    switch (d->type) {
    case ARBOR_PARAM_FLOAT:
    case ARBOR_PARAM_INT:
        if (d->components < 1 || d->components > ARBOR_PARAM_MAX_COMPONENTS)
            return who + ": components must lie in 1..4";
        break;
    case ARBOR_PARAM_BOOL:
    case ARBOR_PARAM_CHOICE:
    case ARBOR_PARAM_STRING:
    case ARBOR_PARAM_PATH:
        if (d->components != 1)
            return who + ": components must be 1 for this type";
        break;
    default:
        return who + ": unknown type " + std::to_string(d->type);
    }
    if (d->type == ARBOR_PARAM_STRING || d->type == ARBOR_PARAM_PATH) {
        if (!d->default_text)
            return who + ": default_text is NULL";
        return "";
    }
    if (!std::isfinite(d->min_value) || !std::isfinite(d->max_value) || d->min_value > d->max_value)
        return who + ": range [min, max] is not a finite interval";
    if ((d->flags & ARBOR_PARAM_FLAG_LOG_SCALE) && d->min_value <= 0)
        return who + ": a log-scale parameter needs min > 0";
    if ((d->flags & ARBOR_PARAM_FLAG_COLOR) &&
        (d->type != ARBOR_PARAM_FLOAT || d->components < 3 || d->min_value < 0 || d->max_value > 1))
        return who + ": a colour is a FLOAT with 3 or 4 components in [0, 1]";
    if (d->type == ARBOR_PARAM_CHOICE) {
        if (d->choice_count == 0 || !d->choices)
            return who + ": a choice needs choices";
        std::set<std::string> ids;
        for (uint32_t c = 0; c < d->choice_count; ++c) {
            if (!d->choices[c] || !*d->choices[c])
                return who + ": choice " + std::to_string(c) + " has no id";
            if (!ids.insert(d->choices[c]).second)
                return who + ": choice id '" + d->choices[c] + "' appears twice";
        }
        if (d->min_value != 0 || d->max_value != d->choice_count - 1.0)
            return who + ": a choice's range must be [0, choice_count - 1]";
    }
    if (d->type == ARBOR_PARAM_BOOL && (d->min_value != 0 || d->max_value != 1))
        return who + ": a boolean's range must be [0, 1]";
    for (uint32_t c = 0; c < d->components; ++c) {
        const double v = d->default_value[c];
        if (!std::isfinite(v) || v < d->min_value || v > d->max_value)
            return who + ": default " + std::to_string(v) + " lies outside its range";
        if (d->type != ARBOR_PARAM_FLOAT && v != std::floor(v))
            return who + ": default " + std::to_string(v) + " is not a whole number";
    }
    return "";
}

std::vector<std::string> check_param_set(const arbor_plugin *plugin, const arbor_params_v1 &params)
{
    std::vector<std::string> problems;
    if (!params.count || !params.describe || !params.get || !params.set) {
        problems.push_back("arbor.params/1 has NULL functions");
        return problems;
    }
    const uint32_t n = params.count(plugin);
    if (n > 1000)
        problems.push_back("more than 1000 parameters");
    std::set<std::string> ids;
    for (uint32_t i = 0; i < n && i < 1000; ++i) {
        const arbor_param_desc *d = params.describe(plugin, i);
        if (std::string e = check_param_desc(d); !e.empty()) {
            problems.push_back(e);
            continue;
        }
        if (!ids.insert(d->id).second)
            problems.push_back("parameter id '" + std::string(d->id) + "' appears twice");
    }
    if (params.describe(plugin, n) != nullptr)
        problems.push_back("describe(count) must return NULL");
    return problems;
}

} // namespace arbor
