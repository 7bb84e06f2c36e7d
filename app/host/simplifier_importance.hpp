// simplifier_importance.hpp - a simplifier plugin as the importance function
// of the host's one pruning engine (topology/branch_decomposition.hpp).
//
// The host hands the plugin every candidate branch's measures, absolute and
// relative to the root, in the columns of the SDK (ARBOR_MEASURE_*), and
// refuses importances that are not finite numbers >= 0 with a message naming
// the plugin and the branch.
#pragma once

#include "plugin_instance.hpp"

#include "topology/branch_decomposition.hpp"

namespace arbor {

// Calls the plugin's prepare with the host's measure columns (throws
// PluginError naming the plugin when it refuses them) and returns the
// function that ranks candidates through it.  The instance must outlive the
// function.
topology::ImportanceFn simplifier_importance(PluginInstance &simplifier);

} // namespace arbor
