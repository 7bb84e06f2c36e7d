// The OpenCV denoising filters through the ABI: on the noisy phantom they cut
// the contour tree's branch count by a large factor while its structures -
// the faint tumour included - survive ITri simplification; constant volumes
// stay constant; types OpenCV cannot take are refused clearly.
#include "plugin_fixture.hpp"

#include "io/phantom.hpp"
#include "host/filter_run.hpp"
#include "host/simplifier_importance.hpp"
#include "topology/simplification.hpp"
#include "topology/topology_pipeline.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace arbor {
namespace {

PluginInstance filter(const std::string &name, const std::map<std::string, std::string> &params = {})
{
    PluginInstance f = test::built_plugins().create("org.arbor.filter." + name);
    for (const auto &[k, v] : params)
        f.set_param(k, parse_param_value(*f.find_param(k), v).value);
    return f;
}

const Volume &noisy_phantom()
{
    static const Volume v = [] {
        io::PhantomOptions o;
        o.noise_sigma = 8;
        o.blobs = 20;
        return io::make_phantom(io::builtin_phantom("head"), o);
    }();
    return v;
}

struct TreeSummary {
    std::size_t branches = 0;
    bool tumour_kept = false;
};

TreeSummary summarise(const Volume &v)
{
    const topology::TopologyResult topo = topology::compute_contour_tree(v);
    PluginInstance itri = test::built_plugins().create("org.arbor.simplifier.itri");
    const topology::FieldView field{v.type(), v.data(), static_cast<uint32_t>(v.voxel_count()), &v.geometry()};
    const topology::BranchDecomposition d = topology::decompose_branches(topo.tree, field, simplifier_importance(itri));
    const topology::SimplificationCut cut = topology::cut_by_count(d, 13);
    TreeSummary s;
    s.branches = d.branches.size();
    for (uint32_t b : cut.kept) {
        const auto p = v.geometry().position_of(topo.tree.node_vertex[d.branches[b].extremum_node]);
        s.tumour_kept = s.tumour_kept || std::hypot(p[0] + 27, p[1] - 47, p[2] - 10) < 8;
    }
    return s;
}

TEST(OpenCvFilters, GaussianCutsTheTreeAndKeepsTheTumour)
{
    const TreeSummary raw = summarise(noisy_phantom());
    ASSERT_TRUE(raw.tumour_kept);
    PluginInstance g = filter("gaussian", {{"sigma", "3"}});
    const TreeSummary smooth = summarise(run_filter(g, noisy_phantom(), nullptr, uint64_t{1} << 32));
    std::printf("branches: %zu unfiltered, %zu after gaussian sigma 3 mm\n", raw.branches, smooth.branches);
    EXPECT_GT(raw.branches, 15 * smooth.branches);
    EXPECT_TRUE(smooth.tumour_kept);
}

TEST(OpenCvFilters, EveryFilterReducesTheBranchCount)
{
    const TreeSummary raw = summarise(noisy_phantom());
    for (const auto &[name, params] : std::vector<std::pair<std::string, std::map<std::string, std::string>>>{
             {"median", {{"size", "5"}}}, {"bilateral", {}}, {"nlmeans", {{"h", "0.03"}}}}) {
        PluginInstance f = filter(name, params);
        const Volume out = run_filter(f, noisy_phantom(), nullptr, uint64_t{1} << 32);
        EXPECT_EQ(out.type(), noisy_phantom().type()) << name;
        const TreeSummary s = summarise(out);
        std::printf("branches after %s: %zu\n", name.c_str(), s.branches);
        EXPECT_LT(s.branches, raw.branches * 0.6) << name;
    }
}

TEST(OpenCvFilters, ConstantVolumesStayConstant)
{
    Geometry g;
    g.dims = {20, 16, 12};
    g.spacing = {0.7, 1.0, 2.5};
    Volume v = Volume::allocate(ARBOR_VOXEL_I16, g, {}, uint64_t{1} << 30);
    for (int64_t i = 0; i < v.voxel_count(); ++i)
        v.as<int16_t>()[i] = -700;
    for (const char *name : {"gaussian", "median", "bilateral"}) {
        PluginInstance f = filter(name);
        const Volume out = run_filter(f, v, nullptr, uint64_t{1} << 30);
        for (int64_t i = 0; i < out.voxel_count(); ++i)
            ASSERT_EQ(out.as<int16_t>()[i], -700) << name << " voxel " << i;
    }
}

TEST(OpenCvFilters, UnsupportedTypesAreRefusedClearly)
{
    Geometry g;
    g.dims = {8, 8, 8};
    Volume v = Volume::allocate(ARBOR_VOXEL_F32, g, {}, uint64_t{1} << 30);
    PluginInstance nl = filter("nlmeans");
    try {
        run_filter(nl, v, nullptr, uint64_t{1} << 30);
        FAIL() << "non-local means accepted a float volume";
    } catch (const PluginError &e) {
        EXPECT_NE(std::string(e.what()).find("8- and 16-bit"), std::string::npos) << e.what();
    }
    PluginInstance median = filter("median", {{"size", "7"}});
    EXPECT_THROW(run_filter(median, v, nullptr, uint64_t{1} << 30), PluginError);
}

} // namespace
} // namespace arbor
