// neighbour_depictor.cpp - org.arbor.depictor.neighbour (thesis §5.3.2): the
// neighbours of a selected branch - its parent, children and siblings - get
// hues on the X-type relation wheel (relation_wheel.hpp), everything else is
// drawn faint and desaturated.  The wheel itself, with branch ids on it, is
// the legend.
#include "depictor_classes.hpp"
#include "relation_wheel_legend.hpp"

namespace arbor::depictors {

const arbor_plugin_descriptor kNeighbourDescriptor = {
    sizeof(arbor_plugin_descriptor),
    ARBOR_PLUGIN_FLAG_NONE,
    "org.arbor.depictor.neighbour",
    ARBOR_KIND_DEPICTOR,
    "Neighbouring",
    "1.0.0",
    "Arbor",
    "Colours the parent, children and siblings of the selected branch from an X-type relation wheel (children "
    "and siblings in opposite 93.6-degree sectors) and fades the rest; draws the wheel as a legend.",
    "",
};

namespace {

class NeighbourDepictor final : public sdk::Depictor {
public:
    explicit NeighbourDepictor(const arbor_host *host)
        : Depictor(kNeighbourDescriptor, host,
                   {sdk::ParamSpec::real("rotation", "Wheel rotation", 0.0, 0.0, 360.0)
                        .unit("degrees")
                        .hint("Hue at the centre of the children's sector"),
                    sdk::ParamSpec::real("faint-opacity", "Opacity of non-neighbours", 0.2, 0.0, 1.0)
                        .hint("Opacity factor of branches that are not neighbours of the selected one"),
                    sdk::ParamSpec::real("faint-saturation", "Saturation of non-neighbours", 0.15, 0.0, 1.0)
                        .hint("Vividness factor of branches that are not neighbours of the selected one")})
    {
    }

    void depict(const sdk::BranchTreeView &tree, int32_t selected, arbor_depiction &out, const sdk::Task &) override
    {
        if (selected < 0)
            return; // nothing selected: no neighbourhood to show
        const Neighbourhood n = neighbourhood(tree, static_cast<uint32_t>(selected));
        const RelationWheel wheel{params().number("rotation")};
        const float faint_opacity = static_cast<float>(params().number("faint-opacity"));
        const float faint_saturation = static_cast<float>(params().number("faint-saturation"));
        for (uint32_t b = 0; b < tree.size(); ++b) {
            out.opacity_at_saddle[b] = out.opacity_at_extremum[b] = faint_opacity;
            out.saturation[b] = faint_saturation;
        }
        const auto show = [&](uint32_t b, arbor_branch_role role, double hue) {
            out.role[b] = role;
            out.hue[b] = static_cast<float>(hue);
            out.opacity_at_saddle[b] = out.opacity_at_extremum[b] = 1.0f;
            out.saturation[b] = 1.0f;
        };
        show(n.selected, ARBOR_ROLE_SELECTED, wheel.selected_hue());
        if (n.parent >= 0)
            show(static_cast<uint32_t>(n.parent), ARBOR_ROLE_PARENT, wheel.parent_hue());
        for (std::size_t k = 0; k < n.children.size(); ++k)
            show(n.children[k], ARBOR_ROLE_CHILD, wheel.child_hue(k, n.children.size()));
        for (std::size_t k = 0; k < n.siblings.size(); ++k)
            show(n.siblings[k], ARBOR_ROLE_SIBLING, wheel.sibling_hue(k, n.siblings.size()));
    }

    // a is b's parent, child or sibling.
    bool related(const sdk::BranchTreeView &tree, uint32_t a, uint32_t b) override
    {
        if (a == b)
            return false;
        return tree.parent(b) == static_cast<int32_t>(a) || tree.parent(a) == static_cast<int32_t>(b) ||
               (tree.parent(a) >= 0 && tree.parent(a) == tree.parent(b));
    }

    void legend(const sdk::BranchTreeView &tree, int32_t selected, arbor_image &image, const sdk::Task &) override
    {
        if (selected < 0)
            sdk::fail(ARBOR_ERROR_INVALID_ARGUMENT, "the relation wheel needs a selected branch");
        draw_relation_wheel(neighbourhood(tree, static_cast<uint32_t>(selected)),
                            RelationWheel{params().number("rotation")}, image);
    }
};

} // namespace

sdk::Instance *create_neighbour(const arbor_host *host)
{
    return new NeighbourDepictor(host);
}

} // namespace arbor::depictors
