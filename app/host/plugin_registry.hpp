// plugin_registry.hpp - finds plugin libraries, loads them, and hands out
// instances by id or kind.
//
// Search order (earlier wins when two plugins share an id): the folders in
// ARBOR_PLUGIN_PATH (':'-separated), the per-user folder
// ($XDG_DATA_HOME or ~/.local/share)/arbor/plugins, then the built-in folder
// <prefix>/lib/arbor/plugins next to the executable.  A library that is
// refused never stops the others from loading.
#pragma once

#include "plugin_instance.hpp"
#include "plugin_library.hpp"

#include <filesystem>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

namespace arbor {

// A plugin's short name: the last part of its id ("itri" for
// org.arbor.simplifier.itri).  It depends on the id alone, never on which
// other plugins are installed; where two loaded plugins share it, it names
// neither of them (and the full ids must be written).
std::string plugin_short_name(std::string_view id);

struct PluginInfo {
    const arbor_plugin_descriptor *descriptor;
    const PluginLibrary *library;
};

class PluginRegistry {
public:
    PluginRegistry() = default;
    PluginRegistry(const PluginRegistry &) = delete;
    PluginRegistry &operator=(const PluginRegistry &) = delete;
    ~PluginRegistry();

    // The folders searched by default, in order; `executable` locates the
    // built-in folder.
    static std::vector<std::filesystem::path> default_search_path(
        const std::filesystem::path &executable);

    // Loads every *.so in the folders (missing folders are skipped).
    void load_directories(const std::vector<std::filesystem::path> &folders);
    // Loads one library; returns false (and records the refusal) if refused.
    bool load_file(const std::filesystem::path &library);

    const std::vector<PluginRefusal> &refusals() const { return refusals_; }
    const std::vector<PluginInfo> &plugins() const { return plugins_; }
    std::vector<const PluginInfo *> plugins_of_kind(std::string_view kind) const;
    const PluginInfo *find(std::string_view id) const;
    // The plugins, of any kind, whose short name is `short_name`.
    std::vector<const PluginInfo *> sharing_short_name(std::string_view short_name) const;
    const std::vector<std::unique_ptr<PluginLibrary>> &libraries() const { return libraries_; }

    // Creates an instance; throws PluginError (unknown id, creation failure,
    // a missing interface for its kind, malformed parameter descriptions).
    PluginInstance create(std::string_view id) const;

private:
    std::vector<std::unique_ptr<PluginLibrary>> libraries_;
    std::vector<PluginInfo> plugins_;
    std::vector<PluginRefusal> refusals_;
};

} // namespace arbor
