// branch_tree_record.hpp - the kept branches of a simplified decomposition as
// the SDK's arbor_branch_tree, the record depictors and transfer-function
// generators work on.  Branch k of the record is kept label k of the cut, so
// label maps index it directly.
#pragma once

#include "branch_tree_arrays.hpp"

#include "core/volume.hpp"
#include "topology/label_thickness.hpp"
#include "topology/simplification.hpp"

namespace arbor {

class BranchTreeRecord {
public:
    // `shapes`, when given: per kept label, the thickness and compactness of
    // the voxels it labels (columns ARBOR_MEASURE_THICKNESS, _COMPACTNESS).
    BranchTreeRecord(const topology::ContourTree &tree, const topology::BranchDecomposition &d,
                     const topology::SimplificationCut &cut, const Volume &volume,
                     const std::vector<topology::LabelShape> *shapes = nullptr);

    const arbor_branch_tree &record() const { return arrays_.record(); }
    uint32_t size() const { return record().branch_count; }

private:
    BranchTreeArrays arrays_;
};

} // namespace arbor
