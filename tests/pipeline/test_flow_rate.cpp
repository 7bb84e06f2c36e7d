// The flow rate Q as the balanced picture's own axis (flow_peel.hpp): the
// peel's known answers on a small tree, and on the phantom through the real
// pipeline that moving Q from its default peels the outer layers away and
// brings the inner ones forward, with the balance the one taken at the
// default.
#include "pipeline/flow_peel.hpp"
#include "pipeline/pipeline.hpp"

#include "plugin_fixture.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numeric>

namespace arbor::pipeline {
namespace {

// root 0 -> 1 -> 2 (leaf), root -> 3 (leaf): heights 2, 1, 0, 0.
struct SmallTree {
    int32_t parent[4] = {-1, 0, 1, 0};
    uint32_t depth[4] = {0, 1, 2, 1};
    arbor_branch_tree record{};
    SmallTree()
    {
        record.struct_size = sizeof record;
        record.branch_count = 4;
        record.parent = parent;
        record.depth = depth;
    }
};

TEST(FlowPeel, TheRootThinsInProportionToQAndLeavesKeepTheirDepth)
{
    const SmallTree t;
    const std::vector<double> at4 = flow_peel(t.record, 4.0);
    ASSERT_EQ(at4.size(), 4u);
    EXPECT_DOUBLE_EQ(at4[0], 0.25);
    EXPECT_DOUBLE_EQ(at4[1], 0.5); // half the root's height: (1/4)^(1/2)
    EXPECT_DOUBLE_EQ(at4[2], 1.0);
    EXPECT_DOUBLE_EQ(at4[3], 1.0);
    const std::vector<double> at_quarter = flow_peel(t.record, 0.25);
    EXPECT_DOUBLE_EQ(at_quarter[0], 4.0);
    EXPECT_DOUBLE_EQ(at_quarter[1], 2.0);
    for (const double q : {1.0, 0.0, -3.0, std::nan("")})
        EXPECT_EQ(flow_peel(t.record, q), std::vector<double>(4, 1.0)) << q;
    EXPECT_EQ(peeled_scale({2.0, 3.0, 4.0, 5.0}, at4), (std::vector<double>{0.5, 1.5, 4.0, 5.0}));
    EXPECT_EQ(peeled_scale({2.0, 3.0}, {}), (std::vector<double>{2.0, 3.0}));
}

TEST(FlowPeel, EveryBranchsDepthIsMonotonicInQ)
{
    const SmallTree t;
    std::vector<double> last(4, INFINITY);
    for (const double q : {0.1, 0.5, 1.0, 2.0, 10.0}) {
        const std::vector<double> p = flow_peel(t.record, q);
        for (std::size_t b = 0; b < 4; ++b)
            EXPECT_LE(p[b], last[b]) << "branch " << b << " at Q/Q0 " << q;
        last = p;
    }
}

double share(const std::vector<double> &v, std::size_t b)
{
    const double total = std::accumulate(v.begin(), v.end(), 0.0);
    return total > 0 ? v[b] / total : 0.0;
}

TEST(FlowRate, PeelsThePhantomsLayersAndKeepsTheBalanceTakenAtTheDefault)
{
    Pipeline p(test::built_plugins());
    Document d = default_document();
    d.input.phantom = PhantomInput{};
    d.input.phantom->size = 64;
    d.view.width = d.view.height = 96;
    d.appearance.generator.params.erase("flow-rate"); // the default Q0
    p.set_document(d);
    const auto at_default = p.run<Stage::Render>();
    ASSERT_TRUE(at_default->balance);
    EXPECT_TRUE(at_default->peel.empty());
    const std::size_t n = at_default->image.label_visibility.size();
    ASSERT_GE(n, 3u);
    const auto cut = p.latest<Stage::Cut>();
    const arbor_branch_tree &tree = cut->tree->record();
    std::vector<bool> leaf(n, true);
    for (std::size_t b = 1; b < n; ++b)
        leaf[static_cast<std::size_t>(tree.parent[b])] = false;
    const auto leaves = [&](const std::vector<double> &v) {
        double s = 0;
        for (std::size_t b = 0; b < n; ++b)
            s += leaf[b] ? share(v, b) : 0.0;
        return s;
    };

    const double root_default = share(at_default->image.label_visibility, 0);
    double root_before = 2.0, leaves_low = 0, leaves_high = 0, root_low = 0, root_high = 1;
    for (const char *q : {"10", "30", "60", "150", "300", "1000"}) {
        d.appearance.generator.params["flow-rate"] = q;
        p.set_document(d);
        const auto r = p.run<Stage::Render>();
        ASSERT_TRUE(r->balance) << q;
        // The balance of the default, not one of this Q.
        EXPECT_EQ(r->balance->scale, at_default->balance->scale) << q;
        EXPECT_EQ(r->balance->iterations, at_default->balance->iterations) << q;
        if (std::string(q) == "60") {
            EXPECT_TRUE(r->peel.empty());
            EXPECT_EQ(r->image.rgba, at_default->image.rgba) << "Q given as its default is the default";
        }
        const double root = share(r->image.label_visibility, 0);
        EXPECT_TRUE(root < root_before || root == 0.0) << "the root's share falls as Q rises: Q " << q << ", " << root;
        root_before = root;
        if (std::string(q) == "10")
            root_low = root, leaves_low = leaves(r->image.label_visibility);
        if (std::string(q) == "1000")
            root_high = root, leaves_high = leaves(r->image.label_visibility);
    }
    // The phantom's root: 16 % of the picture at the default, 38 % at Q 10,
    // none at Q 1000 (the shared scans' bounds are test_cli.py's).
    EXPECT_GT(root_low, 2 * root_default);
    EXPECT_LT(root_high, 0.1);
    EXPECT_GT(leaves_high, leaves_low + 0.1) << "the innermost structures come forward";
}

} // namespace
} // namespace arbor::pipeline
