// topology_json.hpp - the JSON pieces the topology outputs share (tree,
// simplification, comparison reports): points of the contour tree (vertex,
// ijk, LPS mm, value), measure objects, branch kinds and the volume and
// contour-tree summaries, written as members of the object the caller has
// open.
#pragma once

#include "json_writer.hpp"

#include "core/volume.hpp"
#include "topology/branch_decomposition.hpp"
#include "topology/simplification.hpp"

#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace arbor::io {

// Voxel indices (i, j, k) of vertex v.
std::array<int64_t, 3> voxel_ijk(const Geometry &g, uint32_t v);

// "vertex", "ijk", "position_mm", "value" of vertex v.
void write_vertex_fields(JsonWriter &j, const Volume &vol, uint32_t v);
// key: {"node", "vertex", "ijk", "position_mm", "value"} of a contour-tree node.
void write_tree_point(JsonWriter &j, std::string_view key, const topology::ContourTree &t, const Volume &vol,
                      uint32_t node);
// "extremum", "saddle", "measures", "relative_measures" of a branch.
void write_branch_ends_and_measures(JsonWriter &j, const topology::ContourTree &t, const Volume &vol,
                                    const topology::BranchDecomposition &d, uint32_t branch);

// key: {"persistence": ..., "volume": ...} keyed by the SDK's measure ids.
void write_measures(JsonWriter &j, std::string_view key, const std::array<double, topology::kMeasureCount> &m);
void write_relative_measures(JsonWriter &j, std::string_view key, const topology::BranchDecomposition &d,
                             uint32_t branch);

const char *branch_kind_name(topology::BranchKind k);

// "contour_tree": {"nodes", "arcs", "seconds"}, plus "branches" when given.
void write_contour_tree_summary(JsonWriter &j, const topology::ContourTree &tree, double seconds,
                                std::optional<std::size_t> branches = {});

// Depth of every kept branch in the simplified hierarchy (root 0).
std::vector<uint32_t> kept_depths(const topology::SimplificationCut &cut);

// key: an array with one object per kept branch: label, branch, parent
// label, kind, depth, importance, extremum and saddle points, measures
// absolute and relative.
void write_kept_branches(JsonWriter &j, std::string_view key, const topology::ContourTree &tree, const Volume &volume,
                         const topology::BranchDecomposition &d, const topology::SimplificationCut &cut);

// "volume": {"source", "dims", "spacing_mm"}.
void write_volume_summary(JsonWriter &j, const std::string &source, const Geometry &g);

} // namespace arbor::io
