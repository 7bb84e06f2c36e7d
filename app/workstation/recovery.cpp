#include "recovery.hpp"

#include "workstation.hpp"

#include "core/atomic_file.hpp"
#include "pipeline/session.hpp"

#include <algorithm>
#include <cstdlib>
#include <fstream>

namespace arbor::workstation {

namespace fs = std::filesystem;

fs::path state_folder()
{
    if (const char *own = std::getenv("ARBOR_STATE_DIR"); own && *own)
        return own;
    if (const char *xdg = std::getenv("XDG_STATE_HOME"); xdg && *xdg)
        return fs::path(xdg) / "arbor";
    if (const char *home = std::getenv("HOME"); home && *home)
        return fs::path(home) / ".local" / "state" / "arbor";
    return fs::temp_directory_path() / "arbor-state";
}

fs::path recovery_path() { return state_folder() / "recovery.arbor-session.json"; }

void Autosave::tick(Workstation &ws, double now)
{
    if (!ws.has_input() || now - last_ < 2)
        return;
    last_ = now;
    try {
        const pipeline::Document d = ws.pipeline().document();
        const std::string text = pipeline::session_text(d, ws.catalog(), path_.parent_path());
        if (text == saved_)
            return;
        fs::create_directories(path_.parent_path());
        pipeline::write_session(path_, d, ws.catalog());
        saved_ = text;
    } catch (const std::exception &e) {
        ws.say(ARBOR_LOG_WARNING, std::string("autosave: ") + e.what());
        last_ = now + 58; // tell again in a minute, not every frame
    }
}

void Autosave::finish()
{
    std::error_code ec;
    fs::remove(path_, ec);
}

std::vector<fs::path> recent_files()
{
    std::vector<fs::path> out;
    std::ifstream in(state_folder() / "recent.txt");
    std::string line;
    std::error_code ec;
    while (std::getline(in, line) && out.size() < 10)
        if (!line.empty() && fs::exists(line, ec))
            out.emplace_back(line);
    return out;
}

void add_recent_file(const fs::path &path)
{
    std::error_code ec;
    const fs::path absolute = fs::absolute(path, ec);
    std::vector<fs::path> list = recent_files();
    list.erase(std::remove(list.begin(), list.end(), absolute), list.end());
    list.insert(list.begin(), absolute);
    if (list.size() > 10)
        list.resize(10);
    std::string text;
    for (const fs::path &p : list)
        text += p.string() + "\n";
    fs::create_directories(state_folder(), ec);
    try {
        AtomicFile file(state_folder() / "recent.txt");
        file.write(text);
        file.commit();
    } catch (const std::exception &) {
        // The list is a convenience; a read-only home does not stop the work.
    }
}

} // namespace arbor::workstation
