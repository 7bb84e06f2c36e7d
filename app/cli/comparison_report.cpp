#include "comparison_report.hpp"

#include "io/topology_json.hpp"

#include <cmath>
#include <cstdio>
#include <sstream>

namespace arbor::cli {

namespace {

std::string fixed(double x, int digits)
{
    char buf[64];
    std::snprintf(buf, sizeof buf, "%.*f", digits, x);
    return buf;
}

std::string general(double x)
{
    char buf[64];
    std::snprintf(buf, sizeof buf, "%.6g", x);
    return buf;
}

// The CSV field for text that may hold commas or quotes.
std::string csv_text(const std::string &s)
{
    if (s.find_first_of(",\"\n") == std::string::npos)
        return s;
    std::string out = "\"";
    for (char c : s)
        out += c == '"' ? std::string("\"\"") : std::string(1, c);
    return out + "\"";
}

const topology::Branch &kept_branch(const ComparedSimplifier &c, std::size_t label)
{
    return c.run.branches.branches[c.run.cut.kept[label]];
}

} // namespace

void write_report_json(const std::filesystem::path &path, const ComparisonStudy &study)
{
    const pipeline::ContourTreeResult &topo = *study.tree;
    io::write_json_file(path, io::JsonLayout::indented, [&](io::JsonWriter &j) {
        j.field("format", "arbor-comparison/1");
        io::write_volume_summary(j, study.source, study.volume->geometry());
        io::write_contour_tree_summary(j, topo.tree, topo.seconds);
        {
            const io::JsonWriter::Scope cut = j.object("cut");
            if (study.request.keep)
                j.field("keep", *study.request.keep);
            else
                j.field("threshold", study.request.threshold.value_or(0.0));
        }
        {
            const io::JsonWriter::Scope simplifiers = j.array("simplifiers");
            for (const ComparedSimplifier &c : study.runs) {
                const SimplifiedTree &s = c.run;
                const io::JsonWriter::Scope o = j.object();
                j.field("id", s.id);
                j.field("name", s.name);
                j.field("version", s.version);
                j.field("seconds", s.seconds);
                j.field("branches", s.branches.branches.size());
                j.field("kept_count", s.cut.kept.size());
                io::write_kept_branches(j, "kept", topo.tree, *study.volume, s.branches, s.cut);
            }
        }
        {
            const io::JsonWriter::Scope overlaps = j.array("overlaps");
            for (const Overlap &o : study.overlaps) {
                const io::JsonWriter::Scope pair = j.object();
                j.field("a", study.runs[o.a].run.id);
                j.field("b", study.runs[o.b].run.id);
                j.field("shared", o.shared);
                j.field("only_a", o.only_a);
                j.field("only_b", o.only_b);
                j.field("jaccard", o.jaccard);
            }
        }
        if (!study.truth_source.empty()) {
            const io::JsonWriter::Scope truth = j.object("truth");
            j.field("source", study.truth_source);
            const io::JsonWriter::Scope labels = j.array("labels");
            for (const TruthScore &score : study.truth) {
                const io::JsonWriter::Scope label = j.object();
                j.field("label", score.truth_label);
                j.field("voxels", score.voxels);
                const io::JsonWriter::Scope dice = j.object("dice");
                for (std::size_t r = 0; r < study.runs.size(); ++r) {
                    const io::JsonWriter::Scope best = j.object(study.runs[r].run.id);
                    j.field("dice", score.best[r].dice);
                    j.field("kept_label", score.best[r].kept_label);
                }
            }
        }
        j.field("images", study.images);
    });
}

void write_report_csv(const std::filesystem::path &path, const ComparisonStudy &study)
{
    const topology::ContourTree &tree = study.tree->tree;
    AtomicFile file(path);
    file.write("simplifier,label,branch,kind,importance,extremum_vertex,extremum_x_mm,extremum_y_mm,extremum_z_mm,"
               "extremum_value,saddle_value");
    for (int m = 0; m < topology::kMeasureCount; ++m)
        file.write(std::string(",") + topology::measure_id(m));
    for (int m = 0; m < topology::kMeasureCount; ++m)
        file.write(std::string(",relative_") + topology::measure_id(m));
    file.write("\n");
    for (const ComparedSimplifier &c : study.runs) {
        const topology::BranchDecomposition &d = c.run.branches;
        for (std::size_t k = 0; k < c.run.cut.kept.size(); ++k) {
            const uint32_t b = c.run.cut.kept[k];
            const topology::Branch &br = d.branches[b];
            const uint32_t ext = tree.node_vertex[br.extremum_node];
            const auto pos = study.volume->geometry().position_of(ext);
            std::ostringstream row;
            row.precision(10);
            row << csv_text(c.run.id) << ',' << k << ',' << b << ',' << io::branch_kind_name(br.kind) << ','
                << (std::isinf(br.importance) ? 1.0 : br.importance) << ',' << ext << ',' << pos[0] << ',' << pos[1]
                << ',' << pos[2] << ',' << study.volume->value(ext) << ','
                << study.volume->value(tree.node_vertex[br.saddle_node]);
            for (int m = 0; m < topology::kMeasureCount; ++m)
                row << ',' << br.measures[static_cast<std::size_t>(m)];
            for (int m = 0; m < topology::kMeasureCount; ++m)
                row << ',' << d.relative(b, m);
            file.write(row.str() + "\n");
        }
    }
    file.commit();
}

void write_report_markdown(const std::filesystem::path &path, const ComparisonStudy &study)
{
    const pipeline::ContourTreeResult &topo = *study.tree;
    const Geometry &g = study.volume->geometry();
    std::ostringstream md;
    md << "# Simplifier comparison: " << study.source << "\n\n";
    md << "Volume " << g.dims[0] << " x " << g.dims[1] << " x " << g.dims[2] << ", contour tree of "
       << topo.tree.node_count() << " nodes computed once in " << fixed(topo.seconds, 3)
       << " s; every simplifier decomposes that tree with its own importance and is cut to "
       << study.request.describe() << ".\n\n";
    md << "| simplifier | version | branches | kept | seconds |\n|---|---|---:|---:|---:|\n";
    for (const ComparedSimplifier &c : study.runs)
        md << "| " << c.run.id << " | " << c.run.version << " | " << c.run.branches.branches.size() << " | "
           << c.run.cut.kept.size() << " | " << fixed(c.run.seconds, 3) << " |\n";

    md << "\n## Overlap of the kept sets\n\nKept branches of two simplifiers are the same structure when the extremum of each lies in the region the other labels; the root is left out.\n\n";
    md << "| a | b | shared | only a | only b | Jaccard |\n|---|---|---:|---:|---:|---:|\n";
    for (const Overlap &o : study.overlaps)
        md << "| " << study.runs[o.a].run.id << " | " << study.runs[o.b].run.id << " | " << o.shared << " | "
           << o.only_a << " | " << o.only_b << " | " << fixed(o.jaccard, 3) << " |\n";

    if (!study.truth_source.empty()) {
        md << "\n## Ground truth (" << study.truth_source << ")\n\nDice of each ground-truth label with the "
           << "best-matching kept branch region.\n\n| truth label | voxels |";
        for (const ComparedSimplifier &c : study.runs)
            md << " " << c.run.id << " |";
        md << "\n|---:|---:|";
        for (std::size_t r = 0; r < study.runs.size(); ++r)
            md << "---:|";
        md << "\n";
        for (const TruthScore &t : study.truth) {
            md << "| " << t.truth_label << " | " << t.voxels << " |";
            for (const TruthMatch &m : t.best)
                md << " " << fixed(m.dice, 3) << " (label " << m.kept_label << ") |";
            md << "\n";
        }
    }

    const topology::ContourTree &tree = topo.tree;
    for (const ComparedSimplifier &c : study.runs) {
        md << "\n## " << c.run.name << " (" << c.run.id << ")\n\n"
           << "| label | kind | extremum (mm) | value | persistence | volume (mm3) | importance |\n"
           << "|---:|---|---|---:|---:|---:|---:|\n";
        for (std::size_t k = 0; k < c.run.cut.kept.size(); ++k) {
            const topology::Branch &br = kept_branch(c, k);
            const uint32_t ext = tree.node_vertex[br.extremum_node];
            const auto pos = g.position_of(ext);
            md << "| " << k << " | " << io::branch_kind_name(br.kind) << " | (" << fixed(pos[0], 1) << ", "
               << fixed(pos[1], 1) << ", " << fixed(pos[2], 1) << ") | " << general(study.volume->value(ext))
               << " | " << general(br.measures[topology::kPersistence]) << " | "
               << general(br.measures[topology::kVolumeMm3]) << " | "
               << (std::isinf(br.importance) ? std::string("root") : general(br.importance)) << " |\n";
        }
    }
    if (!study.images.empty()) {
        md << "\n## Images\n\n";
        for (const std::string &image : study.images)
            md << "![" << image << "](" << image << ")\n\n";
    }
    AtomicFile file(path);
    file.write(md.str());
    file.commit();
}

} // namespace arbor::cli
