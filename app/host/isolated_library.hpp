// isolated_library.hpp - a plugin library loaded into a process of its own
// (`arbor-plugin-host`), presented to the host through the same C ABI as a
// library loaded in-process: its descriptors, and instances whose
// arbor_plugin records and interface tables are proxies that carry every
// call over shared memory (plugin_process.hpp).  Nothing above the registry
// knows which plugins are isolated.
//
// A crash, an abort, a runaway allocation (the child's data segment is
// limited) or a hang (IsolationSettings::timeout_seconds without a sign of
// life) fails the call in progress with ARBOR_ERROR_INTERNAL and a reason
// naming the call; the host carries on.  At the instance's next call the
// library gets a new process, the instance is created there again and its
// parameters set again to the values the host last set.  What the instance
// had built up (a renderer's caches) is built again.
//
// Limits of the proxy: it offers the interfaces this host knows (params,
// importer, filter, simplifier, depictor, tf-generator, renderer /1 and /2,
// render-device), not ones a later SDK adds; a library may have at most 63
// live instances at once.
#pragma once

#include "plugin_process.hpp"

#include <arbor/arbor.h>

#include <filesystem>
#include <memory>
#include <mutex>
#include <string>
#include <vector>

namespace arbor {

class IsolatedLibrary {
public:
    // Starts the process and loads the library there; throws PluginRefused
    // with the reason (the child's dlopen error, a crash in its init...).
    IsolatedLibrary(const std::filesystem::path &path, const IsolationSettings &settings);
    // The same in two halves, so that many libraries load at once: begin
    // starts the process and asks it to load; finish waits for the answer
    // (throws PluginRefused).  Nothing else may be called before finish.
    static std::unique_ptr<IsolatedLibrary> begin(const std::filesystem::path &path, const IsolationSettings &settings);
    void finish();
    ~IsolatedLibrary();
    IsolatedLibrary(const IsolatedLibrary &) = delete;
    IsolatedLibrary &operator=(const IsolatedLibrary &) = delete;

    // Every descriptor the library gave (copies the host owns), before the
    // rules were applied, in its order; nullptr where it gave NULL.
    const std::vector<const arbor_plugin_descriptor *> &descriptors() const { return descriptor_pointers_; }
    arbor_version abi_version() const { return abi_version_; }

    // entry.create_plugin, answered by a proxy instance.
    arbor_status create_plugin(const arbor_host *host, const char *plugin_id, arbor_plugin **out);

    // The running process: the current one, or a new one when it died.
    std::shared_ptr<PluginProcess> process();

private:
    struct OwnedDescriptor;
    struct Started {
        std::shared_ptr<PluginProcess> process;
        uint32_t posted = 0;
    };
    IsolatedLibrary(const std::filesystem::path &path, const IsolationSettings &settings, bool);
    Started start_process();                           // spawned, the load posted
    std::shared_ptr<PluginProcess> finish_start(const Started &started); // the load's answer
    std::shared_ptr<PluginProcess> start() { return finish_start(start_process()); }
    Started pending_;

    std::filesystem::path path_;
    std::string name_;
    IsolationSettings settings_;
    std::mutex mutex_;
    std::shared_ptr<PluginProcess> process_;
    arbor_version abi_version_{};
    std::vector<std::unique_ptr<OwnedDescriptor>> descriptors_;
    std::vector<const arbor_plugin_descriptor *> descriptor_pointers_;
    int starts_ = 0;
};

} // namespace arbor
