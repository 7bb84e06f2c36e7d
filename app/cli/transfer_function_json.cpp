#include "transfer_function_json.hpp"

#include "host/param_text.hpp"

#include <algorithm>

namespace arbor::cli {

namespace {

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

void write_plugin(JsonStream &j, const PluginInstance &p)
{
    j.raw("{");
    j.key("id");
    j.string(p.id());
    j.raw(",");
    j.key("version");
    j.string(p.descriptor().version);
    j.raw(",");
    j.key("parameters");
    j.raw("{");
    bool first = true;
    for (const arbor_param_desc *d : p.param_descriptions()) {
        if (!first)
            j.raw(",");
        first = false;
        j.key(d->id);
        j.string(format_param_value(*d, p.get_param(d->id)));
    }
    j.raw("}}");
}

void write_rgba(JsonStream &j, const float *c)
{
    j.raw("[");
    for (int k = 0; k < 4; ++k) {
        if (k)
            j.raw(",");
        j.number(static_cast<float>(std::round(c[k] * 1e6) / 1e6));
    }
    j.raw("]");
}

} // namespace

void write_transfer_functions(const std::string &path, const TransferFunctionFile &f)
{
    const TransferFunctions &tf = *f.functions;
    const arbor_branch_tree &tree = *f.tree;
    AtomicFile file(path);
    JsonStream j(file);
    j.raw("{\n");
    j.key("format");
    j.string("arbor-transfer-functions/1");
    j.raw(",\n");
    j.key("source");
    j.string(f.source);
    j.raw(",\n");
    j.key("simplifier");
    j.raw("{");
    j.key("id");
    j.string(f.simplifier_id);
    j.raw(",");
    j.key("cut");
    j.string(f.cut);
    j.raw("},\n");
    j.key("generator");
    write_plugin(j, *f.generator);
    j.raw(",\n");
    j.key("depictor");
    if (f.depictor) {
        write_plugin(j, *f.depictor);
        j.raw(",\n");
        j.key("selected_branch");
        j.number(f.selected_branch);
    } else {
        j.raw("null");
    }
    j.raw(",\n");
    j.key("value_range");
    j.raw("[");
    j.number(f.value_range[0]);
    j.raw(",");
    j.number(f.value_range[1]);
    j.raw("],\n");
    j.key("lut_size");
    j.number(tf.lut_size());
    j.raw(",\n");
    j.key("opacity_unit_distance_mm");
    j.number(tf.record().opacity_unit_distance);
    j.raw(",\n");
    j.key("branches");
    j.raw("[");
    for (uint32_t b = 0; b < tf.branch_count(); ++b) {
        j.raw(b ? ",\n{" : "\n{");
        j.key("label");
        j.number(b);
        j.raw(",");
        j.key("parent");
        j.number(tree.parent[b]);
        j.raw(",");
        j.key("depth");
        j.number(tree.depth[b]);
        j.raw(",");
        j.key("kind");
        j.string(b == 0 ? "root" : (tree.extremum_kind[b] == ARBOR_EXTREMUM_MINIMUM ? "minimum" : "maximum"));
        j.raw(",");
        j.key("extremum_vertex");
        j.number(static_cast<double>(tree.extremum_vertex[b]));
        if (f.depiction) {
            j.raw(",");
            j.key("role");
            j.string(role_name(f.depiction->role[b]));
        }
        j.raw(",");
        j.key("domain");
        j.raw("[");
        j.number(tf.domain(b).first);
        j.raw(",");
        j.number(tf.domain(b).second);
        j.raw("],");
        const float *lut = tf.lut(b);
        float lo = 1.0f, hi = 0.0f;
        for (uint32_t i = 0; i < tf.lut_size(); ++i) {
            lo = std::min(lo, lut[4 * i + 3]);
            hi = std::max(hi, lut[4 * i + 3]);
        }
        j.key("opacity_range");
        j.raw("[");
        j.number(lo);
        j.raw(",");
        j.number(hi);
        j.raw("],");
        // The colour at the extremum end: the branch's own colour.
        const bool at_low = tree.extremum_value[b] < tree.saddle_value[b] && b != 0;
        j.key("rgba_at_extremum");
        write_rgba(j, lut + 4 * (at_low ? 0 : tf.lut_size() - 1));
        j.raw(",");
        j.key("points");
        j.raw("[");
        for (uint32_t i = tf.point_offsets()[b]; i < tf.point_offsets()[b + 1]; ++i) {
            const arbor_tf_point &p = tf.points()[i];
            j.raw(i > tf.point_offsets()[b] ? ",{" : "{");
            j.key("value");
            j.number(p.value);
            j.raw(",");
            j.key("rgba");
            write_rgba(j, p.rgba);
            j.raw("}");
        }
        j.raw("],");
        j.key("lut");
        j.raw("[");
        for (uint32_t i = 0; i < tf.lut_size(); ++i) {
            if (i)
                j.raw(",");
            write_rgba(j, lut + 4 * i);
        }
        j.raw("]}");
    }
    j.raw("\n]\n}\n");
    file.commit();
}

} // namespace arbor::cli
