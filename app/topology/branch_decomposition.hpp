// branch_decomposition.hpp - the branch decomposition of a contour tree,
// driven by an importance function, with the measures of every branch.
//
// A branch is a monotone path from an extremum to the saddle where it hangs
// off its parent; the root branch joins the global minimum and the global
// maximum.  The decomposition is decided saddle by saddle, upwards for the
// arcs below saddles and downwards for the arcs above them: at a saddle where
// several arcs meet on one side, the candidate branch on each of those arcs
// (the extremum its continuing path reaches, and the region enclosed by its
// contour at the saddle) is given its importance, the most important one
// continues through the saddle, and every other one ends there and becomes a
// child of the continuing branch.  This is the elder rule generalised from
// persistence to any importance: with persistence it reproduces exactly the
// pairs of the join and split trees (what TTK reports), and it is what
// leaf pruning in order of importance produces whenever no leaf is blocked
// behind a saddle of the other kind.  Ties go to the older extremum
// (simulation of simplicity), the global minimum and maximum always continue.
//
// Measures describe the region enclosed by a branch's contour at its saddle,
// saddle included: everything beyond the saddle on the branch's side,
// children and their children included.  They are sums over the contour tree's
// augmentation (per-arc sums, then subtree sums), never a flood of the volume.
#pragma once

#include "contour_tree.hpp"

#include "core/volume.hpp"

#include <array>
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

namespace arbor::topology {

enum Measure : int {
    kPersistence,         // |f(extremum) - f(saddle)|
    kVolume,              // voxels in the region
    kVolumeMm3,           // the same in mm^3
    kHypervolume,         // sum over the region of f - f_min (global minimum)
    kRelativeHypervolume, // sum over the region of |f - f(saddle)|
    kMeasureCount
};

// Stable ids, the same as the SDK's ARBOR_MEASURE_* strings.
const char *measure_id(int measure);

struct BranchMeasures {
    std::array<double, kMeasureCount> absolute{};
    std::array<double, kMeasureCount> relative{}; // absolute / the root's (0 when that is 0)
};

// Importance of candidate branches: fill out[i] for rows[i].  Larger is more
// important; must be finite and >= 0 (checked).
using ImportanceFn = std::function<void(const std::vector<BranchMeasures> &rows, std::vector<double> &out)>;

// The default: relative persistence.
ImportanceFn persistence_importance();

enum class BranchKind : uint8_t { Root, Maximum, Minimum };

struct Branch {
    BranchKind kind = BranchKind::Root;
    uint32_t extremum_node = 0; // node index in the contour tree
    uint32_t saddle_node = 0;   // the global minimum for the root
    int32_t parent = -1;
    uint32_t depth = 0;
    std::vector<uint32_t> children;
    BranchMeasures measures;
    double importance = 0.0; // +infinity for the root
};

struct BranchDecomposition {
    // Root first; every parent before its children.
    std::vector<Branch> branches;
    // Branch of every contour-tree arc and node (a saddle belongs to the
    // branch that continues through it, an extremum to its own branch).
    std::vector<uint32_t> arc_branch;
    std::vector<uint32_t> node_branch;
    double global_min = 0.0, global_max = 0.0;
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
