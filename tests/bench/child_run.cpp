#include "child_run.hpp"

#include "core/resident_memory.hpp"
#include "topology/topology_pipeline.hpp"

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cmath>
#include <csignal>
#include <cstdio>
#include <cstring>
#include <iostream>
#include <limits>
#include <stdexcept>
#include <type_traits>
#include <utility>

#include <malloc.h>
#include <sched.h>
#include <sys/wait.h>
#include <unistd.h>

namespace arbor::bench {

namespace {

// What crosses the pipe: a flat, trivially copyable record (both sides are
// the same binary, so no serialisation format is needed).
struct WireReport {
    bool ok;
    char error[512];
    int64_t dims[3];
    int32_t voxel_type;
    int64_t voxels;
    double load_seconds;
    double total_seconds;
    double stage_seconds[kStageNames.size()];
    int32_t repeats;
    uint64_t base_rss, peak_rss;
    bool peak_reset;
    int64_t nodes, extrema;
};
static_assert(std::is_trivially_copyable_v<WireReport>);

void measure(const VolumeLoader &load, int repeats, WireReport &out)
{
    const auto t0 = std::chrono::steady_clock::now();
    Volume volume = load();
    out.load_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    const Geometry &g = volume.geometry();
    std::copy(g.dims.begin(), g.dims.end(), out.dims);
    out.voxel_type = volume.type();
    out.voxels = volume.voxel_count();

    const topology::ImportanceFn importance = topology::persistence_importance();
    out.total_seconds = std::numeric_limits<double>::infinity();
    for (int r = 0; r < repeats; ++r) {
        // Hand the importer's (or the previous run's) freed heap back, so the
        // baseline is what is really in use.
        malloc_trim(0);
        if (r == 0) {
            out.base_rss = resident_bytes();
            reset_peak_resident_bytes();
            // The reset sets VmHWM to the current RSS; if it is well above,
            // the kernel ignored it and the peak may be the loader's.
            out.peak_reset = peak_resident_bytes() <= out.base_rss + (4u << 20);
        }
        const topology::TopologyResult result = topology::compute_topology(volume, importance);
        if (r == 0) {
            out.peak_rss = peak_resident_bytes();
            out.nodes = static_cast<int64_t>(result.tree.node_count());
            out.extrema = std::count_if(result.tree.node_kind.begin(), result.tree.node_kind.end(),
                                        [](topology::NodeKind k) {
                                            return k == topology::NodeKind::Minimum ||
                                                   k == topology::NodeKind::Maximum;
                                        });
        }
        out.repeats = r + 1;
        if (result.total_seconds < out.total_seconds) {
            out.total_seconds = result.total_seconds;
            for (std::size_t s = 0; s < kStageNames.size(); ++s) {
                out.stage_seconds[s] = std::numeric_limits<double>::quiet_NaN();
                for (const topology::StageTiming &t : result.timings)
                    if (t.stage == kStageNames[s])
                        out.stage_seconds[s] = t.seconds;
            }
        }
    }
    out.ok = true;
}

bool write_all(int fd, const void *data, std::size_t size)
{
    const char *p = static_cast<const char *>(data);
    while (size > 0) {
        const ssize_t n = write(fd, p, size);
        if (n < 0 && errno == EINTR)
            continue;
        if (n <= 0)
            return false;
        p += n;
        size -= static_cast<std::size_t>(n);
    }
    return true;
}

std::size_t read_all(int fd, void *data, std::size_t size)
{
    char *p = static_cast<char *>(data);
    std::size_t got = 0;
    while (got < size) {
        const ssize_t n = read(fd, p + got, size - got);
        if (n < 0 && errno == EINTR)
            continue;
        if (n <= 0)
            break;
        got += static_cast<std::size_t>(n);
    }
    return got;
}

// The first `cores` CPUs of the set this process may use.
void pin_to_cores(int cores)
{
    cpu_set_t allowed;
    CPU_ZERO(&allowed);
    if (sched_getaffinity(0, sizeof allowed, &allowed) != 0)
        throw std::runtime_error(std::string("sched_getaffinity: ") + std::strerror(errno));
    if (CPU_COUNT(&allowed) < cores)
        throw std::runtime_error(std::to_string(cores) + " cores asked, " + std::to_string(CPU_COUNT(&allowed)) +
                                 " available");
    cpu_set_t chosen;
    CPU_ZERO(&chosen);
    for (int cpu = 0, taken = 0; cpu < CPU_SETSIZE && taken < cores; ++cpu)
        if (CPU_ISSET(cpu, &allowed)) {
            CPU_SET(cpu, &chosen);
            ++taken;
        }
    if (sched_setaffinity(0, sizeof chosen, &chosen) != 0)
        throw std::runtime_error(std::string("sched_setaffinity: ") + std::strerror(errno));
}

[[noreturn]] void child_main(int fd, const VolumeLoader &load, int repeats, int cores)
{
    WireReport out{};
    try {
        if (cores > 0)
            pin_to_cores(cores);
        measure(load, repeats, out);
    } catch (const std::exception &e) {
        std::snprintf(out.error, sizeof out.error, "%s", e.what());
    } catch (...) {
        std::snprintf(out.error, sizeof out.error, "unknown exception");
    }
    const bool sent = write_all(fd, &out, sizeof out);
    close(fd);
    // _exit: no atexit handlers or stdio flushing of the parent's state.
    _exit(sent ? 0 : 3);
}

RunReport failure(std::string message)
{
    RunReport r;
    r.error = std::move(message);
    return r;
}

RunReport from_wire(const WireReport &w)
{
    RunReport r;
    r.ok = w.ok;
    r.error = w.error;
    std::copy(std::begin(w.dims), std::end(w.dims), r.dims.begin());
    r.voxel_type = static_cast<arbor_voxel_type>(w.voxel_type);
    r.voxels = w.voxels;
    r.load_seconds = w.load_seconds;
    r.total_seconds = w.total_seconds;
    std::copy(std::begin(w.stage_seconds), std::end(w.stage_seconds), r.stage_seconds.begin());
    r.repeats = w.repeats;
    r.base_rss = w.base_rss;
    r.peak_rss = w.peak_rss;
    r.peak_reset = w.peak_reset;
    r.nodes = w.nodes;
    r.extrema = w.extrema;
    return r;
}

} // namespace

RunReport run_in_child(const VolumeLoader &load, int repeats, int cores)
{
    int fds[2];
    if (pipe(fds) != 0)
        return failure(std::string("pipe: ") + std::strerror(errno));
    std::cout.flush();
    std::cerr.flush();
    std::fflush(nullptr);
    const pid_t pid = fork();
    if (pid < 0) {
        close(fds[0]);
        close(fds[1]);
        return failure(std::string("fork: ") + std::strerror(errno));
    }
    if (pid == 0) {
        close(fds[0]);
        child_main(fds[1], load, repeats, cores);
    }
    close(fds[1]);
    WireReport wire{};
    const std::size_t got = read_all(fds[0], &wire, sizeof wire);
    close(fds[0]);
    int status = 0;
    while (waitpid(pid, &status, 0) < 0 && errno == EINTR) {
    }
    if (got == sizeof wire)
        return from_wire(wire);
    RunReport failed;
    if (WIFSIGNALED(status))
        failed.error = std::string("child killed by signal ") + std::to_string(WTERMSIG(status)) + " (" +
                       strsignal(WTERMSIG(status)) + (WTERMSIG(status) == SIGKILL ? "; out of memory?" : "") +
                       ")";
    else
        failed.error = "child exited with status " + std::to_string(WEXITSTATUS(status)) + " without a report";
    return failed;
}

} // namespace arbor::bench
