#include "plugin_library.hpp"

#include "descriptor_rules.hpp"
#include "isolated_library.hpp"
#include "plugin_call.hpp"

#include <dlfcn.h>

#include <set>

namespace arbor {

std::unique_ptr<PluginLibrary> PluginLibrary::load(const std::filesystem::path &path)
{
    std::unique_ptr<PluginLibrary> lib(new PluginLibrary());
    lib->path_ = path;
    lib->name_ = path.filename().string();
    const char *caller = lib->name_.c_str(); // what a crash report names
    dlerror();
    // RTLD_NODELETE: a plugin's code stays mapped after dlclose.  Libraries
    // it pulls in (VTK's object factories, for one) may keep pointers into it
    // that their own exit handlers follow.
    {
        const PluginCall in(caller, "dlopen (the library's initialisers)");
        lib->handle_ = dlopen(path.c_str(), RTLD_NOW | RTLD_LOCAL | RTLD_NODELETE);
    }
    if (!lib->handle_) {
        const char *e = dlerror();
        throw PluginRefused(std::string("cannot be loaded: ") + (e ? e : "unknown dlopen error"));
    }
    dlerror();
    void *symbol = dlsym(lib->handle_, ARBOR_ENTRY_SYMBOL);
    if (!symbol)
        throw PluginRefused("has no '" ARBOR_ENTRY_SYMBOL "' entry symbol; not an Arbor plugin");
    const auto *entry = static_cast<const arbor_plugin_entry *>(symbol);
    if (const std::string problem = check_entry_record(entry); !problem.empty())
        throw PluginRefused(problem);
    const arbor_version v = entry->abi_version;
    if (v.minor > ARBOR_ABI_VERSION_MINOR)
        log_message(ARBOR_LOG_DEBUG, path.string(),
                    "built for a newer ABI minor (" + std::to_string(v.minor) + ") than the host's");
    lib->entry_ = entry;

    lib->host_ = std::make_unique<HostIdentity>(path.filename().string());
    arbor_status s;
    {
        const PluginCall in(caller, "entry.init");
        s = entry->init(lib->host_->get(), path.c_str());
    }
    if (s != ARBOR_OK)
        throw PluginRefused(std::string("init failed (") + arbor_status_name(s) + ")");
    lib->initialised_ = true;

    uint32_t count;
    {
        const PluginCall in(caller, "entry.plugin_count");
        count = entry->plugin_count();
    }
    if (count == 0)
        throw PluginRefused("holds no plugins");
    if (count > 1000)
        throw PluginRefused("claims " + std::to_string(count) + " plugins (at most 1000)");
    lib->accept(count, [&](uint32_t i) {
        const PluginCall in(caller, "entry.plugin_descriptor");
        return entry->plugin_descriptor(i);
    });
    return lib;
}

void PluginLibrary::accept(uint32_t count, const std::function<const arbor_plugin_descriptor *(uint32_t)> &describe)
{
    const char *caller = name_.c_str();
    std::set<std::string> ids;
    for (uint32_t i = 0; i < count; ++i) {
        const arbor_plugin_descriptor *d = describe(i);
        std::string problem;
        {
            const PluginCall in(caller, "entry.plugin_descriptor");
            problem = check_descriptor(d); // reads the plugin's strings
        }
        if (problem.empty() && !ids.insert(d->id).second)
            problem = "plugin id '" + std::string(d->id) + "' appears twice in the library";
        if (!problem.empty()) {
            const std::string id = d && d->id && check_plugin_id(d->id).empty() ? d->id : "";
            refusals_.push_back({path_.string(), id.empty() ? "#" + std::to_string(i) : id,
                                 "descriptor " + std::to_string(i) + ": " + problem});
            continue;
        }
        accepted_.push_back(d);
    }
}

std::unique_ptr<PluginLibrary> PluginLibrary::load_isolated(const std::filesystem::path &path,
                                                            const IsolationSettings &settings,
                                                            std::unique_ptr<IsolatedLibrary> started)
{
    std::unique_ptr<PluginLibrary> lib(new PluginLibrary());
    lib->path_ = path;
    lib->name_ = path.filename().string();
    if (started) {
        started->finish(); // throws PluginRefused
        lib->isolated_ = std::move(started);
    } else {
        lib->isolated_ = std::make_unique<IsolatedLibrary>(path, settings); // throws PluginRefused
    }
    const auto &descriptors = lib->isolated_->descriptors();
    if (lib->isolated_->abi_version().minor > ARBOR_ABI_VERSION_MINOR)
        log_message(ARBOR_LOG_DEBUG, path.string(),
                    "built for a newer ABI minor (" + std::to_string(lib->isolated_->abi_version().minor) +
                        ") than the host's");
    lib->accept(static_cast<uint32_t>(descriptors.size()), [&](uint32_t i) { return descriptors[i]; });
    return lib;
}

arbor_status PluginLibrary::create_plugin(const arbor_host *host, const char *plugin_id, arbor_plugin **out) const
{
    if (isolated_)
        return isolated_->create_plugin(host, plugin_id, out);
    return entry_->create_plugin(host, plugin_id, out);
}

PluginLibrary::~PluginLibrary()
{
    if (initialised_ && entry_) {
        const PluginCall in(name_.c_str(), "entry.deinit");
        entry_->deinit();
    }
    if (handle_)
        dlclose(handle_);
}

} // namespace arbor
