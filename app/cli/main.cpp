// `arbor`: the command-line front of the Arbor host.  Loads the plugins
// first (their parameters become flags), parses, runs one subcommand.
//
// Exit status: 0 success, 1 the work failed (bad input, plugin error),
// 2 the command line was wrong (what CLI11 refuses; a UsageError; a plugin
// name that names no plugin or two; a plugin flag's value the plugin
// refuses or a required one not given), 130 cancelled with Ctrl-C.  A crash
// inside a plugin is named on stderr before the process dies of it
// (host/plugin_call.hpp); in an isolated one (--isolate, the default for
// third-party libraries) it fails the call and `arbor` carries on.
#include "cli_context.hpp"
#include "commands.hpp"
#include "interrupt_watch.hpp"
#include "isolation_flags.hpp"
#include "usage_error.hpp"

#include "core/cancelled.hpp"
#include "pipeline/plugin_catalog.hpp"
#include "core/volume_header.hpp"

#include <cstdio>
#include <cstdlib>

int main(int argc, char **argv)
{
    using namespace arbor;
    cli::Context context;
    // First Ctrl-C: stop the command's work.  Second: leave now.
    const cli::InterruptWatch interrupt([&context] { context.stop.request_stop(); });

    // Verbosity must be known before plugins load (they log while loading).
    for (int i = 1; i < argc; ++i) {
        const std::string a = argv[i];
        if (a == "-v" || a == "--verbose")
            set_log_level(ARBOR_LOG_DEBUG);
        else if (a == "-q" || a == "--quiet")
            set_log_level(ARBOR_LOG_ERROR);
    }

    context.executable = cli::executable_path(argv[0]);
    context.command_line.assign(argv, argv + argc);
    context.max_volume_bytes = default_max_volume_bytes();
    try {
        const cli::IsolationChoice isolation = cli::isolation_from_command_line(argc, argv);
        context.registry.set_isolation(
            default_isolation(context.executable, isolation.mode, isolation.timeout_seconds));
    } catch (const cli::UsageError &e) {
        log_message(ARBOR_LOG_ERROR, "", e.what());
        return 2;
    }
    context.registry.load_directories(PluginRegistry::default_search_path(context.executable));

    CLI::App app{"Arbor: explore CT and MR volumes through their contour tree.\n"
                 "Run `arbor <command> --help` for the options of a command."};
    app.name("arbor");
    app.set_version_flag("--version", std::string("arbor ") + ARBOR_HOST_VERSION + " (plugin ABI " +
                                          std::to_string(ARBOR_ABI_VERSION_MAJOR) + "." +
                                          std::to_string(ARBOR_ABI_VERSION_MINOR) + ")");
    bool verbose = false, quiet = false; // applied above, before plugins load
    app.add_flag("-v,--verbose", verbose, "Log debug messages");
    app.add_flag("-q,--quiet", quiet, "Log errors only");
    cli::add_isolation_options(app);
    app.require_subcommand(1);

    cli::add_info_command(app, context);
    cli::add_dicom_command(app, context);
    cli::add_pacs_command(app, context);
    cli::add_phantom_command(app, context);
    cli::add_convert_command(app, context);
    cli::add_tree_command(app, context);
    cli::add_simplify_command(app, context);
    cli::add_compare_command(app, context);
    cli::add_tf_command(app, context);
    cli::add_render_command(app, context);
    cli::add_run_command(app, context);
    cli::add_view_command(app, context);
    cli::add_denoise_study_command(app, context);
    cli::add_pairs_command(app, context);
    cli::add_diagram_distance_command(app, context);
    cli::add_plugins_command(app, context);
    cli::add_plugin_check_command(app, context);

    try {
        app.parse(argc, argv);
    } catch (const CLI::CallForHelp &e) {
        return app.exit(e);
    } catch (const CLI::CallForAllHelp &e) {
        return app.exit(e);
    } catch (const CLI::CallForVersion &e) {
        return app.exit(e);
    } catch (const CLI::ParseError &e) {
        app.exit(e);
        return 2;
    }

    // Nested commands ("dicom ls") register under their full path.
    std::string name;
    for (CLI::App *sub = &app; !sub->get_subcommands().empty();) {
        sub = sub->get_subcommands().front();
        name += (name.empty() ? "" : " ") + sub->get_name();
    }
    try {
        return context.commands.at(name)();
    } catch (const Cancelled &) {
        log_message(ARBOR_LOG_ERROR, "", "cancelled");
        return 130;
    } catch (const pipeline::SettingError &e) {
        // The pipeline names the parameter; the user typed a flag.
        const std::string flag = context.flag_names.flag_of(e.plugin_id, e.param_id);
        const char *how = e.problem == pipeline::SettingError::Problem::Missing ? " (give " : " (from ";
        log_message(ARBOR_LOG_ERROR, "", std::string(e.what()) + (flag.empty() ? "" : how + flag + ")"));
        return 2; // sessions report their own values as SessionError
    } catch (const pipeline::PluginNameError &e) {
        log_message(ARBOR_LOG_ERROR, "", e.what());
        return 2;
    } catch (const cli::UsageError &e) {
        log_message(ARBOR_LOG_ERROR, "", e.what());
        return 2;
    } catch (const std::exception &e) {
        if (interrupt.interrupted()) {
            log_message(ARBOR_LOG_ERROR, "", "cancelled");
            return 130;
        }
        log_message(ARBOR_LOG_ERROR, "", e.what());
        return 1;
    }
}
