#include "comparison_report.hpp"

#include "io/json_writer.hpp"
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
    std::snprintf(buf, sizeof buf, "%.10g", x);
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

void write_point(io::JsonWriter &j, std::string_view key, const TreePoint &p)
{
    const io::JsonWriter::Scope point = j.object(key);
    j.field("node", p.node);
    j.field("vertex", p.vertex);
    j.field("ijk", p.ijk);
    j.field("position_mm", p.position_mm);
    j.field("value", p.value);
}

void write_kept(io::JsonWriter &j, const std::vector<KeptRecord> &kept)
{
    const io::JsonWriter::Scope list = j.array("kept");
    for (const KeptRecord &r : kept) {
        const io::JsonWriter::Scope o = j.object();
        j.field("label", r.label);
        j.field("branch", r.branch);
        j.field("parent_label", r.parent_label);
        j.field("kind", io::branch_kind_name(r.kind));
        j.field("depth", r.depth);
        j.field("importance", r.importance);
        write_point(j, "extremum", r.extremum);
        write_point(j, "saddle", r.saddle);
        io::write_measures(j, "measures", r.measures);
        io::write_measures(j, "relative_measures", r.relative);
    }
}

void write_match(io::JsonWriter &j, std::string_view key, const study::RegionMatch &m)
{
    const io::JsonWriter::Scope o = j.object(key);
    if (m.region >= 0)
        j.field("kept_label", m.region);
    else
        j.key("kept_label"), j.null();
    j.field("dice", m.dice);
    j.field("precision", m.precision);
    j.field("recall", m.recall);
    j.field("overlap_voxels", m.overlap);
    j.field("region_voxels", m.region_voxels);
}

void write_setting(io::JsonWriter &j, const pipeline::PluginSetting &s)
{
    j.field("id", s.id);
    j.field("version", s.version);
    const io::JsonWriter::Scope params = j.object("parameters");
    for (const auto &[key, value] : s.params)
        j.field(key, value);
}

void write_filter_results(io::JsonWriter &j, const StudyOutcome &study, const FilterOutcome &f);

} // namespace

std::string cut_name(const pipeline::CutChoice &cut) { return cut.describe(); }

void write_report_json(const std::filesystem::path &path, const StudyReport &report)
{
    const StudyOutcome &study = *report.study;
    io::write_json_file(path, io::JsonLayout::indented, [&](io::JsonWriter &j) {
        j.field("format", "arbor-comparison/2");
        if (report.provenance)
            report.provenance(j);
        io::write_volume_summary(j, study.input, study.geometry);
        {
            const io::JsonWriter::Scope grid = j.object("study");
            {
                const io::JsonWriter::Scope filters = j.array("filters");
                for (const FilterOutcome &f : study.filters) {
                    const io::JsonWriter::Scope o = j.object();
                    j.field("label", f.filter.label);
                    const io::JsonWriter::Scope chain = j.array("chain");
                    for (const pipeline::PluginSetting &s : f.filter.chain) {
                        const io::JsonWriter::Scope setting = j.object();
                        write_setting(j, s);
                    }
                }
            }
            {
                const io::JsonWriter::Scope simplifiers = j.array("simplifiers");
                for (const SimplifierOutcome &s : study.filters.front().simplifiers) {
                    const io::JsonWriter::Scope o = j.object();
                    j.field("label", s.simplifier.label);
                    j.field("name", s.name);
                    write_setting(j, s.simplifier.setting);
                }
            }
            {
                const io::JsonWriter::Scope cuts = j.array("cuts");
                for (const pipeline::CutChoice &c : study.grid.cuts)
                    j.value(cut_name(c));
            }
            j.field("scoring", scoring_name(study.scoring));
        }
        if (!study.truth_source.empty()) {
            const io::JsonWriter::Scope truth = j.object("truth");
            j.field("source", study.truth_source);
            const io::JsonWriter::Scope structures = j.array("structures");
            for (const TruthStructure &t : study.truth) {
                const io::JsonWriter::Scope o = j.object();
                j.field("label", t.label);
                j.field("name", t.name);
                j.field("colour", t.colour);
                j.field("voxels", t.voxels);
            }
        }
        {
            const io::JsonWriter::Scope results = j.array("results");
            for (const FilterOutcome &f : study.filters)
                write_filter_results(j, study, f);
        }
        j.field("figures", report.figures);
    });
}

namespace {

void write_filter_results(io::JsonWriter &j, const StudyOutcome &study, const FilterOutcome &f)
{
    const io::JsonWriter::Scope fo = j.object();
    j.field("filter", f.filter.label);
    j.field("source", f.source);
    {
        const io::JsonWriter::Scope tree = j.object("contour_tree");
        j.field("nodes", f.nodes);
        j.field("arcs", f.arcs);
    }
    {
        const io::JsonWriter::Scope simplifiers = j.array("simplifiers");
        for (const SimplifierOutcome &s : f.simplifiers) {
            const io::JsonWriter::Scope so = j.object();
            j.field("label", s.simplifier.label);
            j.field("branches", s.branches);
            const io::JsonWriter::Scope cuts = j.array("cuts");
            for (const CutOutcome &c : s.cuts) {
                const io::JsonWriter::Scope co = j.object();
                j.field("cut", cut_name(c.cut));
                j.field("kept_count", c.kept.size());
                j.field("importance_level", c.level);
                if (c.scores) {
                    const io::JsonWriter::Scope scores = j.array("truth");
                    for (std::size_t t = 0; t < study.truth.size(); ++t) {
                        const io::JsonWriter::Scope o = j.object();
                        j.field("label", study.truth[t].label);
                        j.field("name", study.truth[t].name);
                        write_match(j, "one_to_one", c.scores->one_to_one[t]);
                        write_match(j, "best_match", c.scores->best[t]);
                    }
                }
                write_kept(j, c.kept);
            }
        }
    }
    const io::JsonWriter::Scope overlaps = j.array("overlaps");
    for (const OverlapOutcome &o : f.overlaps) {
        const io::JsonWriter::Scope pair = j.object();
        j.field("cut", cut_name(study.grid.cuts[o.cut]));
        j.field("a", f.simplifiers[o.a].simplifier.label);
        j.field("b", f.simplifiers[o.b].simplifier.label);
        j.field("shared", o.overlap.shared);
        j.field("only_a", o.overlap.only_a);
        j.field("only_b", o.overlap.only_b);
        j.field("jaccard", o.overlap.jaccard);
    }
}

} // namespace

void write_timings_json(const std::filesystem::path &path, const StudyOutcome &study)
{
    io::write_json_file(path, io::JsonLayout::indented, [&](io::JsonWriter &j) {
        j.field("format", "arbor-comparison-timings/1");
        const io::JsonWriter::Scope filters = j.array("filters");
        for (const FilterOutcome &f : study.filters) {
            const io::JsonWriter::Scope fo = j.object();
            j.field("filter", f.filter.label);
            j.field("filter_seconds", f.filter_seconds);
            j.field("contour_tree_seconds", f.tree_seconds);
            j.field("contour_tree_from_cache", f.tree_from_cache);
            const io::JsonWriter::Scope simplifiers = j.array("simplifiers");
            for (const SimplifierOutcome &s : f.simplifiers) {
                const io::JsonWriter::Scope so = j.object();
                j.field("label", s.simplifier.label);
                j.field("decomposition_seconds", s.seconds);
                const io::JsonWriter::Scope cuts = j.object("cut_seconds");
                for (const CutOutcome &c : s.cuts)
                    j.field(cut_name(c.cut), c.seconds);
            }
        }
    });
}

void write_study_csv(const std::filesystem::path &path, const StudyOutcome &study)
{
    AtomicFile file(path);
    const bool truth = !study.truth_source.empty();
    file.write("filter,cut,keep,threshold,simplifier,simplifier_id,kept");
    if (truth)
        file.write(",scoring,truth_label,truth_name,truth_voxels,matched_label,dice,precision,recall,region_voxels,"
                   "best_label,best_dice,best_precision,best_recall");
    file.write("\n");
    for (const FilterOutcome &f : study.filters)
        for (std::size_t c = 0; c < study.grid.cuts.size(); ++c)
            for (const SimplifierOutcome &s : f.simplifiers) {
                const CutOutcome &co = s.cuts[c];
                std::ostringstream head;
                head << csv_text(f.filter.label) << ',' << cut_name(co.cut) << ','
                     << (co.cut.keep ? std::to_string(*co.cut.keep) : "") << ','
                     << (co.cut.threshold ? general(*co.cut.threshold) : "") << ',' << csv_text(s.simplifier.label)
                     << ',' << s.simplifier.setting.id << ',' << co.kept.size();
                if (!truth) {
                    file.write(head.str() + "\n");
                    continue;
                }
                for (std::size_t t = 0; t < study.truth.size(); ++t) {
                    const study::RegionMatch &m = co.scores->one_to_one[t], &b = co.scores->best[t];
                    std::ostringstream row;
                    row << head.str() << ',' << scoring_name(study.scoring) << ',' << study.truth[t].label << ','
                        << csv_text(study.truth[t].name) << ',' << study.truth[t].voxels << ','
                        << (m.region >= 0 ? std::to_string(m.region) : "") << ',' << general(m.dice) << ','
                        << general(m.precision) << ',' << general(m.recall) << ',' << m.region_voxels << ','
                        << (b.region >= 0 ? std::to_string(b.region) : "") << ',' << general(b.dice) << ','
                        << general(b.precision) << ',' << general(b.recall) << '\n';
                    file.write(row.str());
                }
            }
    file.commit();
}

void write_kept_csv(const std::filesystem::path &path, const StudyOutcome &study)
{
    AtomicFile file(path);
    file.write("filter,cut,simplifier,label,branch,parent_label,kind,depth,importance,extremum_vertex,extremum_x_mm,"
               "extremum_y_mm,extremum_z_mm,extremum_value,saddle_value");
    for (int m = 0; m < topology::kMeasureCount; ++m)
        file.write(std::string(",") + topology::measure_id(m));
    for (int m = 0; m < topology::kMeasureCount; ++m)
        file.write(std::string(",relative_") + topology::measure_id(m));
    file.write("\n");
    for (const FilterOutcome &f : study.filters)
        for (const SimplifierOutcome &s : f.simplifiers)
            for (const CutOutcome &c : s.cuts)
                for (const KeptRecord &r : c.kept) {
                    std::ostringstream row;
                    row << csv_text(f.filter.label) << ',' << cut_name(c.cut) << ',' << csv_text(s.simplifier.label)
                        << ',' << r.label << ',' << r.branch << ',' << r.parent_label << ','
                        << io::branch_kind_name(r.kind) << ',' << r.depth << ',' << general(r.importance) << ','
                        << r.extremum.vertex << ',' << general(r.extremum.position_mm[0]) << ','
                        << general(r.extremum.position_mm[1]) << ',' << general(r.extremum.position_mm[2]) << ','
                        << general(r.extremum.value) << ',' << general(r.saddle.value);
                    for (const double m : r.measures)
                        row << ',' << general(m);
                    for (const double m : r.relative)
                        row << ',' << general(m);
                    file.write(row.str() + "\n");
                }
    file.commit();
}

void write_report_markdown(const std::filesystem::path &path, const StudyReport &report)
{
    const StudyOutcome &study = *report.study;
    const Geometry &g = study.geometry;
    std::ostringstream md;
    md << "# Simplifier comparison: " << study.input << "\n\n";
    md << "Volume " << g.dims[0] << " x " << g.dims[1] << " x " << g.dims[2] << ". " << study.filters.size()
       << " filter setting(s) x " << study.filters.front().simplifiers.size() << " simplifier setting(s) x "
       << study.grid.cuts.size()
       << " cut(s). The contour tree is computed once per filter setting; every simplifier decomposes it once "
          "with its own importance and every cut is made on that decomposition. Seconds are in timings.json.\n";
    for (const FilterOutcome &f : study.filters) {
        md << "\n## Filter: " << f.filter.label << "\n\nContour tree of " << f.nodes << " nodes ("
           << f.source << ").\n\n";
        md << "| simplifier | version | branches |";
        for (const pipeline::CutChoice &c : study.grid.cuts)
            md << " kept at " << cut_name(c) << " |";
        md << "\n|---|---|---:|";
        for (std::size_t c = 0; c < study.grid.cuts.size(); ++c)
            md << "---:|";
        md << "\n";
        for (const SimplifierOutcome &s : f.simplifiers) {
            md << "| " << s.simplifier.label << " | " << s.version << " | " << s.branches << " |";
            for (const CutOutcome &c : s.cuts)
                md << " " << c.kept.size() << " |";
            md << "\n";
        }
        if (!study.truth_source.empty()) {
            md << "\n### Dice with the ground truth (" << study.truth_source << ", " << scoring_name(study.scoring)
               << " regions)\n\nOne-to-one: each kept region matched to at most one structure (the assignment of "
                  "highest total Dice); in brackets the best match, where one region may serve several "
                  "structures.\n\n| cut | simplifier |";
            for (const TruthStructure &t : study.truth)
                md << " " << t.name << " |";
            md << "\n|---|---|";
            for (std::size_t t = 0; t < study.truth.size(); ++t)
                md << "---:|";
            md << "\n";
            for (std::size_t c = 0; c < study.grid.cuts.size(); ++c)
                for (const SimplifierOutcome &s : f.simplifiers) {
                    md << "| " << cut_name(study.grid.cuts[c]) << " | " << s.simplifier.label << " |";
                    for (std::size_t t = 0; t < study.truth.size(); ++t)
                        md << " " << fixed(s.cuts[c].scores->one_to_one[t].dice, 3) << " ("
                           << fixed(s.cuts[c].scores->best[t].dice, 3) << ") |";
                    md << "\n";
                }
        }
        if (!f.overlaps.empty()) {
            md << "\n### Overlap of the kept sets\n\nKept branches of two simplifiers are the same structure when "
                  "the extremum of each lies in the region the other labels; the root is left out.\n\n"
               << "| cut | a | b | shared | only a | only b | Jaccard |\n|---|---|---|---:|---:|---:|---:|\n";
            for (const OverlapOutcome &o : f.overlaps)
                md << "| " << cut_name(study.grid.cuts[o.cut]) << " | " << f.simplifiers[o.a].simplifier.label
                   << " | " << f.simplifiers[o.b].simplifier.label << " | " << o.overlap.shared << " | "
                   << o.overlap.only_a << " | " << o.overlap.only_b << " | " << fixed(o.overlap.jaccard, 3)
                   << " |\n";
        }
    }
    if (!report.figures.empty()) {
        md << "\n## Figures\n\n";
        for (const std::string &image : report.figures)
            if (image.size() > 4 && image.substr(image.size() - 4) == ".png")
                md << "![" << image << "](" << image << ")\n\n";
    }
    AtomicFile file(path);
    file.write(md.str());
    file.commit();
}

} // namespace arbor::cli
