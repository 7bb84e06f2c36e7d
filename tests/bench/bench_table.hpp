// bench_table.hpp - the benchmark's printed table: one row per input as soon
// as it is measured, then which TIMINGS.md rows were used, then a summary.
//
// Ratios are TTK / Arbor, so larger is better for Arbor in both: "speed-up"
// is TTK seconds / our seconds, "mem" is TTK peak RSS / our peak RSS.
#pragma once

#include "child_run.hpp"
#include "ttk_anchor.hpp"

#include <optional>
#include <ostream>
#include <string>
#include <vector>

namespace arbor::bench {

struct TableRow {
    std::string name;
    RunReport run;
    std::optional<TtkAnchor> ttk;
};

// Inputs below this many voxels are left out of the summary's memory maximum:
// there the process itself (libraries, ~20-50 MB) dominates bytes per voxel.
inline constexpr int64_t kSummaryMinVoxels = int64_t{1} << 20;

void print_header(std::ostream &out);
void print_row(std::ostream &out, const TableRow &row);
// Which TIMINGS.md row anchors each input, and why.
void print_anchor_notes(std::ostream &out, const std::vector<TableRow> &rows);
// "summary: ..." - min and median speed-up over inputs with an anchor, and the
// maximum peak bytes per voxel.
void print_summary(std::ostream &out, const std::vector<TableRow> &rows);

} // namespace arbor::bench
