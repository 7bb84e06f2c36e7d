// plugin_catalog.hpp - the plugins a pipeline can use, found by kind and by
// name (the id, or its short name, the last part: "itri" for
// org.arbor.simplifier.itri, unless another plugin of the kind has it), and
// plugin settings checked against the plugins' own parameter descriptions.
// That check is what lets a session save and restore a third party's plugin
// without code of ours, and what turns a bad value into a clear message
// before any work starts.
#pragma once

#include "document.hpp"

#include "host/plugin_registry.hpp"

#include <map>
#include <memory>
#include <mutex>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

namespace arbor::pipeline {

// A parameter value a plugin cannot take, or a parameter it does not have, or
// a required one nobody gave: names both, so a front can say it its own way
// (the CLI names the flag).
class SettingError : public std::invalid_argument {
public:
    enum class Problem { Unknown, Invalid, Missing };
    SettingError(Problem problem, std::string plugin_id, std::string param_id, const std::string &message)
        : std::invalid_argument(message), problem(problem), plugin_id(std::move(plugin_id)),
          param_id(std::move(param_id))
    {
    }
    Problem problem;
    std::string plugin_id, param_id;
};

// A name that is no plugin of the kind, or a short name two plugins of the
// kind share (the message names both and says to write the full id).
class PluginNameError : public std::invalid_argument {
public:
    using std::invalid_argument::invalid_argument;
};

class PluginCatalog {
public:
    explicit PluginCatalog(const PluginRegistry &registry) : registry_(registry) {}
    PluginCatalog(const PluginCatalog &) = delete;
    PluginCatalog &operator=(const PluginCatalog &) = delete;

    const PluginRegistry &registry() const { return registry_; }

    // The full id `name` stands for among the plugins of `kind`
    // (ARBOR_KIND_*): a full id always, a short name when no other plugin of
    // the kind has it.  Throws PluginNameError listing those there are, or
    // those that share the short name.
    std::string find(std::string_view kind, const std::string &name) const;

    // The setting with its full id, the plugin's version and every
    // parameter's value: those given (parsed and checked against their
    // descriptions, the plugin's own set() included), the others at their
    // defaults.  Throws std::invalid_argument for an unknown plugin and
    // SettingError for an unknown parameter, a value out of range or a
    // required parameter not given.
    PluginSetting resolve(std::string_view kind, const PluginSetting &setting) const;

    // A new instance (thread-safe; throws PluginError).
    PluginInstance create(const std::string &id) const;

    // The parameter descriptions of a plugin, valid for the catalog's life.
    std::vector<const arbor_param_desc *> descriptions(const std::string &id) const;

    // What the renderer name "auto" (the default) stands for, and why: the
    // OpenGL ray caster when its OpenGL runs on graphics hardware, else the
    // CPU ray caster (faster than OpenGL emulated on the CPU, as Mesa's
    // llvmpipe is).  Probed once per catalog.
    struct RendererChoice {
        std::string id;
        std::string reason; // one sentence, e.g. "the OpenGL ray caster would run on llvmpipe, ..."
    };
    const RendererChoice &renderer_choice() const;

private:
    const PluginInstance &prototype(const std::string &id) const; // under mutex_

    const PluginRegistry &registry_;
    mutable std::mutex mutex_;
    mutable std::map<std::string, std::unique_ptr<PluginInstance>> prototypes_;
    mutable std::once_flag choice_once_;
    mutable RendererChoice choice_;
};

// How messages name a kind: "simplifier", "transfer-function generator"...
std::string kind_noun(std::string_view kind);

// Sets every parameter of `setting` on the instance; throws SettingError.
void apply_setting(PluginInstance &instance, const PluginSetting &setting);
// Throws SettingError for a REQUIRED parameter `setting` does not give.
void require_parameters(const PluginInstance &instance, const PluginSetting &setting);

// Every parameter's current value, as text.
std::map<std::string, std::string> read_params(const PluginInstance &instance);

// "gaussian:sigma=1.5": the id's last part and the values that differ from
// their defaults (the form --filter takes).
std::string describe_setting(const PluginSetting &setting, const std::vector<const arbor_param_desc *> &descriptions);

// The last part of a plugin id ("itri"): plugin_short_name.
std::string short_name(const std::string &id);

} // namespace arbor::pipeline
