#include "time_left.hpp"

#include <cmath>
#include <cstdio>

namespace arbor::pipeline {

std::optional<double> StageClock::observe(const std::string &stage, double fraction, double now)
{
    if (!started_ || stage != stage_ || fraction < last_fraction_) {
        stage_ = stage;
        start_ = now;
        started_ = true;
        last_fraction_ = fraction;
        return std::nullopt;
    }
    last_fraction_ = fraction;
    const double elapsed = now - start_;
    if (elapsed < 2.0 || fraction < 0.02 || fraction >= 1.0)
        return std::nullopt;
    return elapsed * (1.0 - fraction) / fraction;
}

std::string format_time_left(double seconds)
{
    char text[48];
    const long s = std::lround(seconds);
    if (s < 5)
        return "a few seconds left";
    if (s < 60)
        std::snprintf(text, sizeof text, "about %ld s left", s);
    else if (s < 3600)
        std::snprintf(text, sizeof text, "about %ld min %02ld s left", s / 60, s % 60);
    else
        std::snprintf(text, sizeof text, "about %ld h %02ld min left", s / 3600, s / 60 % 60);
    return text;
}

} // namespace arbor::pipeline
