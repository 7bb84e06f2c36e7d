#include "plugin_registry.hpp"

#include "descriptor_rules.hpp"

#include <algorithm>
#include <cstdlib>
#include <sstream>
#include <stdexcept>

#include <unistd.h>

namespace arbor {

namespace fs = std::filesystem;

std::string plugin_short_name(std::string_view id)
{
    const auto dot = id.rfind('.');
    return std::string(dot == std::string_view::npos ? id : id.substr(dot + 1));
}

const char *isolation_mode_name(IsolationMode mode)
{
    switch (mode) {
    case IsolationMode::None: return "none";
    case IsolationMode::ThirdParty: return "third-party";
    case IsolationMode::All: return "all";
    }
    return "none";
}

IsolationMode parse_isolation_mode(std::string_view text)
{
    for (IsolationMode m : {IsolationMode::None, IsolationMode::ThirdParty, IsolationMode::All})
        if (text == isolation_mode_name(m))
            return m;
    throw std::invalid_argument("isolation '" + std::string(text) + "': choose all, third-party or none");
}

IsolationPolicy default_isolation(const fs::path &executable, IsolationMode mode, double timeout_seconds)
{
    IsolationPolicy policy;
    policy.mode = mode;
    policy.settings.helper = executable.parent_path() / "arbor-plugin-host";
    policy.settings.timeout_seconds = timeout_seconds;
    // A plugin may use what the machine has, not more: a runaway allocation
    // fails in the plugin's process instead of swapping the host out.
    const long pages = sysconf(_SC_PHYS_PAGES), page = sysconf(_SC_PAGESIZE);
    policy.settings.memory_limit = pages > 0 && page > 0 ? static_cast<uint64_t>(pages) * static_cast<uint64_t>(page) : 0;
    std::error_code ec;
    policy.builtin_folder = fs::weakly_canonical(executable.parent_path().parent_path() / ARBOR_PLUGIN_SUBDIR, ec);
    return policy;
}

bool PluginRegistry::isolates(const fs::path &path) const
{
    switch (isolation_.mode) {
    case IsolationMode::None: return false;
    case IsolationMode::All: return true;
    case IsolationMode::ThirdParty: return path.parent_path() != isolation_.builtin_folder;
    }
    return false;
}

PluginRegistry::~PluginRegistry()
{
    // Libraries unload in reverse order of loading.
    while (!libraries_.empty())
        libraries_.pop_back();
}

std::vector<fs::path> PluginRegistry::default_search_path(const fs::path &executable)
{
    std::vector<fs::path> dirs;
    if (const char *env = std::getenv("ARBOR_PLUGIN_PATH")) {
        std::stringstream ss(env);
        std::string item;
        while (std::getline(ss, item, ':'))
            if (!item.empty())
                dirs.emplace_back(item);
    }
    if (const char *xdg = std::getenv("XDG_DATA_HOME"); xdg && *xdg)
        dirs.push_back(fs::path(xdg) / "arbor" / "plugins");
    else if (const char *home = std::getenv("HOME"); home && *home)
        dirs.push_back(fs::path(home) / ".local" / "share" / "arbor" / "plugins");
    dirs.push_back(executable.parent_path().parent_path() / ARBOR_PLUGIN_SUBDIR);
    return dirs;
}

void PluginRegistry::load_directories(const std::vector<fs::path> &folders)
{
    std::vector<fs::path> files;
    for (const fs::path &dir : folders) {
        std::error_code ec;
        if (!fs::is_directory(dir, ec))
            continue;
        std::vector<fs::path> in_folder;
        for (const auto &e : fs::directory_iterator(dir, ec))
            if (e.path().extension() == ".so" && e.is_regular_file(ec))
                in_folder.push_back(e.path());
        std::sort(in_folder.begin(), in_folder.end());
        files.insert(files.end(), in_folder.begin(), in_folder.end());
    }
    // Isolated libraries load in their processes at the same time; the
    // results are taken in search-path order, as if loaded one by one.
    std::vector<std::unique_ptr<IsolatedLibrary>> started(files.size());
    for (std::size_t i = 0; i < files.size(); ++i) {
        std::error_code ec;
        const fs::path canonical = fs::weakly_canonical(files[i], ec);
        if (!isolates(canonical))
            continue;
        try {
            started[i] = IsolatedLibrary::begin(canonical, isolation_.settings);
        } catch (const PluginRefused &) {
            // load_file tries again and records why
        }
    }
    for (std::size_t i = 0; i < files.size(); ++i)
        load_file(files[i], std::move(started[i]));
}

bool PluginRegistry::load_file(const fs::path &file, std::unique_ptr<IsolatedLibrary> started)
{
    std::error_code ec;
    const fs::path canonical = fs::weakly_canonical(file, ec);
    for (const auto &lib : libraries_)
        if (lib->path() == canonical)
            return true;
    std::unique_ptr<PluginLibrary> lib;
    try {
        lib = isolates(canonical) ? PluginLibrary::load_isolated(canonical, isolation_.settings, std::move(started))
                                  : PluginLibrary::load(canonical);
    } catch (const PluginRefused &e) {
        refusals_.push_back({file.string(), "", e.what()});
        log_message(ARBOR_LOG_WARNING, "", "plugin library " + file.string() + " refused: " + e.what());
        return false;
    }
    for (const PluginRefusal &r : lib->refusals()) {
        refusals_.push_back(r);
        log_message(ARBOR_LOG_WARNING, "",
                    "plugin " + r.plugin_id + " in " + r.path + " refused: " + r.reason);
    }
    for (const arbor_plugin_descriptor *d : lib->descriptors()) {
        if (const PluginInfo *existing = find(d->id)) {
            const std::string reason = "id '" + std::string(d->id) + "' is already provided by " +
                                       existing->library->path().string() + " (earlier in the search path)";
            refusals_.push_back({file.string(), d->id, reason});
            log_message(ARBOR_LOG_INFO, "", "plugin in " + file.string() + " skipped: " + reason);
            continue;
        }
        plugins_.push_back({d, lib.get()});
    }
    libraries_.push_back(std::move(lib));
    return true;
}

std::vector<const PluginInfo *> PluginRegistry::plugins_of_kind(std::string_view kind) const
{
    std::vector<const PluginInfo *> out;
    for (const PluginInfo &p : plugins_)
        if (kind == p.descriptor->kind)
            out.push_back(&p);
    return out;
}

const PluginInfo *PluginRegistry::find(std::string_view id) const
{
    for (const PluginInfo &p : plugins_)
        if (id == p.descriptor->id)
            return &p;
    return nullptr;
}

std::vector<const PluginInfo *> PluginRegistry::sharing_short_name(std::string_view short_name) const
{
    std::vector<const PluginInfo *> out;
    for (const PluginInfo &p : plugins_)
        if (plugin_short_name(p.descriptor->id) == short_name)
            out.push_back(&p);
    return out;
}

PluginInstance PluginRegistry::create(std::string_view id) const
{
    const PluginInfo *info = find(id);
    if (!info) {
        std::string known;
        for (const PluginInfo &p : plugins_)
            known += (known.empty() ? "" : ", ") + std::string(p.descriptor->id);
        throw PluginError(ARBOR_ERROR_NOT_FOUND, "no plugin with id '" + std::string(id) +
                                                     "' (loaded: " + known + ")");
    }
    auto host = std::make_unique<HostIdentity>(std::string(id));
    const char *caller = host->source().c_str(); // the id a crash report names; lives with the instance
    arbor_plugin *plugin = nullptr;
    arbor_status s;
    {
        const PluginCall in(caller, "entry.create_plugin");
        s = info->library->create_plugin(host->get(), info->descriptor->id, &plugin);
    }
    if (s != ARBOR_OK || !plugin)
        throw PluginError(s == ARBOR_OK ? ARBOR_ERROR_INTERNAL : s,
                          std::string(id) + ": could not create an instance (" +
                              arbor_status_name(s) + ")");
    if (plugin->struct_size < ARBOR_MIN_SIZE(arbor_plugin) || !plugin->destroy || !plugin->get_interface ||
        !plugin->last_error || !plugin->descriptor) {
        // Cannot trust destroy() here; leak rather than crash.
        throw PluginError(ARBOR_ERROR_INTERNAL,
                          std::string(id) + ": the instance record is malformed");
    }
    PluginInstance instance(plugin, std::move(host));
    const char *iface = kind_interface_id(info->descriptor->kind);
    if (!instance.call("plugin.get_interface", plugin->get_interface, iface))
        throw PluginError(ARBOR_ERROR_UNSUPPORTED,
                          std::string(id) + ": a " + info->descriptor->kind +
                              " plugin must offer interface " + iface);
    if (const arbor_params_v1 *params = instance.params()) {
        std::vector<std::string> problems;
        {
            const PluginCall in(caller, "params.describe");
            problems = check_param_set(plugin, *params);
        }
        if (!problems.empty())
            throw PluginError(ARBOR_ERROR_INTERNAL,
                              std::string(id) + ": malformed parameter description: " + problems.front());
    }
    return instance;
}

} // namespace arbor
