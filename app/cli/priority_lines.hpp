// priority_lines.hpp - the thesis' priority line window (Appendix A) as a
// PNG: one row per importance (persistence, volume, hypervolume, ITri...),
// the same branches along x in a fixed order in every row, a vertical line
// per branch whose height is its importance in that row, and the row's
// threshold as a horizontal line.  Lines above the threshold (kept) are
// coloured, the others grey.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

namespace arbor::cli {

struct PriorityRow {
    std::string name;
    std::vector<double> values; // one per branch (column), >= 0
    double threshold = 0.0;     // branches above it are kept
};

// Throws std::runtime_error naming the file when it cannot be written.
void write_priority_lines(const std::filesystem::path &path, const std::string &title,
                          const std::vector<PriorityRow> &rows);

} // namespace arbor::cli
