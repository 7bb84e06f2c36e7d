#include "plugin_registry.hpp"

#include "descriptor_rules.hpp"

#include <algorithm>
#include <cstdlib>
#include <sstream>

namespace arbor {

namespace fs = std::filesystem;

std::string plugin_short_name(std::string_view id)
{
    const auto dot = id.rfind('.');
    return std::string(dot == std::string_view::npos ? id : id.substr(dot + 1));
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
    for (const fs::path &dir : folders) {
        std::error_code ec;
        if (!fs::is_directory(dir, ec))
            continue;
        std::vector<fs::path> files;
        for (const auto &e : fs::directory_iterator(dir, ec))
            if (e.path().extension() == ".so" && e.is_regular_file(ec))
                files.push_back(e.path());
        std::sort(files.begin(), files.end());
        for (const fs::path &f : files)
            load_file(f);
    }
}

bool PluginRegistry::load_file(const fs::path &file)
{
    std::error_code ec;
    const fs::path canonical = fs::weakly_canonical(file, ec);
    for (const auto &lib : libraries_)
        if (lib->path() == canonical)
            return true;
    std::unique_ptr<PluginLibrary> lib;
    try {
        lib = PluginLibrary::load(canonical);
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
        s = info->library->entry().create_plugin(host->get(), info->descriptor->id, &plugin);
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
