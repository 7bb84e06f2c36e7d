// relation_wheel_view.hpp - the relation-wheel legend of the selected
// branch (or the deepest one), as the legend stage draws it; it follows the
// selection live.
#pragma once

#include "gl_texture.hpp"

namespace arbor::workstation {

class Workstation;

class RelationWheelView {
public:
    void draw(Workstation &workstation);

private:
    GlTexture texture_;
    const void *shown_ = nullptr;
};

} // namespace arbor::workstation
