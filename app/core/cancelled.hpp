// cancelled.hpp - how long work stops when it is asked to: the caller's
// std::stop_token is polled between chunks of work and the work unwinds with
// Cancelled.  There is no process-wide flag: every job owns its own stop
// source, so cancelling one job leaves the others running (the CLI's Ctrl-C
// cancels the jobs of its own pipeline).
#pragma once

#include <stdexcept>
#include <stop_token>

namespace arbor {

class Cancelled : public std::runtime_error {
public:
    Cancelled() : std::runtime_error("cancelled") {}
};

inline void throw_if_stopped(const std::stop_token &stop)
{
    if (stop.stop_requested())
        throw Cancelled();
}

} // namespace arbor
