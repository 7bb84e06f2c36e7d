#include "conformance.hpp"

#include "conformance_checks.hpp"
#include "plugin_library.hpp"

#include <poll.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstring>
#include <sstream>

namespace arbor {

namespace fs = std::filesystem;

int ConformanceReport::failures() const
{
    int n = 0;
    for (const auto &c : checks)
        n += c.passed ? 0 : 1;
    return n;
}

namespace {

// Line protocol from the child: "B\tplugin\tcheck", "R\tplugin\tcheck\t0|1\tdetail",
// "P\tplugin-id" (a plugin to check next).
std::string clean(std::string s)
{
    for (char &c : s)
        if (c == '\t' || c == '\n' || c == '\r')
            c = ' ';
    return s;
}

class PipeSink : public CheckSink {
public:
    explicit PipeSink(int fd) : fd_(fd) {}
    void begin(const std::string &plugin, const std::string &check) override
    {
        send("B\t" + clean(plugin) + "\t" + clean(check) + "\n");
    }
    void result(const std::string &plugin, const std::string &check, bool passed,
                const std::string &detail) override
    {
        send("R\t" + clean(plugin) + "\t" + clean(check) + "\t" + (passed ? "1" : "0") + "\t" +
             clean(detail) + "\n");
    }
    void send(const std::string &line)
    {
        const char *p = line.data();
        std::size_t left = line.size();
        while (left > 0) {
            const ssize_t w = ::write(fd_, p, left);
            if (w <= 0)
                return;
            p += w;
            left -= static_cast<std::size_t>(w);
        }
    }

private:
    int fd_;
};

struct ChildOutcome {
    std::vector<ConformanceCheck> checks;
    std::vector<std::string> plugins; // "P" lines
};

// Runs `work` in a child process and collects what it reports.  A crash or a
// timeout becomes a failed check naming the check that was running.
template <class Work>
ChildOutcome run_child(const std::string &subject, std::chrono::seconds timeout, Work &&work)
{
    ChildOutcome out;
    int fds[2];
    if (pipe(fds) != 0) {
        out.checks.push_back({subject, "isolation", false, std::string("pipe: ") + std::strerror(errno)});
        return out;
    }
    const pid_t pid = fork();
    if (pid < 0) {
        close(fds[0]);
        close(fds[1]);
        out.checks.push_back({subject, "isolation", false, std::string("fork: ") + std::strerror(errno)});
        return out;
    }
    if (pid == 0) {
        close(fds[0]);
        PipeSink sink(fds[1]);
        work(sink);
        close(fds[1]);
        _exit(0);
    }
    close(fds[1]);

    std::string buffer, running_plugin = subject, running_check = "loading";
    bool finished_check = true;
    const auto deadline = std::chrono::steady_clock::now() + timeout;
    bool timed_out = false;
    char chunk[4096];
    for (;;) {
        const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(
            deadline - std::chrono::steady_clock::now());
        if (left.count() <= 0) {
            timed_out = true;
            break;
        }
        pollfd pfd{fds[0], POLLIN, 0};
        const int r = poll(&pfd, 1, static_cast<int>(left.count()));
        if (r < 0 && errno == EINTR)
            continue;
        if (r <= 0) {
            timed_out = r == 0;
            break;
        }
        const ssize_t n = read(fds[0], chunk, sizeof chunk);
        if (n <= 0)
            break;
        buffer.append(chunk, static_cast<std::size_t>(n));
        std::size_t nl;
        while ((nl = buffer.find('\n')) != std::string::npos) {
            const std::string line = buffer.substr(0, nl);
            buffer.erase(0, nl + 1);
            std::vector<std::string> f;
            std::stringstream ss(line);
            std::string part;
            while (std::getline(ss, part, '\t'))
                f.push_back(part);
            if (line.rfind("B\t", 0) == 0 && f.size() >= 3) {
                running_plugin = f[1];
                running_check = f[2];
                finished_check = false;
            } else if (line.rfind("R\t", 0) == 0 && f.size() >= 4) {
                out.checks.push_back({f[1], f[2], f[3] == "1", f.size() > 4 ? f[4] : ""});
                finished_check = true;
            } else if (line.rfind("P\t", 0) == 0 && f.size() >= 2) {
                out.plugins.push_back(f[1]);
            }
        }
    }
    close(fds[0]);
    if (timed_out)
        kill(pid, SIGKILL);
    int status = 0;
    waitpid(pid, &status, 0);
    const std::string where = finished_check ? "after its last check" : "during '" + running_check + "'";
    if (timed_out)
        out.checks.push_back({running_plugin, running_check, false,
                              "did not finish within " + std::to_string(timeout.count()) + " s " + where});
    else if (WIFSIGNALED(status))
        out.checks.push_back({running_plugin, running_check, false,
                              std::string("crashed with signal ") + std::to_string(WTERMSIG(status)) +
                                  " (" + strsignal(WTERMSIG(status)) + ") " + where});
    else if (!WIFEXITED(status) || WEXITSTATUS(status) != 0)
        out.checks.push_back({running_plugin, running_check, false,
                              "exited with status " + std::to_string(WEXITSTATUS(status)) + " " + where});
    return out;
}

} // namespace

ConformanceReport check_plugin_conformance(const fs::path &library, std::chrono::seconds timeout)
{
    ConformanceReport report;
    report.library = library.string();
    std::error_code ec;
    const fs::path path = fs::absolute(library, ec);
    const fs::path scratch = fs::temp_directory_path(ec) / ("arbor-plugin-check-" + std::to_string(getpid()));

    // Library level: load (ABI version, entry, init) and descriptors.
    ChildOutcome lib = run_child("", timeout, [&](PipeSink &sink) {
        sink.begin("", "load");
        std::unique_ptr<PluginLibrary> loaded;
        try {
            loaded = PluginLibrary::load(path);
        } catch (const std::exception &e) {
            sink.result("", "load", false, path.string() + " " + e.what());
            return;
        }
        sink.result("", "load", true, "");
        for (const PluginRefusal &r : loaded->refusals())
            sink.result(r.plugin_id, "descriptor", false, r.reason);
        HostIdentity host("plugin-check");
        check_entry(loaded->entry(), host.get(), sink);
        for (const arbor_plugin_descriptor *d : loaded->descriptors())
            sink.send(std::string("P\t") + clean(d->id) + "\n");
    });
    report.checks = lib.checks;

    // One child per plugin, so one crash loses only that plugin's checks.
    for (const std::string &id : lib.plugins) {
        ChildOutcome one = run_child(id, timeout, [&](PipeSink &sink) {
            std::unique_ptr<PluginLibrary> loaded;
            try {
                loaded = PluginLibrary::load(path);
            } catch (const std::exception &e) {
                sink.result(id, "load", false, e.what());
                return;
            }
            for (const arbor_plugin_descriptor *d : loaded->descriptors()) {
                if (id != d->id)
                    continue;
                const fs::path dir = scratch / id;
                std::error_code e2;
                fs::create_directories(dir, e2);
                HostIdentity host(id);
                check_plugin(loaded->entry(), host.get(), *d, dir, sink);
            }
        });
        report.checks.insert(report.checks.end(), one.checks.begin(), one.checks.end());
    }
    fs::remove_all(scratch, ec);
    return report;
}

} // namespace arbor
