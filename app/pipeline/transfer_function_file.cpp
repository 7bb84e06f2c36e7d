#include "transfer_function_file.hpp"

#include "control_points.hpp"

#include "io/json_writer.hpp"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <fstream>
#include <limits>
#include <optional>
#include <string_view>

namespace arbor::pipeline {

namespace {

// Longest lookup table a file may hold (as `--lut-size` and sessions allow).
constexpr int64_t kMaxLutSize = 65536;

const char *role_name(arbor_branch_role r)
{
    switch (r) {
    case ARBOR_ROLE_SELECTED: return "selected";
    case ARBOR_ROLE_PARENT: return "parent";
    case ARBOR_ROLE_CHILD: return "child";
    case ARBOR_ROLE_SIBLING: return "sibling";
    case ARBOR_ROLE_ANCESTOR: return "ancestor";
    case ARBOR_ROLE_DESCENDANT: return "descendant";
    default: return "other";
    }
}

void write_plugin(io::JsonWriter &j, std::string_view key, const PluginSetting &p)
{
    const io::JsonWriter::Scope plugin = j.object(key);
    j.field("id", p.id);
    j.field("version", p.version);
    const io::JsonWriter::Scope parameters = j.object("parameters");
    for (const auto &[id, value] : p.params)
        j.field(id, value);
}

// A whole number of JSON in [lo, hi], or nullopt: get<T>() would take a
// fraction, wrap a negative and overflow on a large float without a word.
std::optional<int64_t> whole(const nlohmann::json &v, int64_t lo, int64_t hi)
{
    if (v.is_number_unsigned()) {
        const uint64_t u = v.get<uint64_t>();
        return u <= static_cast<uint64_t>(hi) ? std::optional<int64_t>(static_cast<int64_t>(u)) : std::nullopt;
    }
    if (v.is_number_integer() && v.get<int64_t>() >= lo && v.get<int64_t>() <= hi)
        return v.get<int64_t>();
    return std::nullopt;
}

// A colour with six decimals (as a float: what renderers read back).
void write_rgba(io::JsonWriter &j, const float *c)
{
    const io::JsonWriter::Scope rgba = j.array();
    for (int k = 0; k < 4; ++k)
        j.value(static_cast<float>(std::round(c[k] * 1e6) / 1e6));
}

} // namespace

void write_transfer_functions(const std::filesystem::path &path, const TransferFunctionsResult &result,
                              const std::string &source, const std::function<void(io::JsonWriter &)> &annotate)
{
    const TransferFunctions &tf = *result.functions;
    const DepictionResult &depicted = *result.depiction;
    const CutResult &cut = *depicted.cut;
    const arbor_branch_tree &tree = cut.tree->record();
    const arbor_depiction *depiction = depicted.depictor.empty() ? nullptr : &depicted.depiction->record();
    io::write_json_file(path, io::JsonLayout::indented, [&](io::JsonWriter &j) {
        j.field("format", "arbor-transfer-functions/1");
        if (annotate)
            annotate(j);
        j.field("source", source);
        {
            const io::JsonWriter::Scope simplifier = j.object("simplifier");
            j.field("id", cut.decomposition->simplifier.id);
            j.field("cut", cut.effective().describe());
        }
        if (result.generator.empty()) {
            j.key("generator");
            j.null();
            j.field("edited_from", result.file.string());
        } else {
            write_plugin(j, "generator", result.generator);
        }
        if (depiction) {
            write_plugin(j, "depictor", depicted.depictor);
            j.field("selected_branch", depicted.request.selected_branch);
        } else {
            j.key("depictor");
            j.null();
        }
        j.field("value_range", result.value_range);
        j.field("lut_size", tf.lut_size());
        j.field("opacity_unit_distance_mm", tf.record().opacity_unit_distance);
        const io::JsonWriter::Scope branches = j.array("branches");
        for (uint32_t b = 0; b < tf.branch_count(); ++b) {
            const io::JsonWriter::Scope branch = j.object();
            j.field("label", b);
            j.field("parent", tree.parent[b]);
            j.field("depth", tree.depth[b]);
            j.field("kind", b == 0                                           ? "root"
                            : tree.extremum_kind[b] == ARBOR_EXTREMUM_MINIMUM ? "minimum"
                                                                              : "maximum");
            j.field("extremum_vertex", tree.extremum_vertex[b]);
            if (depiction)
                j.field("role", role_name(depiction->role[b]));
            j.field("domain", std::array<double, 2>{tf.domain(b).first, tf.domain(b).second});
            const float *lut = tf.lut(b);
            float lo = 1.0f, hi = 0.0f;
            for (uint32_t i = 0; i < tf.lut_size(); ++i) {
                lo = std::min(lo, lut[4 * i + 3]);
                hi = std::max(hi, lut[4 * i + 3]);
            }
            j.field("opacity_range", std::array<float, 2>{lo, hi});
            // The colour at the extremum end: the branch's own colour.
            const bool at_low = tree.extremum_value[b] < tree.saddle_value[b] && b != 0;
            j.key("rgba_at_extremum");
            write_rgba(j, lut + 4 * (at_low ? 0 : tf.lut_size() - 1));
            {
                const io::JsonWriter::Scope points = j.array("points");
                for (uint32_t i = tf.point_offsets()[b]; i < tf.point_offsets()[b + 1]; ++i) {
                    const arbor_tf_point &p = tf.points()[i];
                    const io::JsonWriter::Scope point = j.object();
                    j.field("value", p.value);
                    j.key("rgba");
                    write_rgba(j, p.rgba);
                }
            }
            // Tells points edited later from these: edited points are rebaked.
            j.field("points_digest", points_digest(tf.points().data() + tf.point_offsets()[b],
                                                   tf.point_offsets()[b + 1] - tf.point_offsets()[b]));
            const io::JsonWriter::Scope entries = j.array("lut");
            for (uint32_t i = 0; i < tf.lut_size(); ++i)
                write_rgba(j, lut + 4 * i);
        }
    });
}

StoredTransferFunctions read_transfer_functions(const std::filesystem::path &path)
{
    std::ifstream in(path);
    if (!in)
        throw std::invalid_argument(path.string() + ": cannot open the transfer-function file");
    const auto bad = [&](const std::string &what) { return std::invalid_argument(path.string() + ": " + what); };
    nlohmann::json j;
    try {
        j = nlohmann::json::parse(in);
    } catch (const nlohmann::json::exception &e) {
        throw bad(std::string("not valid JSON (") + e.what() + ")");
    }
    if (!j.is_object() || !j.contains("format") || j.at("format") != "arbor-transfer-functions/1")
        throw bad("not an arbor-transfer-functions/1 file");
    try {
        StoredTransferFunctions out;
        out.source = j.at("source").get<std::string>();
        out.simplifier_id = j.at("simplifier").at("id").get<std::string>();
        out.cut = j.at("simplifier").at("cut").get<std::string>();
        const auto &branches = j.at("branches");
        const std::optional<int64_t> lut_size = whole(j.at("lut_size"), 2, kMaxLutSize);
        if (!lut_size)
            throw bad("lut_size " + j.at("lut_size").dump() + " is not a whole number in [2, " +
                      std::to_string(kMaxLutSize) + "]");
        const auto lut = static_cast<uint32_t>(*lut_size);
        const double unit = j.at("opacity_unit_distance_mm").get<double>();
        if (branches.empty() || !(unit > 0))
            throw bad("no branches or a non-positive opacity unit distance");
        // Every table is checked before any is allocated: the tables a file
        // claims must be in it.
        for (uint32_t b = 0; b < branches.size(); ++b)
            if (branches[b].at("lut").size() != lut)
                throw bad("branch " + std::to_string(b) + " has " + std::to_string(branches[b].at("lut").size()) +
                          " lookup-table entries, not " + std::to_string(lut));
        out.functions = std::make_shared<TransferFunctions>(static_cast<uint32_t>(branches.size()), lut, unit);
        std::vector<uint32_t> offsets{0};
        std::vector<arbor_tf_point> points;
        std::vector<float> rgba(std::size_t{lut} * 4);
        for (uint32_t b = 0; b < branches.size(); ++b) {
            const auto &br = branches[b];
            const std::optional<int64_t> vertex =
                whole(br.at("extremum_vertex"), std::numeric_limits<int64_t>::min(), std::numeric_limits<int64_t>::max());
            if (!vertex)
                throw bad("branch " + std::to_string(b) + ": extremum_vertex " + br.at("extremum_vertex").dump() +
                          " is not a voxel index");
            out.extremum_vertex.push_back(*vertex);
            const auto &entries = br.at("lut");
            for (uint32_t i = 0; i < lut; ++i)
                for (int c = 0; c < 4; ++c) {
                    const float x = entries[i].at(static_cast<std::size_t>(c)).get<float>();
                    if (!(x >= 0.0f && x <= 1.0f))
                        throw bad("branch " + std::to_string(b) + ": lookup-table value outside [0, 1]");
                    rgba[4 * i + c] = x;
                }
            const double lo = br.at("domain").at(0).get<double>(), hi = br.at("domain").at(1).get<double>();
            if (!(lo <= hi))
                throw bad("branch " + std::to_string(b) + ": domain is not an interval");
            const std::size_t first = points.size();
            for (const auto &p : br.at("points")) {
                arbor_tf_point pt{};
                pt.value = p.at("value").get<double>();
                if (!std::isfinite(pt.value))
                    throw bad("branch " + std::to_string(b) + ": a control point at a value that is not a number");
                for (int c = 0; c < 4; ++c) {
                    pt.rgba[c] = p.at("rgba").at(static_cast<std::size_t>(c)).get<float>();
                    if (!(pt.rgba[c] >= 0.0f && pt.rgba[c] <= 1.0f))
                        throw bad("branch " + std::to_string(b) + ": a control point's colour outside [0, 1]");
                }
                if (points.size() > first && pt.value < points.back().value)
                    throw bad("branch " + std::to_string(b) + ": control points out of value order (" +
                              std::to_string(points.back().value) + " before " + std::to_string(pt.value) + ")");
                points.push_back(pt);
            }
            // Points edited since they were written win over the table: the
            // table is rebaked from them (transfer_function.h).
            const std::size_t count = points.size() - first;
            if (count > 0 && br.contains("points_digest") &&
                br.at("points_digest").get<std::string>() != points_digest(points.data() + first, count)) {
                bake_from_points(points.data() + first, count, {lo, hi}, lut, rgba.data());
                out.rebaked.push_back(b);
            }
            out.functions->assign(b, {lo, hi}, rgba.data());
            offsets.push_back(static_cast<uint32_t>(points.size()));
        }
        out.functions->assign_points(std::move(offsets), std::move(points));
        return out;
    } catch (const nlohmann::json::exception &e) {
        throw bad(std::string("missing or malformed field (") + e.what() + ")");
    }
}

} // namespace arbor::pipeline
