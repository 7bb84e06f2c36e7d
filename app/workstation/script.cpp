#include "script.hpp"

#include "controls.hpp"
#include "workstation.hpp"

#include <cmath>
#include <map>
#include <sstream>

namespace arbor::workstation {

namespace {

// Command -> (least, most) arguments.
const std::map<std::string, std::pair<std::size_t, std::size_t>> &commands()
{
    static const std::map<std::string, std::pair<std::size_t, std::size_t>> table = {
        {"open", {1, 1}},          {"wait", {1, 2}},        {"set", {2, 2}},
        {"select", {1, 1}},        {"drag-threshold", {1, 1}}, {"orbit", {2, 2}},
        {"view", {1, 1}},          {"window-level", {2, 2}}, {"window-preset", {1, 1}},
        {"pick", {2, 2}},          {"hide", {1, 1}},        {"show", {1, 1}},
        {"branch-opacity", {2, 2}}, {"reset-styles", {0, 0}},          {"undo", {0, 0}},        {"redo", {0, 0}},
        {"screenshot", {1, 1}},    {"screenshot-window", {1, 1}}, {"save-session", {1, 1}},
        {"export-labels", {1, 1}}, {"export-tf", {1, 1}},   {"quit", {0, 0}},
        {"pacs-search", {1, 5}},   {"pacs-open", {1, 1}},    {"expect-error", {1, 1}},
        {"expect-frames", {1, 1}},
    };
    return table;
}

double number(const std::string &text, const std::string &what) { return parse_number(text, what); }

// Words split on blanks; the last argument of `open`, `set` and the file
// commands may contain blanks (a path): the rest of the line.
std::vector<std::string> words(const std::string &line, std::size_t max_args)
{
    std::vector<std::string> out;
    std::istringstream in(line);
    std::string w;
    in >> w;
    out.push_back(w);
    while (out.size() < max_args && in >> w)
        out.push_back(w);
    std::string rest;
    std::getline(in, rest);
    const auto first = rest.find_first_not_of(" \t");
    if (first != std::string::npos) {
        rest = rest.substr(first);
        rest.erase(rest.find_last_not_of(" \t\r") + 1);
        out.push_back(rest);
    }
    return out;
}

} // namespace

std::vector<ScriptLine> parse_script(const std::string &text, const std::string &name)
{
    std::vector<ScriptLine> out;
    std::istringstream in(text);
    std::string line;
    std::size_t number = 0;
    while (std::getline(in, line)) {
        ++number;
        if (!line.empty() && line.back() == '\r')
            line.pop_back();
        const auto first = line.find_first_not_of(" \t");
        if (first == std::string::npos || line[first] == '#')
            continue;
        std::istringstream head(line);
        std::string command;
        head >> command;
        const auto c = commands().find(command);
        if (c == commands().end())
            throw ScriptError(name + ":" + std::to_string(number) + ": unknown command '" + command + "'");
        const auto [least, most] = c->second;
        // A path or a value is the last argument and may hold blanks.
        std::vector<std::string> w = words(line.substr(first), most);
        ScriptLine l{number, command, {w.begin() + 1, w.end()}};
        if (l.args.size() < least || l.args.size() > most)
            throw ScriptError(name + ":" + std::to_string(number) + ": '" + command + "' takes " +
                              (least == most ? std::to_string(least) : std::to_string(least) + " to " + std::to_string(most)) +
                              " argument" + (most == 1 ? "" : "s") + ", not " + std::to_string(l.args.size()));
        if (command == "wait" && l.args[0] != "idle")
            throw ScriptError(name + ":" + std::to_string(number) + ": 'wait' takes 'idle' [SECONDS]");
        out.push_back(std::move(l));
    }
    return out;
}

std::string ScriptRunner::current() const
{
    if (done())
        return "";
    const ScriptLine &l = lines_[next_];
    std::string s = l.command;
    for (const std::string &a : l.args)
        s += " " + a;
    return s;
}

bool ScriptRunner::step(Workstation &ws, ScriptWindow &window)
{
    if (done())
        return false;
    const ScriptLine &line = lines_[next_];
    try {
        if (line.command == "expect-error") {
            // A test's step: the work must fail saying this.  The failure
            // comes when the job the last change started ends, so wait for
            // it rather than for idleness (which may come first).
            const auto now = std::chrono::steady_clock::now();
            if (!waiting_since_)
                waiting_since_ = now;
            const std::string error = ws.error();
            if (error.find(line.args[0]) == std::string::npos) {
                if (!error.empty() && ws.idle())
                    throw std::runtime_error("expected an error saying '" + line.args[0] + "', got '" + error + "'");
                if (std::chrono::duration<double>(now - *waiting_since_).count() > 600)
                    throw std::runtime_error("expected an error saying '" + line.args[0] + "', got none in 600 s");
                return true;
            }
            waiting_since_.reset();
        } else if (line.command == "wait") {
            const double limit = line.args.size() > 1 ? number(line.args[1], "wait idle") : 600.0;
            const auto now = std::chrono::steady_clock::now();
            if (!waiting_since_)
                waiting_since_ = now;
            if (!ws.idle() || window.busy()) {
                if (std::chrono::duration<double>(now - *waiting_since_).count() > limit)
                    throw std::runtime_error("still busy after " + std::to_string(static_cast<int>(limit)) + " s");
                return true;
            }
            waiting_since_.reset();
            if (!ws.error().empty())
                throw std::runtime_error(ws.error());
        } else {
            run(line, ws, window);
        }
    } catch (const std::exception &e) {
        throw ScriptError(name_ + ":" + std::to_string(line.number) + ": " + line.command + ": " + e.what());
    }
    ++next_;
    return !done();
}

void ScriptRunner::run(const ScriptLine &line, Workstation &ws, ScriptWindow &window)
{
    const std::string &c = line.command;
    const auto &a = line.args;
    if (c == "open")
        ws.open(a[0]);
    else if (c == "set")
        ws.set(a[0], a[1]);
    else if (c == "select")
        ws.select(a[0] == "none" ? std::nullopt : std::optional<int32_t>(static_cast<int32_t>(number(a[0], "select"))));
    else if (c == "drag-threshold")
        ws.drag_threshold(number(a[0], "drag-threshold"));
    else if (c == "orbit")
        ws.orbit(number(a[0], "azimuth"), number(a[1], "elevation"));
    else if (c == "view")
        ws.standard_view(a[0]);
    else if (c == "window-level")
        ws.window_level(number(a[0], "width"), number(a[1], "level"));
    else if (c == "window-preset")
        ws.window_preset(a[0]);
    else if (c == "pick") {
        if (!ws.pick(number(a[0], "x"), number(a[1], "y")))
            throw std::runtime_error("nothing opaque under (" + a[0] + ", " + a[1] + ")");
    } else if (c == "hide" || c == "show" || c == "branch-opacity") {
        const double label = number(a[0], c);
        if (label < 0 || label != std::floor(label))
            throw std::invalid_argument("'" + a[0] + "' is not a branch label");
        pipeline::BranchStyle style = ws.branch_style(static_cast<uint32_t>(label));
        if (c == "branch-opacity")
            style.opacity = number(a[1], "opacity");
        else
            style.visible = c == "show";
        ws.set_branch_style(static_cast<uint32_t>(label), style);
    } else if (c == "reset-styles") {
        ws.reset_branch_styles();
    } else if (c == "undo") {
        if (!ws.undo())
            throw std::runtime_error("nothing to undo");
    } else if (c == "redo") {
        if (!ws.redo())
            throw std::runtime_error("nothing to redo");
    } else if (c == "screenshot")
        ws.screenshot(a[0]);
    else if (c == "screenshot-window")
        window.capture_window(a[0]);
    else if (c == "expect-frames") {
        // A test's step: where the 3D view's latest frame was drawn.
        if (a[0] != "gpu" && a[0] != "image")
            throw std::runtime_error("'" + a[0] + "' is not a kind of frame (gpu or image)");
        const auto frame = ws.volume_view().latest();
        if (!frame)
            throw std::runtime_error("the 3D view has no frame");
        const char *kind = frame->gpu ? "gpu" : "image";
        if (a[0] != kind)
            throw std::runtime_error(std::string("the 3D view's frame is ") +
                                     (frame->gpu ? "drawn on the GPU" : "an image from the CPU") + ", not " +
                                     (a[0] == "gpu" ? "drawn on the GPU" : "an image"));
    }
    else if (c == "save-session")
        ws.save_session(a[0]);
    else if (c == "export-labels")
        ws.export_labels(a[0]);
    else if (c == "export-tf")
        ws.export_transfer_functions(a[0]);
    else if (c == "pacs-search")
        window.pacs_search(a[0], {a.begin() + 1, a.end()});
    else if (c == "pacs-open") {
        const double row = number(a[0], "pacs-open");
        if (row < 1 || row != std::floor(row))
            throw std::invalid_argument("'" + a[0] + "' is not a row (1, 2, ...)");
        window.pacs_open(static_cast<std::size_t>(row) - 1);
    } else if (c == "quit")
        window.quit();
}

} // namespace arbor::workstation
