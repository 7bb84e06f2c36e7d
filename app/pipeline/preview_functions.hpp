// preview_functions.hpp - a picture of a scan before its contour tree is
// known: one transfer function from the values alone, so the workstation
// shows the volume within a second of opening it and the topology's
// transfer functions replace it when the tree is done (as Slicer shows a
// default preset at once).  The background's values (core/background_level)
// stay transparent; on CT (HU) soft tissue is a faint veil and bone (from
// 300 HU) opaque ivory, as a bone preset shows it; on other scans the
// values above the background ramp up to their 99th percentile.
#pragma once

#include "stage_results.hpp"

#include <memory>

namespace arbor::pipeline {

std::unique_ptr<TransferFunctions> preview_functions(const FilterResult &filtered, uint32_t lut_size = 256);

} // namespace arbor::pipeline
