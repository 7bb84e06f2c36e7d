#include "run_report.hpp"

#include "core/atomic_file.hpp"
#include "core/ct_tissue.hpp"
#include "pipeline/context_structures.hpp"

#include <nlohmann/json.hpp>

#include <cmath>
#include <cstdio>
#include <sstream>

namespace arbor::cli {

namespace {

using nlohmann::json;
using pipeline::Stage;

json plugin_json(const pipeline::PluginSetting &s)
{
    return {{"id", s.id}, {"version", s.version}, {"parameters", s.params}};
}

// Colour (straight sRGB) and opacity range of branch b's lookup table, its
// share of the image's visibility, and for CT the HU it spans.
json branch_json(const arbor_branch_tree &t, const TransferFunctions &tf, const RenderedImage &image,
                 const ValueMapping &mapping, uint32_t b)
{
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
    json j = {{"label", b},
            {"parent", t.parent[b]},
            {"depth", t.depth[b]},
            {"kind", b == 0 ? "root" : (t.extremum_kind[b] == ARBOR_EXTREMUM_MINIMUM ? "minimum" : "maximum")},
            {"extremum_position_mm",
             {t.extremum_position[3 * b], t.extremum_position[3 * b + 1], t.extremum_position[3 * b + 2]}},
            {"value_range", {tf.domain(b).first, tf.domain(b).second}},
            {"importance", t.importance ? t.importance[b] : 0.0},
            {"opacity_range", {lo, hi}},
            {"colour", hex},
            {"colour_srgb", {c[0], c[1], c[2]}},
            {"visibility", image.label_visibility.empty() ? json(nullptr) : json(visibility_share(image, b))},
            {"generator_note", tf.note(b)}};
    if (mapping.unit == "HU") {
        const double a = mapping.physical(tf.domain(b).first), z = mapping.physical(tf.domain(b).second);
        j["hu_range"] = {std::min(a, z), std::max(a, z)};
        j["tissues"] = ct_tissues_spanned(std::min(a, z), std::max(a, z));
    }
    return j;
}

} // namespace

double visibility_share(const RenderedImage &image, uint32_t label)
{
    double total = 0;
    for (double v : image.label_visibility)
        total += v;
    return total > 0 && label < image.label_visibility.size() ? image.label_visibility[label] / total : 0.0;
}

namespace {

std::string fixed(double x, int digits)
{
    char buf[64];
    std::snprintf(buf, sizeof buf, "%.*f", digits, x);
    return buf;
}

json stage_runs_json(const std::array<uint64_t, pipeline::kStageCount> &runs)
{
    json j = json::object();
    for (std::size_t s = 0; s < pipeline::kStageCount; ++s)
        j[pipeline::stage_name(static_cast<Stage>(s))] = runs[s];
    return j;
}

// What one rendered image is made of: everything below the contour tree.
json run_json(const RunReport &report, const RenderedRun &run, std::vector<std::pair<std::string, double>> &seconds)
{
    const pipeline::CutResult &cut = *run.cut;
    const pipeline::DecompositionResult &d = *cut.decomposition;
    const pipeline::Document &doc = run.document;
    json j;
    if (!run.name.empty()) {
        j["name"] = run.name;
        j["caption"] = run.caption;
    }
    j["plugins"] = {{"simplifier", plugin_json(d.simplifier)},
                    {"generator", plugin_json(run.tf->generator)},
                    {"renderer", plugin_json(run.render->renderer)}};
    j["plugins"]["simplifier"]["name"] = d.simplifier_name;
    if (!report.filtered->filters.empty()) {
        j["plugins"]["filters"] = json::array();
        for (const pipeline::PluginSetting &f : report.filtered->filters)
            j["plugins"]["filters"].push_back(plugin_json(f));
        j["plugins"]["filter"] = j["plugins"]["filters"][0];
    }
    if (!run.tf->depiction->depictor.empty())
        j["plugins"]["depictor"] = plugin_json(run.tf->depiction->depictor);
    if (run.legend)
        j["plugins"]["legend"] = plugin_json(run.legend->depictor);
    j["simplification"] = {{"cut", cut.effective().describe()},
                           {"requested", cut.requested.describe()},
                           {"automatic", cut.knee.has_value()},
                           {"contour_tree_nodes", report.tree->tree.node_count()},
                           {"branches_before", d.branches.branches.size()},
                           {"branches_after", cut.kept()},
                           {"background_branches_left_out", cut.background_branches},
                           {"specks_left_out", cut.speck_branches}};
    if (cut.knee)
        j["simplification"]["knee_ranks_considered"] = cut.knee->considered;
    const Orbit &o = doc.view.orbit;
    const double azimuth = run.render->viewpoint ? run.render->viewpoint->azimuth : o.azimuth;
    const double elevation = run.render->viewpoint ? run.render->viewpoint->elevation : o.elevation;
    j["camera"] = {{"azimuth", azimuth},          {"elevation", elevation},
                   {"zoom", o.zoom},              {"perspective", o.perspective},
                   {"width", doc.view.width},     {"height", doc.view.height}};
    seconds = {{"import", report.import->seconds},
               {"filter", report.filtered->seconds},
               {"contour tree", report.tree->seconds},
               {"simplification", d.seconds + cut.seconds},
               {"transfer functions", run.tf->depiction->seconds + run.tf->seconds},
               {"render", run.render->seconds},
               {"legend", run.legend ? run.legend->seconds : 0.0},
               {"write", run.write_seconds}};
    json stages = json::object();
    double total = 0;
    for (const auto &[name, s] : seconds) {
        stages[name] = s;
        total += s;
    }
    stages["total"] = total;
    j["seconds"] = stages;
    j["branches"] = json::array();
    const arbor_branch_tree &tree = cut.tree->record();
    for (uint32_t b = 0; b < tree.branch_count; ++b)
        j["branches"].push_back(
            branch_json(tree, *run.render->functions, run.render->image, report.filtered->volume->mapping(), b));
    for (uint32_t b = 0; b < tree.branch_count && b < cut.shapes.size(); ++b) {
        j["branches"][b]["thickness_mm"] = cut.shapes[b].thickness_mm;
        j["branches"][b]["compactness"] = cut.shapes[b].compactness;
        j["branches"][b]["field_of_view_cut"] = cut.shapes[b].cut_fraction;
        j["branches"][b]["outside_body"] = cut.shapes[b].outside_body;
        const pipeline::ContextReason context = pipeline::context_reason(
            cut.shapes[b], tree.extremum_kind[b] == ARBOR_EXTREMUM_MAXIMUM, b == 0);
        if (context != pipeline::ContextReason::None)
            j["branches"][b]["context"] = pipeline::describe(context);
    }
    if (const auto &balance = run.render->balance) {
        const std::vector<double> &peel = run.render->peel;
        for (uint32_t b = 0; b < tree.branch_count; ++b) {
            // What the balance chose at the default flow rate, then the
            // flow rate's peel on top (flow_peel.hpp): the product applied.
            const double flow = b < peel.size() ? peel[b] : 1.0;
            j["branches"][b]["optical_depth_scale"] = balance->scale[b] * flow;
            j["branches"][b]["balance_scale"] = balance->scale[b];
            j["branches"][b]["flow_peel"] = flow;
            j["branches"][b]["visibility_before_balance"] = balance->shares_before[b];
        }
        j["balance"] = {{"iterations", balance->iterations},
                        {"views", {"anterior", "left", "superior"}},
                        {"taken_at", "the generator's default flow rate"}};
    }
    if (const auto &vp = run.render->viewpoint)
        j["viewpoint"] = {{"azimuth", vp->azimuth},
                          {"elevation", vp->elevation},
                          {"score", vp->score},
                          {"anterior_score", vp->anterior_score}};
    if (const auto &framing = run.render->framing)
        j["framing"] = {{"content_fraction_unframed", framing->content_fraction}, {"scale", framing->scale}};
    j["output"] = {{"image", run.image.string()}, {"covered_fraction", run.coverage}};
    if (run.legend) {
        j["output"]["legend"] = run.legend_image.string();
        j["output"]["legend_selected_branch"] = run.legend->selected;
    }
    return j;
}

json input_json(const RunReport &r)
{
    const Volume &v = *r.filtered->volume;
    const Geometry &g = v.geometry();
    const pipeline::DecompositionResult &d = *r.runs.front().cut->decomposition;
    json j = {{"source", r.filtered->source},
              {"importer", r.import->importer.empty() ? "" : r.import->importer.id + " " + r.import->importer.version},
              {"dims", {g.dims[0], g.dims[1], g.dims[2]}},
              {"spacing_mm", {g.spacing[0], g.spacing[1], g.spacing[2]}},
              {"voxel_type", arbor_voxel_type_name(v.type())},
              {"value_range", {d.branches.global_min, d.branches.global_max}},
              {"value_unit", v.mapping().unit}};
    if (const auto &hu = r.import->hounsfield_inferred)
        j["value_unit_inferred"] = {{"air_peak", hu->air_peak},
                                    {"air_fraction", hu->air_fraction},
                                    {"tissue_peak", hu->tissue_peak},
                                    {"tissue_fraction", hu->tissue_fraction}};
    return j;
}

void markdown_run(std::ostringstream &md, const RunReport &r, const RenderedRun &run, const json &j,
                  const std::vector<std::pair<std::string, double>> &seconds)
{
    const pipeline::CutResult &cut = *run.cut;
    const pipeline::DecompositionResult &d = *cut.decomposition;
    md << "Contour tree: " << r.tree->tree.node_count() << " nodes"
       << (r.tree->from_cache ? " (from the cache)" : "") << ", " << d.branches.branches.size() << " branches; "
       << d.simplifier.id << " kept " << cut.kept() << " ("
       << (cut.knee ? "knee of the importance curve" : cut.requested.describe()) << ").\n\n"
       << "Image " << run.document.view.width << " x " << run.document.view.height << " (" << run.image.string()
       << "), " << fixed(100 * run.coverage, 1) << "% covered";
    if (run.legend)
        md << "; legend " << run.legend_image.string() << " (relation wheel of branch " << run.legend->selected << ")";
    md << ".\n\n## Plugins\n\n| role | id | version |\n|---|---|---|\n";
    for (const auto &[role, p] : j["plugins"].items())
        if (role != "filters")
            md << "| " << role << " | " << p["id"].get<std::string>() << " | " << p["version"].get<std::string>()
               << " |\n";
    md << "\nParameters are in the JSON report.\n\n## Seconds per stage\n\n| stage | seconds |\n|---|---:|\n";
    double total = 0;
    for (const auto &[name, s] : seconds) {
        md << "| " << name << " | " << fixed(s, 3) << " |\n";
        total += s;
    }
    md << "| total | " << fixed(total, 3) << " |\n\n## Branches\n\n"
       << "| label | parent | depth | kind | value range | tissues | opacity | visibility | colour | transfer function |\n"
       << "|---:|---:|---:|---|---|---|---|---:|---|---|\n";
    for (const json &b : j["branches"]) {
        std::string tissues;
        if (b.contains("tissues"))
            for (const json &t : b["tissues"])
                tissues += (tissues.empty() ? "" : ", ") + t.get<std::string>();
        md << "| " << b["label"] << " | " << b["parent"] << " | " << b["depth"] << " | "
           << b["kind"].get<std::string>() << " | " << fixed(b["value_range"][0].get<double>(), 1) << " .. "
           << fixed(b["value_range"][1].get<double>(), 1) << " | " << tissues << " | "
           << fixed(b["opacity_range"][0].get<double>(), 3) << " .. " << fixed(b["opacity_range"][1].get<double>(), 3)
           << " | " << (b["visibility"].is_null() ? "-" : fixed(100 * b["visibility"].get<double>(), 1) + "%")
           << " | " << b["colour"].get<std::string>() << " | " << b["generator_note"].get<std::string>() << " |\n";
    }
}

void write_text(const std::filesystem::path &path, const std::string &text)
{
    AtomicFile file(path);
    file.write(text);
    file.commit();
}

} // namespace

void write_run_report(const std::filesystem::path &path, const RunReport &r)
{
    const Geometry &g = r.filtered->volume->geometry();
    const bool sweep = r.runs.size() > 1;
    json j;
    std::ostringstream md;
    md << "# Arbor " << (sweep ? "sweep" : "run") << ": " << r.filtered->source << "\n\n"
       << "Volume " << g.dims[0] << " x " << g.dims[1] << " x " << g.dims[2] << " "
       << arbor_voxel_type_name(r.filtered->volume->type()) << ", spacing " << fixed(g.spacing[0], 3) << " x "
       << fixed(g.spacing[1], 3) << " x " << fixed(g.spacing[2], 3) << " mm"
       << (r.import->importer.empty() ? "" : ", read by " + r.import->importer.id + " " + r.import->importer.version)
       << ".";
    if (const auto &hu = r.import->hounsfield_inferred)
        md << " Values in Hounsfield units: the file names no unit, and they are a CT's (" << hu->describe() << ").";
    md << "\n\n";
    std::vector<std::pair<std::string, double>> seconds;
    if (!sweep) {
        j = run_json(r, r.runs.front(), seconds);
        j["format"] = "arbor-run-report/1";
        markdown_run(md, r, r.runs.front(), j, seconds);
    } else {
        j["format"] = "arbor-sweep-report/1";
        j["runs"] = json::array();
        md << "Contact sheet: " << r.contact_sheet.string() << "\n\n| run | image | kept | seconds (render) |\n"
           << "|---|---|---:|---:|\n";
        for (const RenderedRun &run : r.runs) {
            j["runs"].push_back(run_json(r, run, seconds));
            md << "| " << run.caption << " | " << run.image.string() << " | " << run.cut->kept() << " | "
               << fixed(run.render->seconds, 3) << " |\n";
        }
        j["contact_sheet"] = r.contact_sheet.string();
        md << "\n## First run: " << r.runs.front().caption << "\n\n";
        markdown_run(md, r, r.runs.front(), j["runs"][0], seconds);
    }
    if (!r.provenance.empty())
        j["provenance"] = json::parse(r.provenance);
    j["input"] = input_json(r);
    j["contour_tree"] = {{"nodes", r.tree->tree.node_count()},
                         {"arcs", r.tree->tree.arc_count()},
                         {"seconds", r.tree->seconds},
                         {"from_cache", r.tree->from_cache}};
    if (!r.tree->memory_plan.empty())
        j["contour_tree"]["memory_plan"] = r.tree->memory_plan;
    j["stage_runs"] = stage_runs_json(r.stage_runs);
    if (!r.session.empty())
        j["session"] = r.session.string();
    if (!r.labels.empty())
        j["labels"] = r.labels.string();
    md << "\n## Stage runs\n\n| stage | runs |\n|---|---:|\n";
    for (const auto &[stage, n] : j["stage_runs"].items())
        md << "| " << stage << " | " << n << " |\n";
    // Non-UTF-8 bytes (a file name in another character set) become U+FFFD.
    write_text(path, j.dump(2, ' ', false, json::error_handler_t::replace) + "\n");
    std::filesystem::path md_path = path;
    md_path.replace_extension(".md");
    write_text(md_path, md.str());
}

} // namespace arbor::cli
