// `arbor plugin-check <library>`: the conformance check a plugin author runs
// (see host/conformance.hpp).  Exit status 0 only when every check passed.
#include "commands.hpp"

#include "host/conformance.hpp"

#include <nlohmann/json.hpp>

#include <cstdio>
#include <iostream>
#include <memory>

namespace arbor::cli {

namespace {

struct CheckArgs {
    std::vector<std::string> libraries;
    bool json = false;
    int timeout = 60;
};

} // namespace

void add_plugin_check_command(CLI::App &app, Context &context)
{
    CLI::App *sub = app.add_subcommand(
        "plugin-check", "Check that plugin libraries follow the Arbor ABI (for plugin authors)");
    auto a = std::make_shared<CheckArgs>();
    sub->add_option("library", a->libraries, "Plugin library files (.so)")->required()
        ->check(CLI::ExistingFile);
    sub->add_flag("--json", a->json, "Print JSON instead of text");
    sub->add_option("--timeout", a->timeout, "Seconds each plugin may take before it counts as hung")
        ->default_val(60)->check(CLI::Range(1, 3600));
    context.add_command(sub, [a]() {
        nlohmann::json all = nlohmann::json::array();
        int failures = 0;
        for (const std::string &lib : a->libraries) {
            const ConformanceReport r = check_plugin_conformance(lib, std::chrono::seconds(a->timeout));
            failures += r.failures() + (r.checks.empty() ? 1 : 0);
            if (a->json) {
                nlohmann::json j{{"library", r.library}, {"passed", r.passed()}, {"failures", r.failures()}};
                j["checks"] = nlohmann::json::array();
                for (const auto &c : r.checks)
                    j["checks"].push_back({{"plugin", c.plugin}, {"check", c.name},
                                           {"passed", c.passed}, {"detail", c.detail}});
                all.push_back(j);
                continue;
            }
            std::printf("%s\n", r.library.c_str());
            std::string plugin = "\x01";
            for (const auto &c : r.checks) {
                if (c.plugin != plugin) {
                    plugin = c.plugin;
                    std::printf("  %s\n", plugin.empty() ? "(library)" : plugin.c_str());
                }
                std::printf("    %s  %s%s%s\n", c.passed ? "pass" : "FAIL", c.name.c_str(),
                            c.detail.empty() ? "" : ": ", c.detail.c_str());
            }
            std::printf("  %zu checks, %d failed\n", r.checks.size(), r.failures());
        }
        if (a->json)
            std::cout << all.dump(2, ' ', false, nlohmann::json::error_handler_t::replace) << "\n";
        return failures == 0 ? 0 : 1;
    });
}

} // namespace arbor::cli
