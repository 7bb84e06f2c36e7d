// topology_json.hpp - the JSON pieces the topology outputs share (tree,
// simplification, comparison reports): points of the contour tree (vertex,
// ijk, LPS mm, value), measure objects, branch kinds and the volume and
// contour-tree summaries, written through a JsonStream.
#pragma once

#include "json_stream.hpp"

#include "core/volume.hpp"
#include "topology/branch_decomposition.hpp"

#include <array>
#include <cstdint>
#include <optional>
#include <string>

namespace arbor::io {

// Voxel indices (i, j, k) of vertex v.
std::array<double, 3> voxel_ijk(const Geometry &g, uint32_t v);

// {"node", "vertex", "ijk", "position_mm", "value"} of a contour-tree node.
void write_tree_point(JsonStream &j, const topology::ContourTree &t, const Volume &vol, uint32_t node);
// "vertex", "ijk", "position_mm", "value" of vertex v: fields, no braces.
void write_vertex_fields(JsonStream &j, const Volume &vol, uint32_t v);
// "extremum", "saddle", "measures", "relative_measures" of a branch: fields,
// no braces.
void write_branch_ends_and_measures(JsonStream &j, const topology::ContourTree &t, const Volume &vol,
                                    const topology::BranchDecomposition &d, uint32_t branch);

// {"persistence": ..., "volume": ...} keyed by the SDK's measure ids.
void write_measures(JsonStream &j, const std::array<double, topology::kMeasureCount> &m);
void write_relative_measures(JsonStream &j, const topology::BranchDecomposition &d, uint32_t branch);

const char *branch_kind_name(topology::BranchKind k);

// "contour_tree": {"nodes", "arcs", "seconds"}, plus "branches" when given.
void write_contour_tree_summary(JsonStream &j, const topology::ContourTree &tree, double seconds,
                                std::optional<std::size_t> branches = {});

// "volume": {"source", "dims", "spacing_mm"}.
void write_volume_summary(JsonStream &j, const std::string &source, const Geometry &g);

} // namespace arbor::io
