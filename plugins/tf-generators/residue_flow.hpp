// residue_flow.hpp - opacity ranges by the residue-flow model (thesis
// §6.3-6.4, ALGORITHMS.md §5): opacity "flows" from the root down the branch
// tree like water through sand.  Each branch absorbs part of what reaches
// it and passes the residue on to its children; the Darcy head loss decides
// the split, so the flow rate Q (the one slider) peels outer structures away
// to reveal inner ones.
#pragma once

#include <arbor/sdk/branch_tree.hpp>

#include <vector>

namespace arbor::tf {

struct FlowParameters {
    double flow_rate = 60.0;      // Q, in [0, conductivity]
    double conductivity = 300.0;  // K (water in sand)
    double alpha_min = 0.0;       // opacity below every band
    double alpha_range = 0.9;     // α_r: what all bands on a root-to-leaf path share
    double sibling_floor = 0.25;  // ε of the saddle-value factor among siblings
};

struct OpacityRange {
    double low = 0.0, high = 0.0; // the branch's opacities lie in [low, high]
    double absorbed = 0.0;        // α_b before the sibling factors: what the branch keeps of its inflow
    double head_loss = 0.0;       // Δh_b
};

// One range per branch of the tree (parents first).  Needs the persistence,
// volume and hypervolume columns (relative) for the sibling factor.
std::vector<OpacityRange> residue_flow(const sdk::BranchTreeView &tree, const FlowParameters &p);

} // namespace arbor::tf
