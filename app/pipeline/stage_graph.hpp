// stage_graph.hpp - the stages of the pipeline, the groups of choices, and
// what depends on what.
//
//   import -> filter -> contour tree -> decomposition -> cut -> labels ---------> render
//                                                          \-> depiction -> transfer functions /
//                                                          \-> legend
//
// A stage reads the results of its upstream stages and the choice groups it
// owns; it is stale when the revision of any group it depends on, directly
// or through its upstream stages, changed since its result was computed:
//   input       -> import and everything after it
//   filters     -> filter, contour tree and what follows (never the import)
//   simplifier  -> decomposition and what follows (never the tree)
//   cut         -> cut, labels and what follows (never the decomposition)
//   appearance  -> depiction, transfer functions, legend, render
//   view        -> render only
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <span>

namespace arbor::pipeline {

enum class Stage : uint8_t {
    Import,
    Filter,
    ContourTree,
    Decomposition,
    Cut,
    Labels,
    Depiction,
    TransferFunctions,
    Render,
    Legend,
};
inline constexpr std::size_t kStageCount = 10;

enum class Group : uint8_t { Input, Filters, Simplifier, Cut, Appearance, View };
inline constexpr std::size_t kGroupCount = 6;

// "import", "filter", "contour_tree", ... (report keys).
const char *stage_name(Stage stage);
const char *group_name(Group group);

std::span<const Stage> upstream_of(Stage stage);
// Bit g set: the stage depends on group g, itself or through its upstream.
uint32_t groups_of(Stage stage);

// The revisions of the groups a result was computed from; groups the stage
// does not depend on are zero, so two keys of one stage compare equal exactly
// when the stage's inputs are the same.
using StageKey = std::array<uint64_t, kGroupCount>;
StageKey key_of(Stage stage, const std::array<uint64_t, kGroupCount> &revisions);

constexpr std::size_t index_of(Stage s) { return static_cast<std::size_t>(s); }
constexpr std::size_t index_of(Group g) { return static_cast<std::size_t>(g); }

} // namespace arbor::pipeline
