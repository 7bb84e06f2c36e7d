// The OpenCV denoising filters through the ABI: on the noisy phantom they cut
// the contour tree's branch count by a large factor while its structures -
// the faint tumour included - survive ITri simplification; constant volumes
// stay constant; the Gaussian equals its convolution written out; types
// OpenCV cannot take are refused clearly.
#include "plugin_fixture.hpp"

#include "io/phantom.hpp"
#include "host/filter_run.hpp"
#include "host/simplifier_importance.hpp"
#include "topology/simplification.hpp"
#include "topology/topology_pipeline.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

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

// The oracle: the 3D Gaussian written out, one axis after another, in
// double precision: weights exp(-d^2 / 2 s^2) over |d| <= max(1, ceil(3 s))
// voxels (s = sigma / spacing), normalised, the edge voxel repeated beyond
// the volume.  The volume spans two of the filter's z-column blocks and more
// slices than one step per core.
TEST(OpenCvFilters, GaussianEqualsTheConvolutionWrittenOut)
{
    Geometry g;
    g.dims = {70, 64, 23};
    g.spacing = {0.7, 1.0, 2.5};
    Volume v = Volume::allocate(ARBOR_VOXEL_F32, g, {}, uint64_t{1} << 30);
    uint32_t state = 12345;
    for (int64_t i = 0; i < v.voxel_count(); ++i) {
        state = state * 1664525u + 1013904223u;
        v.as<float>()[i] = static_cast<float>(state >> 8) / static_cast<float>(1u << 24) * 1000.0f - 300.0f;
    }
    const double sigma = 1.5;
    PluginInstance f = filter("gaussian", {{"sigma", "1.5"}});
    const Volume out = run_filter(f, v, nullptr, uint64_t{1} << 30);

    const int64_t n[3] = {g.dims[0], g.dims[1], g.dims[2]};
    std::vector<double> a(v.as<float>(), v.as<float>() + v.voxel_count()), b(a.size());
    for (int axis = 0; axis < 3; ++axis) {
        const double s = sigma / g.spacing[axis];
        const int half = std::max(1, static_cast<int>(std::ceil(3 * s)));
        std::vector<double> w(2 * half + 1);
        double total = 0;
        for (int d = -half; d <= half; ++d)
            total += w[d + half] = std::exp(-d * d / (2 * s * s));
        const int64_t step = axis == 0 ? 1 : axis == 1 ? n[0] : n[0] * n[1];
        for (int64_t k = 0; k < n[2]; ++k)
            for (int64_t j = 0; j < n[1]; ++j)
                for (int64_t i = 0; i < n[0]; ++i) {
                    const int64_t at[3] = {i, j, k}, v0 = i + n[0] * (j + n[1] * k);
                    double sum = 0;
                    for (int d = -half; d <= half; ++d) {
                        const int64_t c = std::clamp<int64_t>(at[axis] + d, 0, n[axis] - 1);
                        sum += w[d + half] * a[v0 + (c - at[axis]) * step];
                    }
                    b[v0] = sum / total;
                }
        std::swap(a, b);
    }
    double worst = 0;
    for (int64_t i = 0; i < out.voxel_count(); ++i)
        worst = std::max(worst, std::fabs(out.as<float>()[i] - a[i]));
    EXPECT_LT(worst, 1e-3) << "largest difference from the written-out convolution";
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
