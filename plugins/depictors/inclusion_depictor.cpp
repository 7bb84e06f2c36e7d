// inclusion_depictor.cpp - org.arbor.depictor.inclusion (thesis §5.3.1): a
// branch is included by its proper ancestors; inclusion opacity grows with
// depth so inner structures stand out of the ones around them.  Depth is
// continuous inside a branch, depth + (f - f_saddle) / (f_extremum -
// f_saddle), so opacity does not jump where a child leaves its parent: a
// child's factor at its saddle is its parent's factor at that value.
#include "depictor_classes.hpp"

#include <algorithm>

namespace arbor::depictors {

const arbor_plugin_descriptor kInclusionDescriptor = {
    sizeof(arbor_plugin_descriptor),
    ARBOR_PLUGIN_FLAG_NONE,
    "org.arbor.depictor.inclusion",
    ARBOR_KIND_DEPICTOR,
    "Inclusion",
    "1.0.0",
    "Arbor",
    "Opacity that grows with the depth of inclusion, continuous across branch boundaries; with a selection, "
    "the selected branch's ancestors and descendants stay vivid and the rest fades.",
    "",
};

namespace {

class InclusionDepictor final : public sdk::Depictor {
public:
    explicit InclusionDepictor(const arbor_host *host)
        : Depictor(kInclusionDescriptor, host,
                   {sdk::ParamSpec::real("floor", "Opacity at the root", 0.15, 0.0, 1.0)
                        .hint("Inclusion opacity factor at the root's saddle; it rises linearly with continuous "
                              "depth to 1 at the deepest extremum"),
                    sdk::ParamSpec::real("unrelated-saturation", "Saturation of unrelated branches", 0.35, 0.0, 1.0)
                        .hint("With a selected branch: vividness factor of branches neither including nor "
                              "included by it")})
    {
    }

    void depict(const sdk::BranchTreeView &tree, int32_t selected, arbor_depiction &out, const sdk::Task &) override
    {
        uint32_t max_depth = 0;
        for (uint32_t b = 0; b < tree.size(); ++b)
            max_depth = std::max(max_depth, tree.depth(b));
        const double floor = params().number("floor");
        const auto factor = [&](double depth) {
            return static_cast<float>(floor + (1.0 - floor) * depth / (max_depth + 1.0));
        };
        for (uint32_t b = 0; b < tree.size(); ++b) {
            const double d = tree.depth(b);
            out.opacity_at_extremum[b] = factor(d + 1.0);
            if (b == 0) {
                out.opacity_at_saddle[b] = factor(0.0);
                continue;
            }
            // The parent's continuous depth at this branch's saddle value.
            const uint32_t p = static_cast<uint32_t>(tree.parent(b));
            const double span = tree.extremum_value(p) - tree.saddle_value(p);
            const double t = span != 0.0 ? std::clamp((tree.saddle_value(b) - tree.saddle_value(p)) / span, 0.0, 1.0)
                                         : 1.0;
            out.opacity_at_saddle[b] = factor(tree.depth(p) + t);
        }
        if (selected < 0)
            return;
        const uint32_t s = static_cast<uint32_t>(selected);
        const float faded = static_cast<float>(params().number("unrelated-saturation"));
        for (uint32_t b = 0; b < tree.size(); ++b) {
            if (b == s)
                out.role[b] = ARBOR_ROLE_SELECTED;
            else if (tree.parent(s) >= 0 && b == static_cast<uint32_t>(tree.parent(s)))
                out.role[b] = ARBOR_ROLE_PARENT;
            else if (tree.within(s, b))
                out.role[b] = ARBOR_ROLE_ANCESTOR;
            else if (tree.parent(b) >= 0 && static_cast<uint32_t>(tree.parent(b)) == s)
                out.role[b] = ARBOR_ROLE_CHILD;
            else if (tree.within(b, s))
                out.role[b] = ARBOR_ROLE_DESCENDANT;
            else
                out.saturation[b] = faded;
        }
    }

    // a is included by b: b is a proper ancestor of a.
    bool related(const sdk::BranchTreeView &tree, uint32_t a, uint32_t b) override
    {
        return a != b && tree.within(a, b);
    }
};

} // namespace

sdk::Instance *create_inclusion(const arbor_host *host)
{
    return new InclusionDepictor(host);
}

} // namespace arbor::depictors
