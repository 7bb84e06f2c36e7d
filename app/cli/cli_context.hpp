// cli_context.hpp - what every command of the `arbor` CLI shares: the plugin
// registry (loaded once, before argument parsing, because plugin parameters
// become flags), the terminal progress display and the memory limit.
#pragma once

#include "plugin_flags.hpp"
#include "terminal_progress.hpp"

#include "host/plugin_registry.hpp"

#include <CLI/CLI.hpp>

#include <filesystem>
#include <functional>
#include <map>
#include <stop_token>
#include <string>
#include <vector>

namespace arbor::cli {

struct Context {
    std::filesystem::path executable;
    // The command line as given (argv), for the provenance of reports.
    std::vector<std::string> command_line;
    PluginRegistry registry;
    TerminalProgress progress;
    uint64_t max_volume_bytes = 0;
    // Ctrl-C asks the command's work to stop through this source.
    std::stop_source stop;
    // Every plugin flag of the command line, to name flags in messages.
    FlagNames flag_names;
    // The run function of each subcommand, by subcommand name.
    std::map<std::string, std::function<int()>> commands;

    // Registers under the command's path below `arbor` ("info", "dicom ls").
    void add_command(CLI::App *sub, std::function<int()> run)
    {
        std::string name = sub->get_name();
        for (CLI::App *p = sub->get_parent(); p && p->get_parent(); p = p->get_parent())
            name = p->get_name() + " " + name;
        commands[name] = std::move(run);
    }
};

// Path of the running executable (/proc/self/exe), for the built-in plugins.
std::filesystem::path executable_path(const char *argv0);

} // namespace arbor::cli
