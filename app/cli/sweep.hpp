// sweep.hpp - comparison studies from one command line: --simplifier, --keep,
// --flow-rate, --shape and --hues of `arbor run` take comma lists, and every
// combination is one point of the sweep.  Points are ordered so the stages
// upstream change least often (simplifier outermost, then the cut, then the
// look), which lets the pipeline compute each decomposition and cut once.
#pragma once

#include <optional>
#include <string>
#include <vector>

namespace arbor::cli {

// The values of one point; unset members keep the document's value.
struct SweepPoint {
    std::optional<std::string> simplifier, keep, flow_rate, shape, hues;
    // "itri-k16-q30-ramp": the values of the swept flags only, file-name safe.
    std::string name;
    // "itri, keep 16, Q 30, ramp": for the contact sheet and the report.
    std::string caption;
};

struct SweepAxes {
    std::vector<std::string> simplifiers, keeps, flow_rates, shapes, hues;
};

// Every combination (one point when nothing is swept).
std::vector<SweepPoint> sweep_points(const SweepAxes &axes);

// Throws std::invalid_argument when a flag other commands take once was
// given a list.
void refuse_lists(const SweepAxes &axes, const std::string &command);

} // namespace arbor::cli
