// fastest_run.hpp - the fastest of several runs of a piece of work, in
// seconds: the benchmarks' measure of a short operation.
#pragma once

#include "core/stopwatch.hpp"

#include <algorithm>
#include <functional>

namespace arbor::bench {

inline double fastest_seconds(const std::function<void()> &work, int repeat)
{
    double best = 1e30;
    for (int r = 0; r < repeat; ++r) {
        Stopwatch watch;
        work();
        best = std::min(best, watch.lap());
    }
    return best;
}

} // namespace arbor::bench
