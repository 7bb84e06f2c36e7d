#include "run_report.hpp"

#include "core/atomic_file.hpp"
#include "host/param_text.hpp"

#include <nlohmann/json.hpp>

#include <cmath>
#include <cstdio>
#include <sstream>

namespace arbor::cli {

namespace {

using nlohmann::json;

json plugin_json(const PluginInstance &p)
{
    json params = json::object();
    for (const arbor_param_desc *d : p.param_descriptions())
        params[d->id] = format_param_value(*d, p.get_param(d->id));
    return {{"id", p.id()}, {"name", p.descriptor().name}, {"version", p.descriptor().version},
            {"parameters", params}};
}

// Colour (straight sRGB) and opacity range of branch b's lookup table.
json branch_json(const RunReport &r, uint32_t b)
{
    const arbor_branch_tree &t = *r.tree;
    const TransferFunctions &tf = *r.tf->functions;
    const float *lut = tf.lut(b);
    float lo = 1, hi = 0;
    for (uint32_t i = 0; i < tf.lut_size(); ++i) {
        lo = std::min(lo, lut[4 * i + 3]);
        hi = std::max(hi, lut[4 * i + 3]);
    }
    const bool at_low = b != 0 && t.extremum_value[b] < t.saddle_value[b];
    const float *c = lut + 4 * (at_low ? 0 : tf.lut_size() - 1);
    char hex[8];
    std::snprintf(hex, sizeof hex, "#%02x%02x%02x", static_cast<int>(std::lround(255 * c[0])),
                  static_cast<int>(std::lround(255 * c[1])), static_cast<int>(std::lround(255 * c[2])));
    return {{"label", b},
            {"parent", t.parent[b]},
            {"depth", t.depth[b]},
            {"kind", b == 0 ? "root" : (t.extremum_kind[b] == ARBOR_EXTREMUM_MINIMUM ? "minimum" : "maximum")},
            {"extremum_position_mm",
             {t.extremum_position[3 * b], t.extremum_position[3 * b + 1], t.extremum_position[3 * b + 2]}},
            {"value_range", {tf.domain(b).first, tf.domain(b).second}},
            {"importance", t.importance ? t.importance[b] : 0.0},
            {"opacity_range", {lo, hi}},
            {"colour", hex},
            {"colour_srgb", {c[0], c[1], c[2]}}};
}

std::string fixed(double x, int digits)
{
    char buf[64];
    std::snprintf(buf, sizeof buf, "%.*f", digits, x);
    return buf;
}

} // namespace

void write_run_report(const std::filesystem::path &path, const RunReport &r)
{
    const Geometry &g = r.volume->geometry();
    json j;
    j["format"] = "arbor-run-report/1";
    j["input"] = {{"source", r.source},
                  {"importer", r.importer},
                  {"dims", {g.dims[0], g.dims[1], g.dims[2]}},
                  {"spacing_mm", {g.spacing[0], g.spacing[1], g.spacing[2]}},
                  {"voxel_type", arbor_voxel_type_name(r.volume->type())},
                  {"value_range", {r.simplified->branches.global_min, r.simplified->branches.global_max}}};
    j["plugins"] = {{"simplifier", {{"id", r.simplified->id}, {"version", r.simplified->version}}},
                    {"generator", plugin_json(*r.tf->generator)},
                    {"renderer", plugin_json(*r.renderer)}};
    if (r.filter)
        j["plugins"]["filter"] = plugin_json(*r.filter);
    if (r.tf->depictor)
        j["plugins"]["depictor"] = plugin_json(*r.tf->depictor);
    j["simplification"] = {{"cut", r.cut.describe()},
                           {"automatic", r.knee.has_value()},
                           {"contour_tree_nodes", r.topology->tree.node_count()},
                           {"branches_before", r.simplified->branches.branches.size()},
                           {"branches_after", r.simplified->cut.kept.size()}};
    if (r.knee)
        j["simplification"]["knee_ranks_considered"] = r.knee->considered;
    j["camera"] = {{"azimuth", r.orbit.azimuth},         {"elevation", r.orbit.elevation},
                   {"zoom", r.orbit.zoom},               {"perspective", r.orbit.perspective},
                   {"width", r.width},                   {"height", r.height}};
    json stages = json::object();
    double total = 0;
    for (const auto &[name, seconds] : r.stages) {
        stages[name] = seconds;
        total += seconds;
    }
    stages["total"] = total;
    j["seconds"] = stages;
    j["branches"] = json::array();
    for (uint32_t b = 0; b < r.tree->branch_count; ++b)
        j["branches"].push_back(branch_json(r, b));
    j["output"] = {{"image", r.image},
                   {"legend", r.legend},
                   {"legend_selected_branch", r.legend_selected},
                   {"covered_fraction", r.coverage}};
    AtomicFile file(path);
    file.write(j.dump(2) + "\n");
    file.commit();

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
    for (const json &b : j["branches"])
        md << "| " << b["label"] << " | " << b["parent"] << " | " << b["depth"] << " | "
           << b["kind"].get<std::string>() << " | " << fixed(b["value_range"][0].get<double>(), 1) << " .. "
           << fixed(b["value_range"][1].get<double>(), 1) << " | " << fixed(b["opacity_range"][0].get<double>(), 3)
           << " .. " << fixed(b["opacity_range"][1].get<double>(), 3) << " | " << b["colour"].get<std::string>()
           << " |\n";
    std::filesystem::path md_path = path;
    md_path.replace_extension(".md");
    AtomicFile mdfile(md_path);
    mdfile.write(md.str());
    mdfile.commit();
}

} // namespace arbor::cli
