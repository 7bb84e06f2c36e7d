// ttk_anchor.hpp - the TTK FTM reference times and memory, read from
// ../shared/reference/ttk/TIMINGS.md (measured once on this machine class,
// not re-run by the benchmark).
//
// The markdown table is parsed by its header names, not by position, so a
// column added or moved in TIMINGS.md does not silently shift the numbers.
#pragma once

#include <cstdint>
#include <filesystem>
#include <istream>
#include <optional>
#include <string>
#include <vector>

namespace arbor::bench {

struct TtkRow {
    int line = 0;              // 1-based line in TIMINGS.md
    std::string label;         // the whole "input" cell
    std::string input;         // its name ("blobs_256"); empty for prose labels
    std::string dims;
    int threads = 0;           // 0 when the column is missing
    int segm = -1;             // FTM arc segmentation: 1 on, 0 off, -1 unknown
    double seconds = 0.0;
    bool includes_read = false; // "(incl. read)": file reading was timed too
    double peak_bytes = 0.0;   // 0 when unparsable
    int64_t extrema = -1;      // -1 when not given ("—")
};

// Rows of the first markdown table whose header has an "input" column.
// Throws std::runtime_error when the table or a required column (input,
// segm, total, peak) is missing.
std::vector<TtkRow> parse_ttk_timings(std::istream &in);
std::vector<TtkRow> load_ttk_timings(const std::filesystem::path &file);

struct TtkAnchor {
    TtkRow row;
    std::string note;           // which line, and caveats ("only segm=0")
    std::vector<TtkRow> others; // the input's rows not used
};

// The row to compare `input` with.  Arbor always computes the segmentation,
// so a segm=1 row is preferred; among equals the fastest.  nullopt when
// TIMINGS.md has no row for `input`.
std::optional<TtkAnchor> choose_ttk_anchor(const std::vector<TtkRow> &rows, const std::string &input);

} // namespace arbor::bench
