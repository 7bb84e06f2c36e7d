// tree_view.hpp - the simplified branch decomposition drawn as a tree by
// value (the thesis' tree window): each kept branch a vertical line from
// its saddle's value to its extremum's, joined to its parent at the saddle,
// in the branch's colour.  Hover shows the branch's measures and
// importance; a click selects it in every view.
#pragma once

namespace arbor::workstation {

class Workstation;

class TreeView {
public:
    void draw(Workstation &workstation);
};

} // namespace arbor::workstation
