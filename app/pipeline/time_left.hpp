// time_left.hpp - an estimate of the time a long stage has left, from how
// far it got and how long that took, for the terminal's progress line and the
// workstation's progress bar: "about 2 min 10 s left".
#pragma once

#include <optional>
#include <string>

namespace arbor::pipeline {

// Watches one stage's progress reports.  A new stage name, or a fraction
// that went back (the stage restarted), starts the clock again.
class StageClock {
public:
    // Seconds left at `fraction` in [0, 1], `now` seconds on any monotonic
    // clock; nothing until the stage has run 2 s and done 2 % (before that
    // the rate says more about start-up than about the stage).
    std::optional<double> observe(const std::string &stage, double fraction, double now);

private:
    std::string stage_;
    double start_ = 0.0;
    double last_fraction_ = 0.0;
    bool started_ = false;
};

// "about 45 s left", "about 2 min 10 s left", "about 1 h 05 min left";
// under 5 s: "a few seconds left".
std::string format_time_left(double seconds);

} // namespace arbor::pipeline
