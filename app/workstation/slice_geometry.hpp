// slice_geometry.hpp - the three slice views in patient orientation, as
// radiologists read them (3D Slicer, Horos): axial seen from the feet
// (patient's right on the screen's left, anterior up), coronal from the
// front (right on the left, superior up), sagittal from the patient's left
// (anterior on the left, superior up).  A volume's axes are matched to the
// patient axes by its direction cosines (the closest axis; an oblique scan
// is shown along its nearest patient planes, as Slicer's reformat does
// without interpolation).
#pragma once

#include "core/volume.hpp"

#include <array>
#include <cstdint>

namespace arbor::workstation {

enum class SliceOrientation { Axial, Coronal, Sagittal };
const char *orientation_name(SliceOrientation o); // "axial", ...

struct SliceGeometry {
    int normal = 2;                 // the voxel axis across slices
    int x_axis = 0, y_axis = 1;     // voxel axes along the screen's x (right) and y (down)
    bool x_flip = false, y_flip = false; // the index decreases along the screen axis
    int64_t width = 0, height = 0, count = 0; // screen pixels (one per voxel), slices
    double x_spacing = 1, y_spacing = 1; // mm per screen pixel
    // Screen-edge labels: the patient direction at the left, right, top and bottom.
    char left = 'R', right = 'L', top = 'A', bottom = 'P';

    // The voxel shown at screen pixel (x, y) of slice `slice`.
    std::array<int64_t, 3> voxel(int64_t x, int64_t y, int64_t slice) const;
    // Where voxel `ijk` appears: screen x, y and its slice.
    std::array<int64_t, 3> screen(const std::array<int64_t, 3> &ijk) const;
};

SliceGeometry slice_geometry(const Geometry &geometry, SliceOrientation orientation);

} // namespace arbor::workstation
