#include "slice_geometry.hpp"

#include <cmath>

namespace arbor::workstation {

const char *orientation_name(SliceOrientation o)
{
    switch (o) {
    case SliceOrientation::Axial: return "axial";
    case SliceOrientation::Coronal: return "coronal";
    case SliceOrientation::Sagittal: return "sagittal";
    }
    return "?";
}

namespace {

// For LPS axis p: the voxel axis most nearly along it, and whether the
// voxel index grows towards +p.
struct AxisMatch {
    int axis;
    bool positive;
};

std::array<AxisMatch, 3> match_axes(const Geometry &g)
{
    // Greedy by the largest cosine, so that no voxel axis is used twice.
    std::array<AxisMatch, 3> out{};
    std::array<bool, 3> used_p{}, used_c{};
    for (int round = 0; round < 3; ++round) {
        int bp = -1, bc = -1;
        double best = -1;
        for (int p = 0; p < 3; ++p)
            for (int c = 0; c < 3; ++c)
                if (!used_p[p] && !used_c[c] && std::fabs(g.direction[3 * p + c]) > best) {
                    best = std::fabs(g.direction[3 * p + c]);
                    bp = p;
                    bc = c;
                }
        used_p[bp] = used_c[bc] = true;
        out[bp] = {bc, g.direction[3 * bp + bc] >= 0};
    }
    return out;
}

} // namespace

SliceGeometry slice_geometry(const Geometry &g, SliceOrientation o)
{
    const auto m = match_axes(g); // m[0]: L, m[1]: P, m[2]: S
    SliceGeometry s;
    // The patient axis along screen x and y, and whether screen x/y run
    // towards the patient axis' positive (L, P, S) direction.
    int px = 0, py = 1, pn = 2;
    bool x_positive = true, y_positive = true;
    switch (o) {
    case SliceOrientation::Axial: // x towards L, y (down) towards P
        px = 0, py = 1, pn = 2;
        s.left = 'R', s.right = 'L', s.top = 'A', s.bottom = 'P';
        break;
    case SliceOrientation::Coronal: // x towards L, y down towards I (-S)
        px = 0, py = 2, pn = 1, y_positive = false;
        s.left = 'R', s.right = 'L', s.top = 'S', s.bottom = 'I';
        break;
    case SliceOrientation::Sagittal: // x towards P, y down towards I
        px = 1, py = 2, pn = 0, y_positive = false;
        s.left = 'A', s.right = 'P', s.top = 'S', s.bottom = 'I';
        break;
    }
    s.x_axis = m[px].axis;
    s.y_axis = m[py].axis;
    s.normal = m[pn].axis;
    s.x_flip = m[px].positive != x_positive;
    s.y_flip = m[py].positive != y_positive;
    s.width = g.dims[s.x_axis];
    s.height = g.dims[s.y_axis];
    s.count = g.dims[s.normal];
    s.x_spacing = g.spacing[s.x_axis];
    s.y_spacing = g.spacing[s.y_axis];
    return s;
}

std::array<int64_t, 3> SliceGeometry::voxel(int64_t x, int64_t y, int64_t slice) const
{
    std::array<int64_t, 3> ijk{};
    ijk[x_axis] = x_flip ? width - 1 - x : x;
    ijk[y_axis] = y_flip ? height - 1 - y : y;
    ijk[normal] = slice;
    return ijk;
}

std::array<int64_t, 3> SliceGeometry::screen(const std::array<int64_t, 3> &ijk) const
{
    const int64_t x = ijk[x_axis], y = ijk[y_axis];
    return {x_flip ? width - 1 - x : x, y_flip ? height - 1 - y : y, ijk[normal]};
}

} // namespace arbor::workstation
