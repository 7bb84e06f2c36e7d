// `arbor plugins`: which plugins were found, from which files, by which
// short name they go (none when another loaded plugin shares it), and which
// libraries or plugins were refused and why.
#include "commands.hpp"

#include <nlohmann/json.hpp>

#include <cstdio>
#include <iostream>
#include <memory>

namespace arbor::cli {

void add_plugins_command(CLI::App &app, Context &context)
{
    CLI::App *sub = app.add_subcommand("plugins", "List loaded plugins and refused ones");
    auto json = std::make_shared<bool>(false);
    sub->add_flag("--json", *json, "Print JSON instead of text");
    context.add_command(sub, [&context, json]() {
        const PluginRegistry &r = context.registry;
        const auto search = PluginRegistry::default_search_path(context.executable);
        if (*json) {
            nlohmann::json j;
            j["abi_version"] = std::to_string(ARBOR_ABI_VERSION_MAJOR) + "." +
                               std::to_string(ARBOR_ABI_VERSION_MINOR) + "." +
                               std::to_string(ARBOR_ABI_VERSION_PATCH);
            for (const auto &p : search)
                j["search_path"].push_back(p.string());
            j["plugins"] = nlohmann::json::array();
            for (const PluginInfo &p : r.plugins()) {
                const arbor_plugin_descriptor &d = *p.descriptor;
                const std::string short_name = plugin_short_name(d.id);
                nlohmann::json sharing = nlohmann::json::array();
                for (const PluginInfo *other : r.sharing_short_name(short_name))
                    if (other != &p)
                        sharing.push_back(other->descriptor->id);
                j["plugins"].push_back({{"id", d.id},
                                        {"short_name", short_name},
                                        {"short_name_shared_with", sharing},
                                        {"kind", d.kind},
                                        {"name", d.name},
                                        {"version", d.version},
                                        {"vendor", d.vendor},
                                        {"description", d.description},
                                        {"library", p.library->path().string()},
                                        {"isolated", p.library->isolated()}});
            }
            j["isolation"] = {{"mode", isolation_mode_name(r.isolation().mode)},
                              {"timeout_s", r.isolation().settings.timeout_seconds}};
            j["refused"] = nlohmann::json::array();
            for (const PluginRefusal &x : r.refusals())
                j["refused"].push_back({{"library", x.path}, {"plugin", x.plugin_id}, {"reason", x.reason}});
            std::cout << j.dump(2, ' ', false, nlohmann::json::error_handler_t::replace) << "\n";
            return 0;
        }
        std::printf("%-34s %-16s %-13s %-8s %s\n", "ID", "SHORT NAME", "KIND", "VERSION", "NAME");
        bool shared = false;
        for (const PluginInfo &p : r.plugins()) {
            std::string short_name = plugin_short_name(p.descriptor->id);
            if (r.sharing_short_name(short_name).size() > 1) {
                short_name = "(shared)";
                shared = true;
            }
            std::printf("%-34s %-16s %-13s %-8s %s\n", p.descriptor->id, short_name.c_str(), p.descriptor->kind,
                        p.descriptor->version, p.descriptor->name);
        }
        if (shared)
            std::printf("\n(shared): another plugin has the same short name; write the full id, also in flags "
                        "(--ID.PARAMETER)\n");
        if (!r.refusals().empty()) {
            std::printf("\nRefused:\n");
            for (const PluginRefusal &x : r.refusals())
                std::printf("  %s%s%s: %s\n", x.path.c_str(), x.plugin_id.empty() ? "" : " ",
                            x.plugin_id.c_str(), x.reason.c_str());
        }
        std::printf("\nSearch path (first wins):\n");
        for (const auto &p : search)
            std::printf("  %s\n", p.c_str());
        return 0;
    });
}

} // namespace arbor::cli
