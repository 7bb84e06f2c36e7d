// residue_flow_generator.cpp - org.arbor.tf.residue-flow: one transfer
// function per branch, opacity by the residue-flow model (residue_flow.hpp)
// shaped over the branch's interval (opacity_shape.hpp) and multiplied by
// the depiction's factors (α = α_d · α_t), colour from the branch's place in
// the tree (branch_colours.hpp).  It reads the branch tree only, so a change
// of flow rate or shape regenerates without the contour tree; colours found
// once are cached across calls.
#include "branch_colours.hpp"
#include "opacity_shape.hpp"
#include "residue_flow.hpp"
#include "shape_choice.hpp"
#include "tf_generator_classes.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <cstring>

namespace arbor::tf {

const arbor_plugin_descriptor kResidueFlowDescriptor = {
    sizeof(arbor_plugin_descriptor),
    ARBOR_PLUGIN_FLAG_NONE,
    "org.arbor.tf.residue-flow",
    ARBOR_KIND_TF_GENERATOR,
    "Residue flow",
    "1.0.0",
    "Arbor",
    "One transfer function per branch: opacity flows from the root down the tree (Darcy head loss, flow rate Q "
    "peels outer structures away), colours from harmonic hue templates with lightness and vividness set in CIELAB.",
    "",
};

namespace {

std::vector<sdk::ParamSpec> residue_flow_params()
{
    std::vector<sdk::ParamSpec> p;
    p.push_back(sdk::ParamSpec::real("flow-rate", "Flow rate Q", 60.0, 0.0, 1e6)
                    .group("Opacity")
                    .hint("Raise to move opacity from outer structures to inner ones (0 .. conductivity)"));
    p.push_back(sdk::ParamSpec::real("conductivity", "Hydraulic conductivity K", 300.0, 1e-6, 1e6)
                    .group("Opacity")
                    .hint("Darcy's K; 300 is water in sand. Head loss = Q p / (K n_children)"));
    p.push_back(sdk::ParamSpec::real("alpha-min", "Minimum opacity", 0.0, 0.0, 1.0)
                    .group("Opacity")
                    .hint("Opacity below every band: what the outermost structure starts from (air stays clear at 0)"));
    p.push_back(sdk::ParamSpec::real("opacity-unit", "Opacity unit distance", 8.0, 0.01, 1000.0)
                    .unit("voxels")
                    .group("Opacity")
                    .hint("The thickness, in smallest voxel spacings, that the opacities refer to: larger sees "
                          "deeper through outer structures"));
    p.push_back(sdk::ParamSpec::real("alpha-range", "Opacity range", 0.9, 0.0, 1.0)
                    .group("Opacity")
                    .hint("What all branches on a path from the root share above the minimum"));
    std::vector<std::string> shapes{"auto"};
    shapes.insert(shapes.end(), opacity_shape_names().begin(), opacity_shape_names().end());
    p.push_back(sdk::ParamSpec::choice("shape", "Opacity shape", shapes, 0,
                                       {"chosen per branch from its thickness and values", "ramp towards the extremum",
                                        "inverse ramp", "hat", "box", "isovalue peak"})
                    .group("Opacity")
                    .hint("auto chooses per branch (thin structures a peak or a hat, solid ones a box, ramp or "
                          "inverse ramp by where their values lie); or one shape for all"));
    p.push_back(sdk::ParamSpec::real("peak-position", "Peak position", 0.5, 0.0, 1.0)
                    .group("Opacity")
                    .hint("Shape peak: where the isovalue lies between saddle (0) and extremum (1)"));
    p.push_back(sdk::ParamSpec::real("peak-width", "Peak width", 0.1, 0.001, 1.0).group("Opacity"));
    p.push_back(sdk::ParamSpec::text("hues", "Hue template", "auto")
                    .group("Colour")
                    .hint("auto: on a CT (Hounsfield units) a hue family per tissue (bone ivory, contrast red, soft "
                          "tissue flesh, fat yellow, lung blue-grey), elsewhere the full wheel; or full, or a "
                          "harmonic template i, V, L, I, T, Y, X with an optional rotation: X:30"));
    p.push_back(sdk::ParamSpec::boolean("clear-background", "Clear background", true)
                    .group("Opacity")
                    .hint("Values at or below the background level the host found (the air around a CT, the noise "
                          "around an MR) stay fully transparent; opacity fades in over the width of its noise"));
    p.push_back(sdk::ParamSpec::real("lightness-min", "Lightness min (L*)", 45.0, 0.0, 100.0).group("Colour"));
    p.push_back(sdk::ParamSpec::real("lightness-max", "Lightness max (L*)", 85.0, 0.0, 100.0).group("Colour"));
    p.push_back(sdk::ParamSpec::real("vividness-min", "Vividness min", 0.25, 0.0, 1.0).group("Colour"));
    p.push_back(sdk::ParamSpec::real("vividness-max", "Vividness max", 1.0, 0.0, 1.0).group("Colour"));
    return p;
}

class ResidueFlowGenerator final : public sdk::TfGenerator {
public:
    explicit ResidueFlowGenerator(const arbor_host *host)
        : TfGenerator(kResidueFlowDescriptor, host, residue_flow_params())
    {
    }

    void generate(const arbor_tf_request &request, const sdk::BranchTreeView &tree, arbor_tf_set &out,
                  const sdk::Task &task) override
    {
        FlowParameters flow;
        flow.flow_rate = params().number("flow-rate");
        flow.conductivity = params().number("conductivity");
        flow.alpha_min = params().number("alpha-min");
        flow.alpha_range = params().number("alpha-range");
        if (flow.alpha_min + flow.alpha_range > 1.0)
            sdk::fail(ARBOR_ERROR_OUT_OF_RANGE, "alpha-min + alpha-range must not exceed 1");
        ShapeSettings fixed;
        const std::string &name = params().choice("shape");
        const bool automatic = name == "auto";
        const auto &names = opacity_shape_names();
        if (!automatic)
            fixed.shape = static_cast<OpacityShape>(std::find(names.begin(), names.end(), name) - names.begin());
        fixed.peak_position = params().number("peak-position");
        fixed.peak_width = params().number("peak-width");
        ColourSettings colour;
        const std::string &hues = params().text("hues");
        try {
            colour.hues = HarmonicTemplate::parse(hues == "auto" ? "full" : hues);
        } catch (const std::invalid_argument &e) {
            sdk::fail(ARBOR_ERROR_INVALID_ARGUMENT, std::string("hues: ") + e.what());
        }
        colour.lightness_min = params().number("lightness-min");
        colour.lightness_max = params().number("lightness-max");
        colour.vividness_min = params().number("vividness-min");
        colour.vividness_max = params().number("vividness-max");

        out.opacity_unit_distance = request.min_spacing > 0 ? request.min_spacing * params().number("opacity-unit")
                                                            : params().number("opacity-unit");
        const std::vector<OpacityRange> ranges = residue_flow(tree, flow);
        // Colour by tissue where values are Hounsfield units.
        const std::vector<TissueChoice> tissues =
            hues == "auto" && holds_hounsfield_units(request) ? choose_tissues(tree, request)
                                                                : std::vector<TissueChoice>{};
        const std::vector<BranchColour> colours =
            branch_colours(tree, colour, request.depiction, cache_, tissues.empty() ? nullptr : &tissues);
        const bool notes = ARBOR_HAS_FIELD(arbor_tf_set, out.struct_size, note_size) && out.notes && out.note_size > 1;
        // The background stays clear: opacity fades in from its level over
        // the width of its noise, and branch intervals start above it.
        const bool clear = params().flag("clear-background") &&
                           ARBOR_HAS_FIELD(arbor_tf_request, request.struct_size, background_peak) &&
                           std::isfinite(request.background_level) &&
                           request.background_level > request.background_peak;
        const double background = clear ? request.background_level : -INFINITY;
        const double fade_width = clear ? request.background_level - request.background_peak : 0.0;
        const auto fade = [&](double value) {
            if (!clear)
                return 1.0;
            const double u = std::clamp((value - background) / fade_width, 0.0, 1.0);
            return u * u * (3 - 2 * u);
        };
        const uint32_t n = tree.size();
        // Per branch its shape (automatic or the one given) and its corners.
        std::vector<ShapeSettings> shapes(n, fixed);
        std::vector<std::vector<double>> corners(n);
        std::size_t total_points = 0;
        for (uint32_t b = 0; b < n; ++b) {
            if (automatic) {
                const ShapeChoice choice = choose_shape(tree, b, request.min_spacing);
                shapes[b].shape = choice.shape;
                if (notes)
                    std::snprintf(out.notes + std::size_t{b} * out.note_size, out.note_size, "%s", choice.why.c_str());
            } else if (notes) {
                out.notes[std::size_t{b} * out.note_size] = '\0';
            }
            if (notes && !tissues.empty()) {
                // After the shape's reason: the colour family's.
                char *note = out.notes + std::size_t{b} * out.note_size;
                const std::size_t used = std::strlen(note);
                std::snprintf(note + used, out.note_size - used, "%scolour: %s (%s)", used ? "; " : "",
                              hue_families()[tissues[b].family].name, tissues[b].why.c_str());
            }
            corners[b] = shape_corners(shapes[b]);
            total_points += corners[b].size();
        }
        auto *points = static_cast<arbor_tf_point *>(task.allocate(sizeof(arbor_tf_point) * total_points));
        const arbor_depiction *depiction = request.depiction;
        out.point_offsets[0] = 0;
        for (uint32_t b = 0; b < n; ++b)
            out.point_offsets[b + 1] = out.point_offsets[b] + static_cast<uint32_t>(corners[b].size());
        for (uint32_t b = 0; b < n; ++b) {
            if ((b & 1023) == 0)
                task.progress(static_cast<double>(b) / n, "transfer functions");
            // t: 0 at the saddle, 1 at the extremum (the root: minimum to
            // maximum), from where the interval leaves the background.
            double saddle = b == 0 ? request.value_range[0] : tree.saddle_value(b);
            const double extremum = b == 0 ? request.value_range[1] : tree.extremum_value(b);
            if (saddle < background && background < extremum)
                saddle = background;
            const auto t_of = [&](double value) {
                return extremum != saddle ? (value - saddle) / (extremum - saddle) : 1.0;
            };
            const ShapeSettings &shape = shapes[b];
            const auto rgba = [&](double t) {
                double alpha = shape_opacity(shape, t, ranges[b].low, ranges[b].high) *
                               fade(saddle + (extremum - saddle) * t);
                if (depiction)
                    alpha *= depiction->opacity_at_saddle[b] +
                             (depiction->opacity_at_extremum[b] - depiction->opacity_at_saddle[b]) * t;
                const Rgb &c = colours[b].rgb;
                return std::array<float, 4>{static_cast<float>(c.r), static_cast<float>(c.g), static_cast<float>(c.b),
                                            static_cast<float>(alpha)};
            };
            bake_lut(out, b, branch_domain(tree, request, b), [&](double value) { return rgba(t_of(value)); });
            const std::vector<double> &c = corners[b];
            for (std::size_t i = 0; i < c.size(); ++i) {
                // Points ascend in value: for minima t runs downwards.
                const double t = saddle <= extremum ? c[i] : c[c.size() - 1 - i];
                arbor_tf_point &pt = points[out.point_offsets[b] + i];
                pt.value = saddle + (extremum - saddle) * t;
                const std::array<float, 4> colour = rgba(t);
                for (int k = 0; k < 4; ++k)
                    pt.rgba[k] = std::clamp(colour[k], 0.0f, 1.0f);
            }
        }
        out.points = points;
    }

private:
    ColourCache cache_;
};

} // namespace

sdk::Instance *create_residue_flow(const arbor_host *host)
{
    return new ResidueFlowGenerator(host);
}

} // namespace arbor::tf
