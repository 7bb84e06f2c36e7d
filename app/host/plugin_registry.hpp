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
#include "isolated_library.hpp"
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

// Which libraries run in a process of their own (isolated_library.hpp).
enum class IsolationMode {
    None,       // every library in this process
    ThirdParty, // all but those in the built-in folder (the default of `arbor`)
    All,
};
// "none", "third-party", "all"; parse_isolation_mode throws
// std::invalid_argument naming the choices.
const char *isolation_mode_name(IsolationMode mode);
IsolationMode parse_isolation_mode(std::string_view text);

struct IsolationPolicy {
    IsolationMode mode = IsolationMode::None;
    IsolationSettings settings;          // the helper, the per-call timeout, the memory limit
    std::filesystem::path builtin_folder; // ours: libraries here count as first-party
};
// The policy `arbor` and the workstation start with: `mode`, the helper
// next to `executable`, a timeout of `timeout_seconds`, and a memory limit of
// the machine's memory.
IsolationPolicy default_isolation(const std::filesystem::path &executable, IsolationMode mode,
                                  double timeout_seconds);

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

    // Applies to the libraries loaded after it.
    void set_isolation(IsolationPolicy policy) { isolation_ = std::move(policy); }
    const IsolationPolicy &isolation() const { return isolation_; }
    // Whether a library at `path` (canonical) would run isolated.
    bool isolates(const std::filesystem::path &path) const;

    // Loads every *.so in the folders (missing folders are skipped).
    void load_directories(const std::vector<std::filesystem::path> &folders);
    // Loads one library; returns false (and records the refusal) if refused.
    // `started`: its isolated process, begun already (load_directories
    // starts them all before it waits for any).
    bool load_file(const std::filesystem::path &library, std::unique_ptr<IsolatedLibrary> started = nullptr);

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
    IsolationPolicy isolation_;
};

} // namespace arbor
