#include "isolation_flags.hpp"

#include "usage_error.hpp"

#include "pipeline/session.hpp"

#include <cmath>
#include <cstdlib>
#include <filesystem>

namespace arbor::cli {

namespace {

IsolationMode mode_of(const std::string &text, const std::string &from)
{
    try {
        return parse_isolation_mode(text);
    } catch (const std::invalid_argument &e) {
        throw UsageError(from + ": " + e.what());
    }
}

double seconds_of(const std::string &text, const std::string &from)
{
    char *end = nullptr;
    const double s = std::strtod(text.c_str(), &end);
    if (text.empty() || *end || !std::isfinite(s) || s <= 0)
        throw UsageError(from + ": '" + text + "' is not a number of seconds above 0");
    return s;
}

} // namespace

IsolationChoice isolation_from_command_line(int argc, char **argv)
{
    IsolationChoice choice;
    if (const char *e = std::getenv("ARBOR_ISOLATE"); e && *e)
        choice.mode = mode_of(e, "ARBOR_ISOLATE");
    if (const char *e = std::getenv("ARBOR_PLUGIN_TIMEOUT"); e && *e)
        choice.timeout_seconds = seconds_of(e, "ARBOR_PLUGIN_TIMEOUT");
    // A session runs its plugins as it was saved.
    for (int i = 1; i < argc; ++i) {
        const std::filesystem::path p = argv[i];
        std::error_code ec;
        if (p.extension() != ".json" || !std::filesystem::is_regular_file(p, ec))
            continue;
        if (const auto saved = pipeline::session_isolation(p)) {
            if (!saved->mode.empty())
                choice.mode = mode_of(saved->mode, p.string() + ": plugins.isolate");
            if (saved->timeout_seconds > 0)
                choice.timeout_seconds = saved->timeout_seconds;
        }
    }
    // The flags, as "--flag value" or "--flag=value".
    for (int i = 1; i < argc; ++i) {
        const std::string a = argv[i];
        for (const std::string flag : {"--isolate", "--plugin-timeout"}) {
            std::string value;
            if (a == flag) {
                if (i + 1 >= argc)
                    throw UsageError(flag + " needs a value");
                value = argv[i + 1];
            } else if (a.rfind(flag + "=", 0) == 0) {
                value = a.substr(flag.size() + 1);
            } else {
                continue;
            }
            if (flag == "--isolate")
                choice.mode = mode_of(value, flag);
            else
                choice.timeout_seconds = seconds_of(value, flag);
        }
    }
    return choice;
}

void add_isolation_options(CLI::App &app)
{
    // Applied before the plugins load (isolation_from_command_line); the
    // parser only has to accept them.
    static std::string mode;
    static double seconds = 0;
    app.add_option("--isolate", mode,
                   "Which plugin libraries run in a process of their own, so that a crash, hang or runaway "
                   "allocation in one cannot take Arbor down: all, third-party (every library outside Arbor's "
                   "plugin folder; the default) or none (env ARBOR_ISOLATE)")
        ->check(CLI::IsMember({"all", "third-party", "none"}));
    app.add_option("--plugin-timeout", seconds,
                   "Seconds an isolated plugin call may go without a sign of life (a reply, progress or a "
                   "cancellation poll) before it counts as hung and its process is stopped (default 60; env "
                   "ARBOR_PLUGIN_TIMEOUT)")
        ->check(CLI::PositiveNumber);
    app.fallthrough();
}

} // namespace arbor::cli
