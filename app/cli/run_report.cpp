#include "run_report.hpp"

#include "core/atomic_file.hpp"
#include "host/param_text.hpp"
#include "io/json_writer.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <span>
#include <sstream>

namespace arbor::cli {

namespace {

void write_plugin(io::JsonWriter &j, std::string_view role, const PluginInstance &p)
{
    const io::JsonWriter::Scope plugin = j.object(role);
    j.field("id", p.id());
    j.field("name", p.descriptor().name);
    j.field("version", p.descriptor().version);
    const io::JsonWriter::Scope params = j.object("parameters");
    for (const arbor_param_desc *d : p.param_descriptions())
        j.field(d->id, format_param_value(*d, p.get_param(d->id)));
}

// How branch b looks: the opacity range of its lookup table and its colour
// (straight sRGB) at the extremum end.
struct BranchLook {
    float opacity[2] = {1, 0};
    std::array<float, 3> colour{};
    char hex[8] = "";
};

BranchLook branch_look(const RunReport &r, uint32_t b)
{
    const arbor_branch_tree &t = *r.tree;
    const TransferFunctions &tf = *r.tf->functions;
    const float *lut = tf.lut(b);
    BranchLook look;
    for (uint32_t i = 0; i < tf.lut_size(); ++i) {
        look.opacity[0] = std::min(look.opacity[0], lut[4 * i + 3]);
        look.opacity[1] = std::max(look.opacity[1], lut[4 * i + 3]);
    }
    const bool at_low = b != 0 && t.extremum_value[b] < t.saddle_value[b];
    const float *c = lut + 4 * (at_low ? 0 : tf.lut_size() - 1);
    look.colour = {c[0], c[1], c[2]};
    std::snprintf(look.hex, sizeof look.hex, "#%02x%02x%02x", static_cast<int>(std::lround(255 * c[0])),
                  static_cast<int>(std::lround(255 * c[1])), static_cast<int>(std::lround(255 * c[2])));
    return look;
}

const char *branch_kind(const arbor_branch_tree &t, uint32_t b)
{
    return b == 0 ? "root" : (t.extremum_kind[b] == ARBOR_EXTREMUM_MINIMUM ? "minimum" : "maximum");
}

std::string fixed(double x, int digits)
{
    char buf[64];
    std::snprintf(buf, sizeof buf, "%.*f", digits, x);
    return buf;
}

void write_report_json(const std::filesystem::path &path, const RunReport &r, const std::vector<BranchLook> &looks,
                       double total_seconds)
{
    const Geometry &g = r.volume->geometry();
    const arbor_branch_tree &t = *r.tree;
    io::write_json_file(path, io::JsonLayout::indented, [&](io::JsonWriter &j) {
        j.field("format", "arbor-run-report/1");
        {
            const io::JsonWriter::Scope input = j.object("input");
            j.field("source", r.source);
            j.field("importer", r.importer);
            j.field("dims", g.dims);
            j.field("spacing_mm", g.spacing);
            j.field("voxel_type", arbor_voxel_type_name(r.volume->type()));
            j.field("value_range",
                    std::array<double, 2>{r.simplified->branches.global_min, r.simplified->branches.global_max});
        }
        {
            const io::JsonWriter::Scope plugins = j.object("plugins");
            {
                const io::JsonWriter::Scope simplifier = j.object("simplifier");
                j.field("id", r.simplified->id);
                j.field("version", r.simplified->version);
            }
            if (r.filter)
                write_plugin(j, "filter", *r.filter);
            if (r.tf->depictor)
                write_plugin(j, "depictor", *r.tf->depictor);
            write_plugin(j, "generator", *r.tf->generator);
            write_plugin(j, "renderer", *r.renderer);
        }
        {
            const io::JsonWriter::Scope simplification = j.object("simplification");
            j.field("cut", r.cut.describe());
            j.field("automatic", r.knee.has_value());
            j.field("contour_tree_nodes", r.topology->tree.node_count());
            j.field("branches_before", r.simplified->branches.branches.size());
            j.field("branches_after", r.simplified->cut.kept.size());
            if (r.knee)
                j.field("knee_ranks_considered", r.knee->considered);
        }
        {
            const io::JsonWriter::Scope camera = j.object("camera");
            j.field("azimuth", r.orbit.azimuth);
            j.field("elevation", r.orbit.elevation);
            j.field("zoom", r.orbit.zoom);
            j.field("perspective", r.orbit.perspective);
            j.field("width", r.width);
            j.field("height", r.height);
        }
        {
            const io::JsonWriter::Scope seconds = j.object("seconds");
            for (const auto &[name, stage_seconds] : r.stages)
                j.field(name, stage_seconds);
            j.field("total", total_seconds);
        }
        {
            const io::JsonWriter::Scope branches = j.array("branches");
            for (uint32_t b = 0; b < t.branch_count; ++b) {
                const io::JsonWriter::Scope branch = j.object();
                const TransferFunctions &tf = *r.tf->functions;
                j.field("label", b);
                j.field("parent", t.parent[b]);
                j.field("depth", t.depth[b]);
                j.field("kind", branch_kind(t, b));
                j.field("extremum_position_mm", std::span<const double>(t.extremum_position + 3 * b, 3));
                j.field("value_range", std::array<double, 2>{tf.domain(b).first, tf.domain(b).second});
                j.field("importance", t.importance ? t.importance[b] : 0.0);
                j.field("opacity_range", looks[b].opacity);
                j.field("colour", looks[b].hex);
                j.field("colour_srgb", looks[b].colour);
            }
        }
        const io::JsonWriter::Scope output = j.object("output");
        j.field("image", r.image);
        j.field("legend", r.legend);
        j.field("legend_selected_branch", r.legend_selected);
        j.field("covered_fraction", r.coverage);
    });
}

} // namespace

void write_run_report(const std::filesystem::path &path, const RunReport &r)
{
    const Geometry &g = r.volume->geometry();
    const arbor_branch_tree &t = *r.tree;
    std::vector<BranchLook> looks;
    for (uint32_t b = 0; b < t.branch_count; ++b)
        looks.push_back(branch_look(r, b));
    double total = 0;
    for (const auto &stage : r.stages)
        total += stage.second;
    write_report_json(path, r, looks, total);

    std::ostringstream md;
    md << "# Arbor run: " << r.source << "\n\n"
       << "Volume " << g.dims[0] << " x " << g.dims[1] << " x " << g.dims[2] << " "
       << arbor_voxel_type_name(r.volume->type()) << ", spacing " << fixed(g.spacing[0], 3) << " x "
       << fixed(g.spacing[1], 3) << " x " << fixed(g.spacing[2], 3) << " mm"
       << (r.importer.empty() ? "" : ", read by " + r.importer) << ".\n\n"
       << "Contour tree: " << r.topology->tree.node_count() << " nodes, " << r.simplified->branches.branches.size()
       << " branches; " << r.simplified->id << " kept " << r.simplified->cut.kept.size() << " ("
       << (r.knee ? "knee of the importance curve" : r.cut.describe()) << ").\n\n"
       << "Image " << r.width << " x " << r.height << " (" << r.image << "), " << fixed(100 * r.coverage, 1)
       << "% covered; legend " << r.legend << " (relation wheel of branch " << r.legend_selected << ").\n\n"
       << "## Plugins\n\n| role | id | version |\n|---|---|---|\n"
       << "| simplifier | " << r.simplified->id << " | " << r.simplified->version << " |\n";
    if (r.tf->depictor)
        md << "| depictor | " << r.tf->depictor->id() << " | " << r.tf->depictor->descriptor().version << " |\n";
    md << "| generator | " << r.tf->generator->id() << " | " << r.tf->generator->descriptor().version << " |\n"
       << "| renderer | " << r.renderer->id() << " | " << r.renderer->descriptor().version << " |\n\n"
       << "Parameters are in the JSON report.\n\n## Seconds per stage\n\n| stage | seconds |\n|---|---:|\n";
    for (const auto &[name, seconds] : r.stages)
        md << "| " << name << " | " << fixed(seconds, 3) << " |\n";
    md << "| total | " << fixed(total, 3) << " |\n\n## Branches\n\n"
       << "| label | parent | depth | kind | value range | opacity | colour |\n|---:|---:|---:|---|---|---|---|\n";
    for (uint32_t b = 0; b < t.branch_count; ++b) {
        const std::pair<double, double> range = r.tf->functions->domain(b);
        md << "| " << b << " | " << t.parent[b] << " | " << t.depth[b] << " | " << branch_kind(t, b) << " | "
           << fixed(range.first, 1) << " .. " << fixed(range.second, 1) << " | " << fixed(looks[b].opacity[0], 3)
           << " .. " << fixed(looks[b].opacity[1], 3) << " | " << looks[b].hex << " |\n";
    }
    std::filesystem::path md_path = path;
    md_path.replace_extension(".md");
    AtomicFile mdfile(md_path);
    mdfile.write(md.str());
    mdfile.commit();
}

} // namespace arbor::cli
