// branch_list.hpp - the kept branches as a table: its colour (a click
// opens a picker), whether it is shown (3D view and slice overlay), its
// opacity (a multiple of its optical depth), its share of the 3D view's
// visibility, the values it spans (HU on CT), its voxel count.  Edits are
// branch styles (pipeline/branch_style.hpp): they survive a new flow rate,
// shape or cut until "Reset edits".  A click on a row selects the branch in
// every view; the hovered row is highlighted everywhere.
#pragma once

namespace arbor::workstation {

class Workstation;

class BranchList {
public:
    void draw(Workstation &workstation);
};

} // namespace arbor::workstation
