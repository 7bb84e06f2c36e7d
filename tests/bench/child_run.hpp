// child_run.hpp - one input's measurement in a child process.
//
// The child (pinned to `cores` CPUs when asked) loads the volume (not timed), resets the peak resident size, and
// runs the topology pipeline `repeats` times.  A fresh process per input makes
// the peak memory that input's alone (no heap kept from earlier inputs) and
// turns a crash or an out-of-memory kill into one failed row instead of the
// end of the benchmark.
#pragma once

#include "core/volume.hpp"

#include <array>
#include <cstdint>
#include <functional>
#include <string>

namespace arbor::bench {

// The pipeline's stages, in the order of TopologyResult::timings.
// "memory": faulting in the sweeps' state, seconds on a virtual machine.
inline constexpr std::array<const char *, 5> kStageNames = {"sort", "memory", "join+split trees", "merge",
                                                            "branches+measures"};

struct RunReport {
    bool ok = false;
    std::string error;
    std::array<int64_t, 3> dims{};
    arbor_voxel_type voxel_type = ARBOR_VOXEL_UNKNOWN;
    int64_t voxels = 0;
    double load_seconds = 0.0;
    // The fastest repetition: its total and its stages (so they add up).
    double total_seconds = 0.0;
    std::array<double, kStageNames.size()> stage_seconds{}; // NaN: stage not reported
    int repeats = 0;
    // Resident size after loading (process, libraries and the input), and the
    // peak during the first run, which sees memory as a fresh process does.
    uint64_t base_rss = 0;
    uint64_t peak_rss = 0;
    bool peak_reset = true; // false: the kernel refused to reset VmHWM
    int64_t nodes = 0;
    int64_t extrema = 0; // minima and maxima of the contour tree
};

using VolumeLoader = std::function<Volume()>;

// `cores` > 0 pins the child to that many of the CPUs it may run on (the
// lowest-numbered), before it loads anything: threads beyond them share them.
RunReport run_in_child(const VolumeLoader &load, int repeats, int cores = 0);

} // namespace arbor::bench
