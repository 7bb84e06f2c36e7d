// The depictors and transfer-function generators through the ABI: the
// inclusion invariant and the opacity range for every shape and several
// flow rates, the flow rate moving opacity inwards, neighbourhoods and
// wheel positions on a hand-built tree, the baseline's global function, and
// the phantom's tumour against its skin.
#include "branch_tree_builder.hpp"
#include "plugin_fixture.hpp"

#include "branch_colours.hpp" // plugins/tf-generators: the colour targets
#include "colour_space.hpp"
#include "harmonic_template.hpp"
#include "tissue_hues.hpp"
#include "io/phantom.hpp"
#include "host/branch_tree_record.hpp"
#include "host/simplifier_importance.hpp"
#include "host/tf_generation.hpp"
#include "relation_wheel.hpp" // plugins/depictors
#include "topology/topology_pipeline.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace arbor {
namespace {

constexpr uint32_t kLut = 64;

PluginInstance create(const std::string &id)
{
    return test::built_plugins().create(id);
}

void set_text(PluginInstance &p, const std::string &param, const std::string &text)
{
    p.set_param(param, parse_param_value(*p.find_param(param), text).value);
}

// 0 -> {1, 2}; 1 -> {3, 4, 5}; 2 -> {6}; 3 -> {7}.  Branch 5 is a minimum.
test::BranchTreeBuilder hand_tree()
{
    test::BranchTreeBuilder t({-1, 0, 0, 1, 1, 1, 2, 3});
    // saddle, extremum, minimum?, relative p, v, hv
    t.set(1, 10, 80, false, 0.7, 0.5, 0.6);
    t.set(2, 5, 40, false, 0.35, 0.3, 0.2);
    t.set(3, 30, 75, false, 0.45, 0.2, 0.25);
    t.set(4, 40, 60, false, 0.2, 0.05, 0.04);
    t.set(5, 50, 20, true, 0.3, 0.04, 0.03);
    t.set(6, 20, 35, false, 0.15, 0.1, 0.05);
    t.set(7, 60, 70, false, 0.1, 0.02, 0.02);
    return t;
}

arbor_tf_request request_for(const arbor_branch_tree &tree, const arbor_depiction *depiction = nullptr)
{
    arbor_tf_request r{};
    r.struct_size = sizeof r;
    r.tree = &tree;
    r.depiction = depiction;
    r.value_range[0] = 0;
    r.value_range[1] = 100;
    r.min_spacing = 1;
    return r;
}

std::pair<float, float> alpha_range(const TransferFunctions &tf, uint32_t b)
{
    float lo = 1, hi = 0;
    for (uint32_t i = 0; i < tf.lut_size(); ++i) {
        lo = std::min(lo, tf.lut(b)[4 * i + 3]);
        hi = std::max(hi, tf.lut(b)[4 * i + 3]);
    }
    return {lo, hi};
}

// Opacity of branch b at a value inside its domain (linear in the LUT).
float alpha_at(const TransferFunctions &tf, uint32_t b, double value)
{
    const auto [lo, hi] = tf.domain(b);
    const double x = hi > lo ? (value - lo) / (hi - lo) * (tf.lut_size() - 1) : 0.0;
    const uint32_t i = std::min<uint32_t>(static_cast<uint32_t>(x), tf.lut_size() - 2);
    const double f = x - i;
    return static_cast<float>((1 - f) * tf.lut(b)[4 * i + 3] + f * tf.lut(b)[4 * (i + 1) + 3]);
}

// Hue in degrees of a straight sRGB colour, and its HSV saturation.
std::pair<double, double> hue_of(const float *c)
{
    const float mx = std::max({c[0], c[1], c[2]}), mn = std::min({c[0], c[1], c[2]});
    double h = 0;
    if (mx > mn) {
        if (mx == c[0])
            h = 60 * std::fmod((c[1] - c[2]) / (mx - mn) + 6.0, 6.0);
        else if (mx == c[1])
            h = 60 * ((c[2] - c[0]) / (mx - mn) + 2);
        else
            h = 60 * ((c[0] - c[1]) / (mx - mn) + 4);
    }
    return {h, mx > 0 ? (mx - mn) / mx : 0.0};
}

TEST(TransferFunctions, InnerBranchesAreMoreOpaqueAndOpacityStaysInRange)
{
    test::BranchTreeBuilder builder = hand_tree();
    const arbor_branch_tree &tree = builder.record();
    PluginInstance g = create("org.arbor.tf.residue-flow");
    set_text(g, "alpha-min", "0.05"); // the range is then [0.05, 0.95]
    for (const char *shape : {"ramp", "inverse-ramp", "hat", "box", "peak"})
        for (double q : {0.0, 30.0, 120.0, 300.0}) {
            set_text(g, "shape", shape);
            set_text(g, "flow-rate", std::to_string(q));
            TransferFunctions tf(tree.branch_count, kLut, 1.0);
            generate_transfer_functions(g, request_for(tree), tf);
            for (uint32_t b = 0; b < tree.branch_count; ++b) {
                const auto [lo, hi] = alpha_range(tf, b);
                EXPECT_GE(lo, 0.05f - 1e-6f) << shape << " Q " << q << " branch " << b;
                EXPECT_LE(hi, 0.95f + 1e-6f) << shape << " Q " << q << " branch " << b;
                // Every ancestor's opacity stays below this branch's.
                for (int32_t a = tree.parent[b]; a >= 0; a = tree.parent[a])
                    EXPECT_LE(alpha_range(tf, static_cast<uint32_t>(a)).second, lo + 1e-6f)
                        << shape << " Q " << q << ": branch " << b << " vs ancestor " << a;
            }
        }
}

// --shape auto: a thin shell gets a hat (or, a voxel thick, an isovalue
// peak), a solid plateau a box, a solid peaked structure a ramp, a bulk with
// a spike an inverse ramp; the root a ramp; each says why in its note.
TEST(TransferFunctions, AutomaticShapesFollowThicknessAndWhereTheValuesLie)
{
    test::BranchTreeBuilder builder({-1, 0, 1, 1, 1, 1});
    for (uint32_t b = 1; b < 6; ++b)
        builder.set(b, 10.0 * b, 10.0 * b + 20, false, 0.2, 0.1, 0.1);
    builder.set_shape(0, 30, 0.5);
    builder.set_shape(1, 2.5, 0.05); // a shell 2.5 voxels thick
    builder.set_shape(2, 1.0, 0.03); // a sheet a voxel thick
    builder.set_shape(3, 8, 0.4);    // solid ...
    builder.set_shape(4, 8, 0.4);
    builder.set_shape(5, 8, 0.4);
    builder.set_absolute(3, 20, 100, 0.8 * 20 * 100); // ... its values near the extremum
    builder.set_absolute(4, 20, 100, 0.4 * 20 * 100); // ... spread
    builder.set_absolute(5, 20, 100, 0.1 * 20 * 100); // ... near the saddle
    const arbor_branch_tree &tree = builder.record();
    PluginInstance g = create("org.arbor.tf.residue-flow");
    TransferFunctions tf(tree.branch_count, kLut, 1.0);
    generate_transfer_functions(g, request_for(tree), tf);
    const char *want[] = {"ramp:", "hat:", "peak:", "box:", "ramp:", "inverse ramp:"};
    for (uint32_t b = 0; b < 6; ++b)
        EXPECT_EQ(tf.note(b).rfind(want[b], 0), 0u) << "branch " << b << ": " << tf.note(b);
    // The box is flat over its interval, the inverse ramp falls towards its extremum.
    EXPECT_NEAR(alpha_at(tf, 3, 31), alpha_at(tf, 3, 49), 1e-3);
    EXPECT_GT(alpha_at(tf, 5, 52), alpha_at(tf, 5, 68));
    // Without the host's columns every branch but the root is solid.
    test::BranchTreeBuilder plain = hand_tree();
    TransferFunctions tf2(plain.record().branch_count, kLut, 1.0);
    generate_transfer_functions(g, request_for(plain.record()), tf2);
    EXPECT_EQ(tf2.note(0).rfind("ramp:", 0), 0u);
    for (uint32_t b = 1; b < plain.record().branch_count; ++b)
        EXPECT_EQ(tf2.note(b).find("thin"), std::string::npos) << tf2.note(b);
}

// The background the host found stays transparent: every branch's opacity
// is 0 at or below its level and fades in over its noise's width.
TEST(TransferFunctions, TheBackgroundStaysClear)
{
    test::BranchTreeBuilder builder = hand_tree();
    const arbor_branch_tree &tree = builder.record();
    PluginInstance g = create("org.arbor.tf.residue-flow");
    set_text(g, "shape", "box");
    arbor_tf_request r = request_for(tree);
    r.background_peak = 2;
    r.background_level = 12;
    TransferFunctions tf(tree.branch_count, kLut, 1.0);
    generate_transfer_functions(g, r, tf);
    EXPECT_EQ(alpha_at(tf, 0, 5), 0.0f);
    EXPECT_EQ(alpha_at(tf, 0, 10), 0.0f); // (a lookup-table step below the level)
    EXPECT_GT(alpha_at(tf, 0, 30), 0.0f);
    EXPECT_LT(alpha_at(tf, 0, 16), alpha_at(tf, 0, 30)); // fading in
    // Switched off, the root's box starts at its saddle again.
    set_text(g, "clear-background", "false");
    TransferFunctions off(tree.branch_count, kLut, 1.0);
    generate_transfer_functions(g, r, off);
    EXPECT_GT(alpha_at(off, 0, 5), 0.0f);
}

TEST(TransferFunctions, InclusionDepictionKeepsInnerBranchesMoreOpaque)
{
    test::BranchTreeBuilder builder = hand_tree();
    const arbor_branch_tree &tree = builder.record();
    PluginInstance g = create("org.arbor.tf.residue-flow");
    PluginInstance inclusion = create("org.arbor.depictor.inclusion");
    DepictionRecord d(tree.branch_count);
    arbor_depiction_request dr{sizeof(arbor_depiction_request), -1, &tree};
    depict(inclusion, dr, d);
    for (double q : {0.0, 60.0, 300.0}) {
        set_text(g, "flow-rate", std::to_string(q));
        TransferFunctions tf(tree.branch_count, kLut, 1.0);
        generate_transfer_functions(g, request_for(tree, &d.record()), tf);
        for (uint32_t b = 1; b < tree.branch_count; ++b) {
            const uint32_t p = static_cast<uint32_t>(tree.parent[b]);
            // Continuous at the saddle, and more opaque than the parent at its most opaque.
            EXPECT_GE(alpha_at(tf, b, tree.saddle_value[b]) + 1e-3f, alpha_at(tf, p, tree.saddle_value[b]))
                << "Q " << q << " branch " << b;
            EXPECT_GT(alpha_range(tf, b).second, alpha_range(tf, p).second) << "Q " << q << " branch " << b;
        }
    }
    // The inclusion depictor's relation: a is included by b iff b is a proper ancestor.
    const auto &table = inclusion.interface<arbor_depictor_v1>(ARBOR_INTERFACE_DEPICTOR);
    const auto included = [&](uint32_t a, uint32_t b) {
        arbor_bool32 r = 0;
        inclusion.check(table.related(inclusion.get(), &tree, a, b, &r), "related");
        return r != 0;
    };
    EXPECT_TRUE(included(7, 3));
    EXPECT_TRUE(included(7, 1));
    EXPECT_TRUE(included(7, 0));
    EXPECT_FALSE(included(3, 7));
    EXPECT_FALSE(included(4, 3)); // siblings
    EXPECT_FALSE(included(6, 1));
    EXPECT_FALSE(included(3, 3));
}

TEST(TransferFunctions, RaisingTheFlowRateMovesOpacityInwards)
{
    test::BranchTreeBuilder builder = hand_tree();
    const arbor_branch_tree &tree = builder.record();
    PluginInstance g = create("org.arbor.tf.residue-flow");
    set_text(g, "shape", "ramp");
    std::vector<double> root, leaf;
    for (double q = 0; q <= 300; q += 20) {
        set_text(g, "flow-rate", std::to_string(q));
        TransferFunctions tf(tree.branch_count, kLut, 1.0);
        generate_transfer_functions(g, request_for(tree), tf);
        const auto r = alpha_range(tf, 0), l = alpha_range(tf, 7);
        root.push_back(r.second - r.first); // what the outermost branch absorbs
        leaf.push_back(l.second - l.first); // what the innermost receives
    }
    for (std::size_t i = 1; i < root.size(); ++i) {
        EXPECT_LE(root[i], root[i - 1] + 1e-6) << i;
        EXPECT_GE(leaf[i], leaf[i - 1] - 1e-6) << i;
    }
    // Q = K: the root (relative persistence 1, two children) keeps half.
    EXPECT_NEAR(root.back(), 0.5 * root.front(), 1e-6);
    EXPECT_GT(leaf.back(), 1.5 * leaf.front());
}

TEST(TransferFunctions, NeighboursGetTheirSectorsOfTheRelationWheel)
{
    test::BranchTreeBuilder builder = hand_tree();
    const arbor_branch_tree &tree = builder.record();
    PluginInstance n = create("org.arbor.depictor.neighbour");
    set_text(n, "rotation", "30");
    DepictionRecord d(tree.branch_count);
    arbor_depiction_request dr{sizeof(arbor_depiction_request), 1, &tree};
    depict(n, dr, d);
    const arbor_depiction &r = d.record();
    const arbor_branch_role expected[] = {ARBOR_ROLE_PARENT, ARBOR_ROLE_SELECTED, ARBOR_ROLE_SIBLING, ARBOR_ROLE_CHILD,
                                          ARBOR_ROLE_CHILD,  ARBOR_ROLE_CHILD,    ARBOR_ROLE_OTHER,   ARBOR_ROLE_OTHER};
    for (uint32_t b = 0; b < 8; ++b)
        EXPECT_EQ(r.role[b], expected[b]) << b;
    const auto angle = [](double a, double b) { return std::fabs(std::remainder(a - b, 360.0)); };
    const double half = depictors::RelationWheel::kSectorWidth / 2;
    for (uint32_t c : {3u, 4u, 5u})
        EXPECT_LT(angle(r.hue[c], 30.0), half) << c;
    EXPECT_LT(angle(r.hue[2], 210.0), half);
    EXPECT_NEAR(angle(r.hue[1], 120.0), 0.0, 1e-4);
    EXPECT_NEAR(angle(r.hue[0], 300.0), 0.0, 1e-4);
    // The three children spread over their sector, apart from each other.
    EXPECT_GT(angle(r.hue[3], r.hue[4]), 20.0);
    EXPECT_GT(angle(r.hue[4], r.hue[5]), 20.0);
    for (uint32_t b : {6u, 7u}) {
        EXPECT_TRUE(std::isnan(r.hue[b]));
        EXPECT_LT(r.saturation[b], 0.5f);
        EXPECT_LT(r.opacity_at_extremum[b], 0.5f);
    }
    // The relation: parent, child or sibling of b.
    const auto &table = n.interface<arbor_depictor_v1>(ARBOR_INTERFACE_DEPICTOR);
    const auto related = [&](uint32_t a, uint32_t b) {
        arbor_bool32 out = 0;
        n.check(table.related(n.get(), &tree, a, b, &out), "related");
        return out != 0;
    };
    EXPECT_TRUE(related(0, 1));
    EXPECT_TRUE(related(3, 1));
    EXPECT_TRUE(related(2, 1));
    EXPECT_FALSE(related(7, 1)); // grandchild
    EXPECT_FALSE(related(6, 1)); // nephew
    // The generator honours the wheel: neighbours' colours have their hues.
    PluginInstance g = create("org.arbor.tf.residue-flow");
    TransferFunctions tf(tree.branch_count, kLut, 1.0);
    generate_transfer_functions(g, request_for(tree, &r), tf);
    for (uint32_t b : {0u, 1u, 2u, 3u, 4u, 5u}) {
        const auto [h, s] = hue_of(tf.lut(b) + 4 * (kLut - 1));
        if (s > 0.05) {
            EXPECT_LT(angle(h, r.hue[b]), 2.0) << "branch " << b << " hue " << h << " wanted " << r.hue[b];
        }
    }
}

TEST(TransferFunctions, HuesStayInsideTheHarmonicTemplate)
{
    test::BranchTreeBuilder builder = test::BranchTreeBuilder::random(40, 3);
    const arbor_branch_tree &tree = builder.record();
    PluginInstance g = create("org.arbor.tf.residue-flow");
    for (const char *spec : {"X:30", "V", "L:200", "i:90", "Y:10", "T", "I"}) {
        set_text(g, "hues", spec);
        TransferFunctions tf(tree.branch_count, kLut, 1.0);
        generate_transfer_functions(g, request_for(tree), tf);
        const tf::HarmonicTemplate t = tf::HarmonicTemplate::parse(spec);
        for (uint32_t b = 0; b < tree.branch_count; ++b) {
            const auto [h, s] = hue_of(tf.lut(b) + 4 * (kLut - 1));
            if (s > 0.1) { // nearly grey colours have no meaningful hue
                EXPECT_TRUE(t.contains(h, 1.5)) << spec << " branch " << b << " hue " << h;
            }
        }
    }
    set_text(g, "hues", "Q:10");
    TransferFunctions tf(tree.branch_count, kLut, 1.0);
    try {
        generate_transfer_functions(g, request_for(tree), tf);
        FAIL() << "unknown template accepted";
    } catch (const PluginError &e) {
        EXPECT_NE(std::string(e.what()).find("hues"), std::string::npos) << e.what();
    }
}

// On a CT each branch's hue family follows its tissue, read from the mean
// of its values (f_min + hypervolume / volume) and, for bone, its peak.
TEST(TransferFunctions, OnACtTheHueFollowsTheTissue)
{
    // Stored values are HU over [-1024, 3071]; every branch 1000 voxels.
    test::BranchTreeBuilder builder({-1, 0, 0, 0, 0, 0, 0});
    struct Made {
        double saddle, peak, mean;
        const char *family;
    };
    const Made made[] = {{-950, -700, -800, "lung and airways"}, {-150, -60, -100, "fat"},
                         {-20, 90, 40, "soft tissue"},          {150, 400, 250, "contrast"},
                         {150, 1200, 250, "bone"},              {300, 1500, 900, "bone"}};
    for (uint32_t b = 1; b < 7; ++b) {
        const Made &m = made[b - 1];
        builder.set(b, m.saddle, m.peak, m.peak < m.saddle, 0.5, 1000, (m.mean + 1024) * 1000);
    }
    const arbor_branch_tree &tree = builder.record();
    int16_t voxel = 0;
    arbor_volume volume{};
    volume.struct_size = sizeof volume;
    volume.voxel_type = ARBOR_VOXEL_I16;
    for (int a = 0; a < 3; ++a)
        volume.dims[a] = 1, volume.spacing[a] = 1;
    volume.value_scale = 1;
    volume.value_unit = "HU";
    volume.voxels = &voxel;
    arbor_tf_request r = request_for(tree);
    r.value_range[0] = -1024;
    r.value_range[1] = 3071;
    r.volume = &volume;
    r.background_level = r.background_peak = std::nan("");
    PluginInstance g = create("org.arbor.tf.residue-flow");
    const auto generated = [&] {
        auto tf = std::make_unique<TransferFunctions>(tree.branch_count, kLut, 1.0);
        generate_transfer_functions(g, r, *tf);
        return tf;
    };
    const auto family = [](const std::string &name) {
        for (const tf::HueFamily &f : tf::hue_families())
            if (name == f.name)
                return f;
        throw std::invalid_argument(name);
    };
    const auto check = [&](const TransferFunctions &tf, const std::string &unit) {
        for (uint32_t b = 0; b < 7; ++b) {
            const std::string name = b == 0 ? "soft tissue" : made[b - 1].family;
            EXPECT_NE(tf.note(b).find("colour: " + name), std::string::npos) << b << ": " << tf.note(b);
            const tf::HueFamily f = family(name);
            const auto [h, sat] = hue_of(tf.lut(b) + 4 * (kLut - 1));
            const double off = std::fabs(std::remainder(h - f.hue, 360.0));
            EXPECT_LE(off, f.width / 2 + 1.5) << name << " branch " << b << " hue " << h;
            const tf::Lab lab = tf::srgb_to_lab({tf.lut(b)[4 * (kLut - 1)], tf.lut(b)[4 * (kLut - 1) + 1],
                                             tf.lut(b)[4 * (kLut - 1) + 2]});
            EXPECT_GE(lab.L, f.lightness_min - 1) << name;
            EXPECT_LE(lab.L, f.lightness_max + 1) << name;
        }
        EXPECT_NE(tf.note(0).find(unit), std::string::npos) << tf.note(0);
    };
    check(*generated(), "values in HU");
    // No unit, but the air around the body at -1000: taken as HU.
    volume.value_unit = "";
    r.background_peak = -1003;
    r.background_level = -950;
    check(*generated(), "the air at -1003 HU: taken as HU");
    // Not a CT (the background at 0), or hues asked for: the harmonic wheel.
    r.background_peak = 0;
    r.background_level = 40;
    EXPECT_EQ(generated()->note(3).find("colour:"), std::string::npos);
    volume.value_unit = "HU";
    set_text(g, "hues", "full");
    EXPECT_EQ(generated()->note(3).find("colour:"), std::string::npos);
}

TEST(TransferFunctions, RelationWheelLegendIsDrawn)
{
    test::BranchTreeBuilder builder = hand_tree();
    const arbor_branch_tree &tree = builder.record();
    PluginInstance n = create("org.arbor.depictor.neighbour");
    const auto &table = n.interface<arbor_depictor_v1>(ARBOR_INTERFACE_DEPICTOR);
    std::vector<float> rgba(256 * 256 * 4, -1.0f);
    arbor_image image{sizeof(arbor_image), 256, 256, 0, 4 * 256, rgba.data(), nullptr, nullptr, 0, 0, 0};
    arbor_depiction_request dr{sizeof(arbor_depiction_request), 1, &tree};
    Task task;
    n.check(table.legend(n.get(), &dr, &image, task.get()), "legend");
    std::size_t coloured = 0;
    for (std::size_t i = 0; i < rgba.size(); i += 4) {
        for (int c = 0; c < 4; ++c)
            ASSERT_TRUE(rgba[i + c] >= 0.0f && rgba[i + c] <= 1.0f);
        const float mx = std::max({rgba[i], rgba[i + 1], rgba[i + 2]}), mn = std::min({rgba[i], rgba[i + 1], rgba[i + 2]});
        coloured += mx - mn > 0.3f;
    }
    EXPECT_GT(coloured, 200u) << "no hue markers drawn";
    dr.selected_branch = -1;
    EXPECT_EQ(table.legend(n.get(), &dr, &image, task.get()), ARBOR_ERROR_INVALID_ARGUMENT);
}

TEST(TransferFunctions, HistogramBaselineIsOneGlobalFunction)
{
    test::BranchTreeBuilder builder = hand_tree();
    const arbor_branch_tree &tree = builder.record();
    io::PhantomOptions o;
    o.size = 32;
    const Volume volume = io::make_phantom(io::builtin_phantom("head"), o);
    const arbor_volume view = volume.view();
    arbor_tf_request r = request_for(tree);
    r.volume = &view;
    PluginInstance g = create("org.arbor.tf.histogram-ramp");
    TransferFunctions tf(tree.branch_count, kLut, 1.0);
    generate_transfer_functions(g, r, tf);
    // Branches 1 and 3 overlap on [30, 75]: the same value gets the same opacity.
    for (double value : {35.0, 50.0, 70.0})
        EXPECT_NEAR(alpha_at(tf, 1, value), alpha_at(tf, 3, value), 2e-3) << value;
    r.volume = nullptr;
    EXPECT_THROW(generate_transfer_functions(g, r, tf), PluginError);
}

// The noisy phantom simplified by ITri: the tumour is the deepest branch.
struct PhantomTree {
    Volume volume;
    topology::TopologyResult topo;
    topology::BranchDecomposition branches;
    topology::SimplificationCut cut;
    std::unique_ptr<BranchTreeRecord> record;
    uint32_t tumour = 0;

    PhantomTree()
    {
        const io::PhantomRecipe recipe = io::builtin_phantom("head");
        io::PhantomOptions o;
        o.noise_sigma = 8;
        volume = io::make_phantom(recipe, o);
        topo = topology::compute_contour_tree(volume);
        PluginInstance itri = create("org.arbor.simplifier.itri");
        const topology::FieldView field{volume.type(), volume.data(), static_cast<uint32_t>(volume.voxel_count()),
                                        &volume.geometry()};
        branches = topology::decompose_branches(topo.tree, field, simplifier_importance(itri));
        cut = topology::cut_by_count(branches, 12);
        record = std::make_unique<BranchTreeRecord>(topo.tree, branches, cut, volume);
        const arbor_branch_tree &t = record->record();
        for (uint32_t b = 0; b < t.branch_count; ++b) {
            const double *p = t.extremum_position + 3 * b;
            if (std::hypot(p[0] + 27, p[1] - 47, p[2] - 10) < 8)
                tumour = b;
        }
    }
};

TEST(TransferFunctions, OnThePhantomTheTumourIsMostOpaqueAndVividTheSkinLeast)
{
    const PhantomTree ph;
    const arbor_branch_tree &t = ph.record->record();
    ASSERT_GT(ph.tumour, 0u) << "ITri kept no tumour branch";
    for (uint32_t b = 0; b < t.branch_count; ++b)
        EXPECT_LE(t.depth[b], t.depth[ph.tumour]) << "the tumour is the deepest branch";
    PluginInstance g = create("org.arbor.tf.residue-flow");
    PluginInstance inclusion = create("org.arbor.depictor.inclusion");
    DepictionRecord d(t.branch_count);
    arbor_depiction_request dr{sizeof(arbor_depiction_request), -1, &t};
    depict(inclusion, dr, d);
    arbor_tf_request r = request_for(t, &d.record());
    r.value_range[0] = ph.branches.global_min;
    r.value_range[1] = ph.branches.global_max;
    TransferFunctions tf(t.branch_count, 256, 1.0);
    generate_transfer_functions(g, r, tf);
    // The skin is the outermost structure: the root branch (global minimum in
    // the air to the global maximum in the scalp).
    for (uint32_t b = 0; b < t.branch_count; ++b) {
        if (b != ph.tumour) {
            EXPECT_GT(alpha_range(tf, ph.tumour).second, alpha_range(tf, b).second) << b;
        }
        if (b != 0) {
            EXPECT_LT(alpha_range(tf, 0).second, alpha_range(tf, b).second) << b;
        }
    }
    // Vividness as the generator asks for it, and what the colours achieve.
    tf::ColourCache cache;
    const sdk::BranchTreeView view(&t);
    const auto colours = tf::branch_colours(view, tf::ColourSettings{}, &d.record(), cache);
    for (uint32_t b = 0; b < t.branch_count; ++b) {
        if (b != ph.tumour) {
            EXPECT_GT(colours[ph.tumour].vividness, colours[b].vividness) << b;
        }
        if (b != 0) {
            EXPECT_LT(colours[0].vividness, colours[b].vividness) << b;
        }
        const tf::LightVivid &c = cache.find(colours[b].hue, colours[b].lightness, colours[b].vividness);
        if (c.exact) {
            EXPECT_NEAR(c.achieved_L, colours[b].lightness, 0.01) << b;
            EXPECT_NEAR(c.achieved_vividness, colours[b].vividness, 0.01) << b;
        } else {
            // Out of the sRGB gamut: the lightness is kept at the most vivid
            // colour there, or the vividness at a darker colour.
            const bool kept_l = std::fabs(c.achieved_L - colours[b].lightness) < 0.01 &&
                                c.achieved_vividness < colours[b].vividness;
            const bool kept_v = std::fabs(c.achieved_vividness - colours[b].vividness) < 0.01 &&
                                c.achieved_L < colours[b].lightness;
            EXPECT_TRUE(kept_l || kept_v) << b;
        }
    }
}

} // namespace
} // namespace arbor
