// branch_decomposition.hpp - the branch decomposition of a contour tree,
// driven by an importance function, with the measures of every branch.
//
// A branch pairs an extremum with the saddle where it hangs off its parent;
// the root branch joins the global minimum and the global maximum.  Pairs are
// decided by the elder rule generalised from persistence to any importance,
// on the join tree (minima, upwards) and the split tree (maxima, downwards),
// both rebuilt from the contour tree: where two or more components of a
// sublevel (superlevel) set meet at a saddle, each component is a candidate
// branch - its representative extremum and the region its contour encloses at
// the saddle - and the most important one continues while the others end
// there.  With persistence this reproduces exactly the pairs TTK reports.
// Ties go to the older extremum (simulation of simplicity); the global minimum
// and maximum always continue.
//
// Each branch owns the contour-tree arcs of the path from its extremum to its
// saddle; where these paths overlap (only in trees that have no monotone
// branch decomposition realising the pairs, e.g. 1 x 1 x n strips) the more
// important branch keeps the shared arcs.  Parents own the arc just rootwards
// of their children.  Ownership drives label maps; pairs and measures do not
// depend on it.
//
// Measures describe the region enclosed by a branch's contour at its saddle,
// saddle included: everything beyond the saddle on the branch's side,
// children and their children included.  They are sums over the contour tree's
// augmentation (per-arc sums, then subtree sums), never a flood of the volume.
// The relative hypervolume is the volume between the function and the saddle
// level (see kRelativeHypervolume): the sum of |f - f(saddle)| over regions
// that lie on one side of their saddle level, with pits inside a peak (bumps
// inside a basin) counting against it.
#pragma once

#include "contour_tree.hpp"

#include "core/volume.hpp"

#include <array>
#include <cstdint>
#include <functional>
#include <ranges>
#include <string>
#include <vector>

namespace arbor::topology {

enum Measure : int {
    kPersistence,         // |f(extremum) - f(saddle)|
    kVolume,              // voxels in the region
    kVolumeMm3,           // the same in mm^3
    kHypervolume,         // sum over the region of f - f_min (global minimum)
    kRelativeHypervolume, // sum of f - f(saddle) (peak) or f(saddle) - f (basin), >= 0
    kMeasureCount
};

// Stable ids, the same as the SDK's ARBOR_MEASURE_* strings.
const char *measure_id(int measure);

enum class BranchKind : uint8_t { Root, Maximum, Minimum };

// A candidate branch as an importance function sees it: its measures and its
// extremum.  The root's row (the component of the sweep's global extremum,
// whose importance is ignored) has kind Root, the global minimum as its
// saddle value and the global maximum as its extremum value.
struct BranchMeasures {
    std::array<double, kMeasureCount> absolute{};
    std::array<double, kMeasureCount> relative{}; // absolute / the root's (0 when that is 0)
    BranchKind kind = BranchKind::Maximum;
    double saddle_value = 0.0, extremum_value = 0.0;
};

// Importance of candidate branches: fill out[i] for rows[i].  Larger is more
// important; must be finite and >= 0 (checked).  Each row's importance
// depends on that row alone.
using ImportanceFn = std::function<void(const std::vector<BranchMeasures> &rows, std::vector<double> &out)>;

// The default: relative persistence.
ImportanceFn persistence_importance();

struct Branch {
    BranchKind kind = BranchKind::Root;
    uint32_t extremum_node = 0; // node index in the contour tree
    uint32_t saddle_node = 0;   // the global minimum for the root
    int32_t parent = -1;
    uint32_t depth = 0;
    double importance = 0.0; // +infinity for the root
    std::array<double, kMeasureCount> measures{}; // absolute; relative ones: BranchDecomposition::relative
    double saddle_value = 0.0, extremum_value = 0.0; // the function there (the root: global min and max)
};

struct BranchDecomposition {
    // Root first, then breadth first: every parent before its children, and
    // the children of a branch consecutive.
    HugeVector<Branch> branches;
    // The children of branch b are branches child_offsets[b] ..
    // child_offsets[b + 1] - 1.
    HugeVector<uint32_t> child_offsets;
    // Branch of every contour-tree arc and node (a saddle belongs to the
    // branch that continues through it, an extremum to its own branch).
    HugeVector<uint32_t> arc_branch;
    HugeVector<uint32_t> node_branch;
    double global_min = 0.0, global_max = 0.0;

    auto children(uint32_t b) const { return std::views::iota(child_offsets[b], child_offsets[b + 1]); }
    // A measure of branch b relative to the root's (0 when the root's is 0).
    double relative(uint32_t b, int measure) const
    {
        const double root = branches[0].measures[measure];
        return root > 0 ? branches[b].measures[measure] / root : 0.0;
    }
};

// The value of every vertex as a double, and the grid's geometry.
struct FieldView {
    arbor_voxel_type type;
    const void *values;
    uint32_t count;
    const Geometry *geometry;

    double value(uint32_t vertex) const;
};

BranchDecomposition decompose_branches(const ContourTree &tree, const FieldView &field,
                                       const ImportanceFn &importance,
                                       const ProgressFn &progress = {});

} // namespace arbor::topology
