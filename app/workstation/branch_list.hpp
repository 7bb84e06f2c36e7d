// branch_list.hpp - the kept branches as a table: colour swatch, whether
// the slice overlay shows it, its share of the 3D view's visibility, the
// values it spans (HU on CT), its voxel count; a click selects it in every
// view, the hovered row is highlighted everywhere.
#pragma once

namespace arbor::workstation {

class Workstation;

class BranchList {
public:
    void draw(Workstation &workstation);
};

} // namespace arbor::workstation
