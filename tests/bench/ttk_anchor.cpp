#include "ttk_anchor.hpp"

#include <algorithm>
#include <cctype>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <tuple>

namespace arbor::bench {

namespace {

std::string trim(const std::string &s)
{
    const auto first = s.find_first_not_of(" \t\r");
    if (first == std::string::npos)
        return {};
    return s.substr(first, s.find_last_not_of(" \t\r") - first + 1);
}

std::string lower(std::string s)
{
    std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return std::tolower(c); });
    return s;
}

// "| a | b |" -> {"a", "b"}; the outer pipes are optional in markdown.
std::vector<std::string> split_cells(std::string line)
{
    line = trim(line);
    if (!line.empty() && line.front() == '|')
        line.erase(0, 1);
    if (!line.empty() && line.back() == '|')
        line.pop_back();
    std::vector<std::string> cells;
    std::stringstream ss(line);
    std::string cell;
    while (std::getline(ss, cell, '|'))
        cells.push_back(trim(cell));
    return cells;
}

bool is_separator(const std::vector<std::string> &cells)
{
    return std::all_of(cells.begin(), cells.end(), [](const std::string &c) {
        return !c.empty() && c.find_first_not_of("-: ") == std::string::npos;
    });
}

// The first number in `text` ("21.7 (incl. read)" -> 21.7); nullopt if none.
std::optional<double> leading_number(const std::string &text)
{
    const auto at = text.find_first_of("0123456789.");
    if (at == std::string::npos)
        return std::nullopt;
    char *end = nullptr;
    const double v = std::strtod(text.c_str() + at, &end);
    if (end == text.c_str() + at)
        return std::nullopt;
    return v;
}

// "79 MB", "4.7 GB", "512 MiB" -> bytes (MB/GB decimal, MiB/GiB binary).
double parse_bytes(const std::string &text)
{
    const std::optional<double> v = leading_number(text);
    if (!v)
        return 0.0;
    const std::string t = lower(text);
    const auto has = [&](const char *unit) { return t.find(unit) != std::string::npos; };
    if (has("gib"))
        return *v * 1073741824.0;
    if (has("mib"))
        return *v * 1048576.0;
    if (has("kib"))
        return *v * 1024.0;
    if (has("gb"))
        return *v * 1e9;
    if (has("mb"))
        return *v * 1e6;
    if (has("kb"))
        return *v * 1e3;
    return *v;
}

// "1 996 460" (any kind of thousands space) -> 1996460; "—" -> -1.
int64_t parse_count(const std::string &text)
{
    std::string digits;
    for (char c : text)
        if (c >= '0' && c <= '9')
            digits += c;
    return digits.empty() ? -1 : std::stoll(digits);
}

// "blobs_64 (smooth)" -> "blobs_64"; "tooth (real)" -> "tooth"; a prose
// label ("a real T1 head MR (not shared)") is no input name -> "".
std::string input_name(const std::string &label)
{
    const std::string name = trim(label.substr(0, label.find('(')));
    const bool word = !name.empty() && std::all_of(name.begin(), name.end(), [](unsigned char c) {
        return std::isalnum(c) || c == '_' || c == '-';
    });
    return word ? name : std::string();
}

int find_column(const std::vector<std::string> &header, const std::string &prefix)
{
    for (std::size_t i = 0; i < header.size(); ++i)
        if (lower(header[i]).rfind(prefix, 0) == 0)
            return static_cast<int>(i);
    return -1;
}

} // namespace

std::vector<TtkRow> parse_ttk_timings(std::istream &in)
{
    std::vector<TtkRow> rows;
    std::vector<std::string> header;
    int c_input = -1, c_dims = -1, c_threads = -1, c_segm = -1, c_total = -1, c_peak = -1, c_extrema = -1;
    std::string line;
    int number = 0;
    bool in_table = false;
    while (std::getline(in, line)) {
        ++number;
        const bool table_line = trim(line).rfind('|', 0) == 0;
        if (!table_line) {
            if (in_table && !rows.empty())
                break; // the table ended: later tables are something else
            in_table = false;
            header.clear();
            continue;
        }
        const std::vector<std::string> cells = split_cells(line);
        if (!in_table) {
            header = cells;
            c_input = find_column(header, "input");
            if (c_input < 0)
                continue; // some other table
            c_dims = find_column(header, "dims");
            c_threads = find_column(header, "threads");
            c_segm = find_column(header, "segm");
            c_total = find_column(header, "total");
            c_peak = find_column(header, "peak");
            c_extrema = find_column(header, "extrema");
            if (c_segm < 0 || c_total < 0 || c_peak < 0)
                throw std::runtime_error("TIMINGS.md line " + std::to_string(number) +
                                         ": the table lacks a segm, total or peak column");
            in_table = true;
            continue;
        }
        if (is_separator(cells))
            continue;
        const auto cell = [&](int c) { return c >= 0 && c < static_cast<int>(cells.size()) ? cells[c] : ""; };
        TtkRow row;
        row.line = number;
        row.label = cell(c_input);
        row.input = input_name(row.label);
        row.dims = cell(c_dims);
        row.threads = static_cast<int>(leading_number(cell(c_threads)).value_or(0));
        row.segm = static_cast<int>(leading_number(cell(c_segm)).value_or(-1));
        const std::optional<double> seconds = leading_number(cell(c_total));
        if (!seconds)
            continue; // a row without a time anchors nothing
        row.seconds = *seconds;
        row.includes_read = lower(cell(c_total)).find("read") != std::string::npos;
        row.peak_bytes = parse_bytes(cell(c_peak));
        row.extrema = parse_count(cell(c_extrema));
        rows.push_back(row);
    }
    if (rows.empty())
        throw std::runtime_error("TIMINGS.md: no table with an input column and rows");
    return rows;
}

std::vector<TtkRow> load_ttk_timings(const std::filesystem::path &file)
{
    std::ifstream in(file);
    if (!in)
        throw std::runtime_error("cannot read " + file.string());
    return parse_ttk_timings(in);
}

std::optional<TtkAnchor> choose_ttk_anchor(const std::vector<TtkRow> &rows, const std::string &input)
{
    std::vector<const TtkRow *> candidates;
    for (const TtkRow &r : rows)
        if (r.input == input)
            candidates.push_back(&r);
    if (candidates.empty())
        return std::nullopt;
    // Best first: segm=1, then timing without file reading, then fastest.
    const auto rank = [](const TtkRow *r) { return std::make_tuple(r->segm != 1, r->includes_read, r->seconds); };
    std::sort(candidates.begin(), candidates.end(),
              [&](const TtkRow *a, const TtkRow *b) { return rank(a) < rank(b); });
    TtkAnchor anchor{*candidates.front(), "", {}};
    std::ostringstream note;
    const TtkRow &r = anchor.row;
    note << "line " << r.line << " (segm=" << r.segm << ", " << r.threads << " thread"
         << (r.threads == 1 ? "" : "s") << ")";
    if (r.segm != 1)
        note << "; only segm=0 (TTK without the segmentation Arbor computes: speed-up conservative)";
    if (r.includes_read)
        note << "; TTK's time includes reading the file";
    anchor.note = note.str();
    for (std::size_t i = 1; i < candidates.size(); ++i)
        anchor.others.push_back(*candidates[i]);
    return anchor;
}

} // namespace arbor::bench
