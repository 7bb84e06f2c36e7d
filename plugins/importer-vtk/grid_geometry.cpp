// grid_geometry.cpp - decomposing an index-to-LPS affine map into spacing,
// direction cosines and origin.
#include "grid_geometry.hpp"

#include <cmath>

namespace arbor::importer_vtk {

void GridGeometry::write_to(arbor_volume &out) const
{
    for (int a = 0; a < 3; ++a) {
        out.spacing[a] = spacing[a];
        out.origin[a] = origin[a];
    }
    for (int e = 0; e < 9; ++e)
        out.direction[e] = direction[e];
}

GridGeometry geometry_from_affine(const std::array<double, 9> &matrix,
                                  const std::array<double, 3> &translation)
{
    GridGeometry g;
    g.origin = translation;
    // Sign flips of zero entries (RAS -> LPS) would show as "-0" in listings.
    const auto tidy = [](double v) { return v == 0.0 ? 0.0 : v; };
    for (double &v : g.origin)
        v = tidy(v);
    for (int c = 0; c < 3; ++c) {
        const double x = matrix[c], y = matrix[3 + c], z = matrix[6 + c];
        const double length = std::sqrt(x * x + y * y + z * z);
        g.spacing[c] = length;
        if (length > 0.0) {
            g.direction[c] = tidy(x / length);
            g.direction[3 + c] = tidy(y / length);
            g.direction[6 + c] = tidy(z / length);
        }
    }
    return g;
}

} // namespace arbor::importer_vtk
