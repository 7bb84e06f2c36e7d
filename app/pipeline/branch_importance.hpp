// branch_importance.hpp - how important another simplifier finds the
// branches of a decomposition: the comparison study's priority lines show
// every simplifier's importance of the same branches (those of the first
// simplifier's decomposition).  The pipeline makes the plugin call, so a
// front never calls a plugin itself.
#pragma once

#include "document.hpp"
#include "plugin_catalog.hpp"

#include "core/volume.hpp"
#include "topology/branch_decomposition.hpp"

#include <vector>

namespace arbor::pipeline {

// The importance `simplifier` (a resolved setting) gives every branch of
// `d` but the root: element b - 1 is branch b's.  `mapping` is the volume's
// (stored -> physical values), which the plugin sees with the rows.  Throws
// PluginError or std::invalid_argument for importances that are not finite
// numbers >= 0.
std::vector<double> branch_importance(const PluginCatalog &catalog, const PluginSetting &simplifier,
                                      const topology::BranchDecomposition &d, const ValueMapping &mapping = {});

} // namespace arbor::pipeline
