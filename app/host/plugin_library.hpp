// plugin_library.hpp - one loaded plugin library (dlopen), checked against
// the ABI before anything in it runs beyond its initialiser.
//
// Loading refuses, with a reason that names the file: files dlopen rejects,
// libraries without the `arbor_entry` symbol, a different ABI major version,
// an entry with missing functions, and an init that fails.  Plugins inside an
// accepted library whose descriptors break the rules are refused one by one.
#pragma once

#include "host_services.hpp"
#include "plugin_process.hpp"

#include <arbor/plugin.h>

#include <filesystem>
#include <functional>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

namespace arbor {

struct PluginRefusal {
    std::string path;
    std::string plugin_id; // empty when the whole library was refused
    std::string reason;
};

class PluginRefused : public std::runtime_error {
public:
    using std::runtime_error::runtime_error;
};

class IsolatedLibrary;

class PluginLibrary {
public:
    // Throws PluginRefused with the reason.
    static std::unique_ptr<PluginLibrary> load(const std::filesystem::path &path);
    // The same library in a process of its own (isolated_library.hpp);
    // `started`: one IsolatedLibrary::begin started already.
    static std::unique_ptr<PluginLibrary> load_isolated(const std::filesystem::path &path,
                                                        const IsolationSettings &settings,
                                                        std::unique_ptr<IsolatedLibrary> started = nullptr);
    ~PluginLibrary();
    PluginLibrary(const PluginLibrary &) = delete;
    PluginLibrary &operator=(const PluginLibrary &) = delete;

    const std::filesystem::path &path() const { return path_; }
    // The library's entry; in-process libraries only (plugin-check).
    const arbor_plugin_entry &entry() const { return *entry_; }
    bool isolated() const { return isolated_ != nullptr; }
    // entry.create_plugin, in this process or through the isolated one.
    arbor_status create_plugin(const arbor_host *host, const char *plugin_id, arbor_plugin **out) const;
    // Descriptors that passed the rules.
    const std::vector<const arbor_plugin_descriptor *> &descriptors() const { return accepted_; }
    // Plugins of this library refused for their descriptors.
    const std::vector<PluginRefusal> &refusals() const { return refusals_; }

private:
    PluginLibrary() = default;
    // Applies the descriptor rules; `describe(i)` reads descriptor i.
    void accept(uint32_t count, const std::function<const arbor_plugin_descriptor *(uint32_t)> &describe);

    std::filesystem::path path_;
    std::string name_; // the file's name, for crash reports
    void *handle_ = nullptr;
    const arbor_plugin_entry *entry_ = nullptr;
    bool initialised_ = false;
    std::unique_ptr<HostIdentity> host_;
    std::unique_ptr<IsolatedLibrary> isolated_;
    std::vector<const arbor_plugin_descriptor *> accepted_;
    std::vector<PluginRefusal> refusals_;
};

} // namespace arbor
