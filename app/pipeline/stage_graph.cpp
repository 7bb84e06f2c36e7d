#include "stage_graph.hpp"

namespace arbor::pipeline {

namespace {

struct StageInfo {
    const char *name;
    std::array<Stage, 3> upstream;
    std::size_t upstream_count;
    uint32_t own_groups;
};

constexpr uint32_t bit(Group g)
{
    return 1u << index_of(g);
}

constexpr std::array<StageInfo, kStageCount> kStages{{
    {"import", {}, 0, bit(Group::Input)},
    {"filter", {Stage::Import}, 1, bit(Group::Filters)},
    {"contour_tree", {Stage::Filter}, 1, 0},
    {"decomposition", {Stage::ContourTree, Stage::Filter}, 2, bit(Group::Simplifier)},
    {"cut", {Stage::Decomposition, Stage::ContourTree, Stage::Filter}, 3, bit(Group::Cut)},
    {"labels", {Stage::Cut}, 1, 0}, // the cut's label map, named: the tree is not read again
    {"depiction", {Stage::Cut}, 1, bit(Group::Appearance)},
    {"transfer_functions", {Stage::Depiction, Stage::Filter}, 2, bit(Group::Appearance)},
    {"render", {Stage::TransferFunctions, Stage::Labels, Stage::Filter}, 3, bit(Group::View)},
    {"legend", {Stage::Cut}, 1, bit(Group::Appearance)},
}};

constexpr uint32_t transitive_groups(Stage s)
{
    const StageInfo &info = kStages[index_of(s)];
    uint32_t g = info.own_groups;
    for (std::size_t i = 0; i < info.upstream_count; ++i)
        g |= transitive_groups(info.upstream[i]);
    return g;
}

constexpr const char *kGroupNames[kGroupCount] = {"input", "filters", "simplifier", "cut", "appearance", "view"};

} // namespace

const char *stage_name(Stage stage)
{
    return kStages[index_of(stage)].name;
}

const char *group_name(Group group)
{
    return kGroupNames[index_of(group)];
}

std::span<const Stage> upstream_of(Stage stage)
{
    const StageInfo &info = kStages[index_of(stage)];
    return {info.upstream.data(), info.upstream_count};
}

uint32_t groups_of(Stage stage)
{
    return transitive_groups(stage);
}

StageKey key_of(Stage stage, const std::array<uint64_t, kGroupCount> &revisions)
{
    const uint32_t groups = groups_of(stage);
    StageKey key{};
    for (std::size_t g = 0; g < kGroupCount; ++g)
        if (groups & (1u << g))
            key[g] = revisions[g];
    return key;
}

} // namespace arbor::pipeline
