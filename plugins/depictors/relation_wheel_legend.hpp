// relation_wheel_legend.hpp - the neighbourhood of a selected branch and the
// relation wheel drawn as a legend image, branch ids at their hues.
#pragma once

#include "relation_wheel.hpp"

#include <arbor/image.h>
#include <arbor/sdk/branch_tree.hpp>

#include <cstdint>
#include <vector>

namespace arbor::depictors {

struct Neighbourhood {
    uint32_t selected = 0;
    int32_t parent = -1;
    std::vector<uint32_t> children, siblings;
};

Neighbourhood neighbourhood(const sdk::BranchTreeView &tree, uint32_t selected);

// Draws the wheel into the whole image (opaque, display sRGB).
void draw_relation_wheel(const Neighbourhood &n, const RelationWheel &wheel, arbor_image &image);

} // namespace arbor::depictors
