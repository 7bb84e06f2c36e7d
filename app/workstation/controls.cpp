#include "controls.hpp"

#include <cmath>
#include <functional>
#include <map>
#include <stdexcept>

namespace arbor::workstation {

namespace {

using pipeline::Document;
using pipeline::PluginSetting;

double number(const std::string &name, const std::string &text) { return parse_number(text, name); }

bool boolean(const std::string &name, const std::string &text)
{
    if (text == "true" || text == "on" || text == "1" || text == "yes")
        return true;
    if (text == "false" || text == "off" || text == "0" || text == "no")
        return false;
    throw std::invalid_argument(name + ": '" + text + "' is not true or false");
}

std::string yes_no(bool b) { return b ? "true" : "false"; }

std::string number_text(double x)
{
    char buf[64];
    std::snprintf(buf, sizeof buf, "%.10g", x);
    return buf;
}

// A plugin chosen by name; its parameters start at their defaults.
PluginSetting plugin_named(const std::string &text) { return PluginSetting{text, "", {}}; }

struct Builtin {
    std::function<void(Document &, const std::string &)> set;
    std::function<std::string(const Document &)> get;
};

const std::map<std::string, Builtin> &builtins()
{
    static const std::map<std::string, Builtin> table = {
        {"keep",
         {[](Document &d, const std::string &t) {
              if (t == "knee") {
                  d.cut.keep.reset();
                  d.cut.threshold.reset();
                  return;
              }
              const double n = number("keep", t);
              if (n < 1 || n != std::floor(n) || n > 1e9)
                  throw std::invalid_argument("keep: '" + t + "' is not a branch count >= 1 (or \"knee\")");
              d.cut.keep = static_cast<std::size_t>(n);
              d.cut.threshold.reset();
          },
          [](const Document &d) { return d.cut.keep ? std::to_string(*d.cut.keep) : std::string("knee"); }}},
        {"threshold",
         {[](Document &d, const std::string &t) {
              const double x = number("threshold", t);
              if (x < 0 || x > 1)
                  throw std::invalid_argument("threshold: " + t + " is outside [0, 1]");
              d.cut.threshold = x;
              d.cut.keep.reset();
          },
          [](const Document &d) { return d.cut.threshold ? number_text(*d.cut.threshold) : std::string("none"); }}},
        {"keep-background",
         {[](Document &d, const std::string &t) { d.cut.keep_background = boolean("keep-background", t); },
          [](const Document &d) { return yes_no(d.cut.keep_background); }}},
        {"simplifier",
         {[](Document &d, const std::string &t) { d.simplifier = plugin_named(t); },
          [](const Document &d) { return pipeline::short_name(d.simplifier.id); }}},
        {"relation",
         {[](Document &d, const std::string &t) {
              d.appearance.depictor = t == "none" ? PluginSetting{} : plugin_named(t);
          },
          [](const Document &d) {
              return d.appearance.depictor.empty() ? std::string("none") : pipeline::short_name(d.appearance.depictor.id);
          }}},
        {"legend",
         {[](Document &d, const std::string &t) { d.appearance.legend = t == "none" ? PluginSetting{} : plugin_named(t); },
          [](const Document &d) {
              return d.appearance.legend.empty() ? std::string("none") : pipeline::short_name(d.appearance.legend.id);
          }}},
        {"generator",
         {[](Document &d, const std::string &t) { d.appearance.generator = plugin_named(t); },
          [](const Document &d) { return pipeline::short_name(d.appearance.generator.id); }}},
        {"renderer",
         {[](Document &d, const std::string &t) { d.view.renderer = plugin_named(t); },
          [](const Document &d) { return pipeline::short_name(d.view.renderer.id); }}},
        {"filter",
         {[](Document &d, const std::string &t) {
              std::vector<PluginSetting> chain;
              if (t != "auto" && t != "none")
                  chain.push_back(pipeline::parse_plugin_spec(t, "filter")); // throws before anything changes
              d.filters = std::move(chain);
              d.auto_denoise = t == "auto";
          },
          [](const Document &d) {
              if (d.filters.empty())
                  return std::string(d.auto_denoise ? "auto" : "none");
              return pipeline::short_name(d.filters.front().id);
          }}},
        {"select",
         {[](Document &d, const std::string &t) {
              if (t == "none") {
                  d.appearance.selected.reset();
                  return;
              }
              const double n = number("select", t);
              if (n < 0 || n != std::floor(n) || n > 1e9)
                  throw std::invalid_argument("select: '" + t + "' is not a branch label");
              d.appearance.selected = static_cast<int32_t>(n);
          },
          [](const Document &d) {
              return d.appearance.selected ? std::to_string(*d.appearance.selected) : std::string("none");
          }}},
        {"balance-visibility",
         {[](Document &d, const std::string &t) { d.appearance.balance_visibility = boolean("balance-visibility", t); },
          [](const Document &d) { return yes_no(d.appearance.balance_visibility); }}},
        {"azimuth",
         {[](Document &d, const std::string &t) { d.view.orbit.azimuth = number("azimuth", t); },
          [](const Document &d) { return number_text(d.view.orbit.azimuth); }}},
        {"elevation",
         {[](Document &d, const std::string &t) {
              const double e = number("elevation", t);
              if (e < -90 || e > 90)
                  throw std::invalid_argument("elevation: " + t + " is outside [-90, 90]");
              d.view.orbit.elevation = e;
          },
          [](const Document &d) { return number_text(d.view.orbit.elevation); }}},
        {"zoom",
         {[](Document &d, const std::string &t) {
              const double z = number("zoom", t);
              if (!(z > 0 && z <= 1000))
                  throw std::invalid_argument("zoom: " + t + " is outside (0, 1000]");
              d.view.orbit.zoom = z;
          },
          [](const Document &d) { return number_text(d.view.orbit.zoom); }}},
        {"projection",
         {[](Document &d, const std::string &t) {
              if (t != "perspective" && t != "orthographic")
                  throw std::invalid_argument("projection: '" + t + "' is not perspective or orthographic");
              d.view.orbit.perspective = t == "perspective";
          },
          [](const Document &d) { return std::string(d.view.orbit.perspective ? "perspective" : "orthographic"); }}},
        {"frame-content",
         {[](Document &d, const std::string &t) { d.view.frame_content = boolean("frame-content", t); },
          [](const Document &d) { return yes_no(d.view.frame_content); }}},
        {"auto-view",
         {[](Document &d, const std::string &t) { d.view.auto_view = boolean("auto-view", t); },
          [](const Document &d) { return yes_no(d.view.auto_view); }}},
    };
    return table;
}

// The plugin settings of the document whose parameters are controls, in the
// order a bare parameter id is looked up.
std::vector<std::pair<std::string, PluginSetting *>> plugin_slots(Document &d)
{
    std::vector<std::pair<std::string, PluginSetting *>> out{
        {"generator", &d.appearance.generator}, {"relation", &d.appearance.depictor},
        {"simplifier", &d.simplifier},          {"renderer", &d.view.renderer},
        {"legend", &d.appearance.legend}};
    for (PluginSetting &f : d.filters)
        out.push_back({"filter", &f});
    return out;
}

bool has_param(const pipeline::PluginCatalog &catalog, const PluginSetting &s, const std::string &param)
{
    if (s.empty())
        return false;
    try {
        for (const arbor_param_desc *p : catalog.descriptions(s.id))
            if (param == p->id)
                return true;
    } catch (const std::exception &) {
    }
    return false;
}

// The plugin setting that holds parameter `name` ("shape", "residue-flow.shape",
// "generator.shape"), and the parameter's id; null when none does.
std::pair<PluginSetting *, std::string> find_param(Document &d, const std::string &name,
                                                   const pipeline::PluginCatalog &catalog)
{
    const std::size_t dot = name.find('.');
    const std::string qualifier = dot == std::string::npos ? "" : name.substr(0, dot);
    const std::string param = dot == std::string::npos ? name : name.substr(dot + 1);
    for (auto &[slot, setting] : plugin_slots(d)) {
        if (!qualifier.empty() && qualifier != slot && qualifier != pipeline::short_name(setting->id) &&
            qualifier != setting->id)
            continue;
        if (has_param(catalog, *setting, param))
            return {setting, param};
    }
    return {nullptr, param};
}

} // namespace

double parse_number(const std::string &text, const std::string &what)
{
    std::size_t used = 0;
    double x = 0;
    try {
        x = std::stod(text, &used);
    } catch (const std::exception &) {
        used = 0;
    }
    if (text.empty() || used != text.size() || !std::isfinite(x))
        throw std::invalid_argument(what + ": '" + text + "' is not a number");
    return x;
}

void set_control(Document &document, const std::string &name, const std::string &text,
                 const pipeline::PluginCatalog &catalog)
{
    if (auto b = builtins().find(name); b != builtins().end()) {
        b->second.set(document, text);
        return;
    }
    auto [setting, param] = find_param(document, name, catalog);
    if (!setting)
        throw std::invalid_argument("no control named '" + name + "' (the document's plugins have no such parameter)");
    setting->params[param] = text;
}

std::string control_value(const Document &document, const std::string &name, const pipeline::PluginCatalog &catalog)
{
    if (auto b = builtins().find(name); b != builtins().end())
        return b->second.get(document);
    Document copy = document;
    auto [setting, param] = find_param(copy, name, catalog);
    if (!setting)
        throw std::invalid_argument("no control named '" + name + "'");
    const auto v = setting->params.find(param);
    return v == setting->params.end() ? std::string() : v->second;
}

std::vector<std::string> control_names(const Document &document, const pipeline::PluginCatalog &catalog)
{
    std::vector<std::string> out;
    for (const auto &[name, b] : builtins())
        out.push_back(name);
    Document copy = document;
    for (auto &[slot, setting] : plugin_slots(copy)) {
        if (setting->empty())
            continue;
        try {
            for (const arbor_param_desc *p : catalog.descriptions(setting->id))
                out.push_back(pipeline::short_name(setting->id) + "." + p->id);
        } catch (const std::exception &) {
        }
    }
    return out;
}

} // namespace arbor::workstation
