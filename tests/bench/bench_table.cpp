#include "bench_table.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

namespace arbor::bench {

namespace {

constexpr const char *kHeaderFormat =
    "%-32s %-11s %-4s %10s %7s %7s %7s %7s %7s %8s | %8s %6s %6s %5s %7s | %9s %9s | %8s %8s %-6s %8s %6s\n";
constexpr const char *kRowFormat =
    "%-32s %-11s %-4s %10lld %7s %7s %7s %7s %7s %8s | %8s %6s %6s %5s %7s | %9lld %9lld | %8s %8s %-6s %8s %6s\n";

std::string fixed(double v, int decimals)
{
    if (!std::isfinite(v))
        return "-";
    char buf[64];
    std::snprintf(buf, sizeof buf, "%.*f", decimals, v);
    return buf;
}

// Seconds with 3 significant decimals for small values, fewer for large.
std::string seconds(double s)
{
    return fixed(s, s < 10 ? 3 : s < 100 ? 2 : 1);
}

std::string ratio(double r)
{
    return std::isfinite(r) ? fixed(r, r < 10 ? 2 : 1) + "x" : "-";
}

double megabytes(double bytes)
{
    return bytes / 1e6;
}

double speedup(const TableRow &r)
{
    return r.ttk && r.run.ok ? r.ttk->row.seconds / r.run.total_seconds : NAN;
}

double peak_per_voxel(const TableRow &r)
{
    return r.run.ok ? static_cast<double>(r.run.peak_rss) / static_cast<double>(r.run.voxels) : NAN;
}

double work_per_voxel(const TableRow &r)
{
    return r.run.ok ? (static_cast<double>(r.run.peak_rss) - static_cast<double>(r.run.base_rss)) /
                          static_cast<double>(r.run.voxels)
                    : NAN;
}

} // namespace

void print_header(std::ostream &out)
{
    char line[512];
    std::snprintf(line, sizeof line, kHeaderFormat, "input", "dims", "type", "voxels", "sort", "alloc", "trees", "merge",
                  "branch", "total s", "peak MB", "B/vx", "work", "in", "base MB", "nodes", "extrema", "TTK s",
                  "TTK MB", "row", "speed-up", "mem");
    out << line;
    out << std::string(std::string(line).size() - 1, '-') << '\n';
}

void print_row(std::ostream &out, const TableRow &row)
{
    const RunReport &r = row.run;
    if (!r.ok) {
        out << row.name << "  FAILED: " << r.error << std::endl;
        return;
    }
    const std::string dims =
        std::to_string(r.dims[0]) + "x" + std::to_string(r.dims[1]) + "x" + std::to_string(r.dims[2]);
    std::string ttk_s = "-", ttk_mb = "-", ttk_row = "-", speed = "-", mem = "-";
    if (row.ttk) {
        const TtkRow &t = row.ttk->row;
        ttk_s = seconds(t.seconds);
        ttk_mb = t.peak_bytes > 0 ? fixed(megabytes(t.peak_bytes), 0) : "-";
        ttk_row = "s" + std::to_string(t.segm) + "/" + std::to_string(t.threads) + "t";
        speed = ratio(speedup(row));
        mem = t.peak_bytes > 0 ? ratio(t.peak_bytes / static_cast<double>(r.peak_rss)) : "-";
    }
    // '*': the kernel did not reset the peak, so it may be the loader's.
    const std::string peak = fixed(megabytes(static_cast<double>(r.peak_rss)), 0) + (r.peak_reset ? "" : "*");
    char line[512];
    std::snprintf(line, sizeof line, kRowFormat, row.name.c_str(), dims.c_str(), arbor_voxel_type_name(r.voxel_type),
                  static_cast<long long>(r.voxels), seconds(r.stage_seconds[0]).c_str(),
                  seconds(r.stage_seconds[1]).c_str(), seconds(r.stage_seconds[2]).c_str(),
                  seconds(r.stage_seconds[3]).c_str(), seconds(r.stage_seconds[4]).c_str(), seconds(r.total_seconds).c_str(), peak.c_str(),
                  fixed(peak_per_voxel(row), 1).c_str(), fixed(work_per_voxel(row), 1).c_str(),
                  fixed(static_cast<double>(arbor_voxel_size(r.voxel_type)), 0).c_str(),
                  fixed(megabytes(static_cast<double>(r.base_rss)), 0).c_str(), static_cast<long long>(r.nodes),
                  static_cast<long long>(r.extrema), ttk_s.c_str(), ttk_mb.c_str(), ttk_row.c_str(),
                  speed.c_str(), mem.c_str());
    out << line << std::flush;
}

void print_anchor_notes(std::ostream &out, const std::vector<TableRow> &rows)
{
    bool any = false;
    for (const TableRow &r : rows) {
        if (!r.ttk)
            continue;
        if (!any)
            out << "\nTTK rows used (TIMINGS.md; row column sN/Mt = segm N, M threads):\n";
        any = true;
        out << "  " << r.name << ": " << r.ttk->note;
        // The rows left out, with the speed-up they would give: a segm=1 row
        // can have fewer threads than its segm=0 twin (blobs_384).
        for (const TtkRow &other : r.ttk->others) {
            out << "; not used: line " << other.line << " (segm=" << other.segm << ", " << other.threads << "t, "
                << seconds(other.seconds) << " s";
            if (r.run.ok)
                out << ", speed-up " << ratio(other.seconds / r.run.total_seconds);
            out << ")";
        }
        if (r.ttk->row.extrema >= 0)
            out << "; TTK extrema " << r.ttk->row.extrema << (r.run.ok ? ", ours " + std::to_string(r.run.extrema) : "");
        out << '\n';
    }
}

void print_summary(std::ostream &out, const std::vector<TableRow> &rows)
{
    std::vector<std::pair<double, std::string>> speedups;
    std::pair<double, std::string> max_peak{NAN, "-"}, max_work{NAN, "-"};
    int failed = 0;
    for (const TableRow &r : rows) {
        if (!r.run.ok) {
            ++failed;
            continue;
        }
        if (r.ttk)
            speedups.emplace_back(speedup(r), r.name);
        if (r.run.voxels >= kSummaryMinVoxels) {
            if (!(peak_per_voxel(r) <= max_peak.first))
                max_peak = {peak_per_voxel(r), r.name};
            if (!(work_per_voxel(r) <= max_work.first))
                max_work = {work_per_voxel(r), r.name};
        }
    }
    std::sort(speedups.begin(), speedups.end());
    out << "\nsummary: ";
    if (speedups.empty()) {
        out << "no input with a TTK anchor";
    } else {
        const std::size_t n = speedups.size();
        const double median = n % 2 ? speedups[n / 2].first : (speedups[n / 2 - 1].first + speedups[n / 2].first) / 2;
        out << "speed-up vs TTK FTM over " << n << " anchored inputs: min " << ratio(speedups.front().first) << " ("
            << speedups.front().second << "), median " << ratio(median);
    }
    out << "; max peak " << fixed(max_peak.first, 1) << " B/voxel (" << max_peak.second << "), max working "
        << fixed(max_work.first, 1) << " B/voxel (" << max_work.second << ") over inputs of >= "
        << kSummaryMinVoxels << " voxels";
    if (failed)
        out << "; " << failed << " input(s) FAILED";
    out << std::endl;
}

} // namespace arbor::bench
