// branch_style.hpp - a person's edits of single structures (document.hpp's
// BranchStyle) applied to the transfer functions a renderer gets: hidden
// branches fully transparent, opacity as a multiple of the optical depth
// (as the visibility balance scales it), colour replaced with the opacity
// kept.  Branches are matched by their extremum vertex, so an edit follows
// its structure through a new cut, and one whose branch is not kept now
// waits until it is again.
#pragma once

#include "document.hpp"

#include "host/tf_generation.hpp"

#include <arbor/branch_tree.h>

#include <map>
#include <memory>

namespace arbor::pipeline {

// `functions` unchanged (shared) when no style applies to a kept branch.
std::shared_ptr<const TransferFunctions> styled(std::shared_ptr<const TransferFunctions> functions,
                                                const arbor_branch_tree &tree,
                                                const std::map<int64_t, BranchStyle> &styles);

} // namespace arbor::pipeline
