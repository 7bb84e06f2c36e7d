// simplifier_importance.hpp - a simplifier plugin as the importance function
// of the host's one decomposition engine (topology/branch_decomposition.hpp).
//
// The host hands the plugin every candidate branch's measures, absolute and
// relative to the root, in the columns of the SDK (ARBOR_MEASURE_*), with
// each row's extremum kind, saddle and extremum values, the root's row and
// the volume's value mapping (ABI 1.4), and refuses importances that are not
// finite numbers >= 0 with a message naming the plugin and the branch.
#pragma once

#include "plugin_instance.hpp"

#include "core/volume.hpp"
#include "topology/branch_decomposition.hpp"

namespace arbor {

// Calls the plugin's prepare with the host's measure columns (throws
// PluginError naming the plugin when it refuses them) and returns the
// function that ranks candidates through it.  The instance must outlive the
// function; `mapping` is the volume's (stored -> physical values; the
// identity for tests on bare fields).
topology::ImportanceFn simplifier_importance(PluginInstance &simplifier, const ValueMapping &mapping = {});

} // namespace arbor
