#include "label_thickness.hpp"

#include "core/parallel_ranges.hpp"

#include <cmath>

namespace arbor::topology {

std::vector<LabelShape> label_shapes(std::span<const uint32_t> labels, const std::array<int64_t, 3> &dims,
                                     const std::array<double, 3> &spacing, uint32_t label_count)
{
    const int64_t nx = dims[0], ny = dims[1], nz = dims[2];
    const double voxel = spacing[0] * spacing[1] * spacing[2];
    const double face[3] = {spacing[1] * spacing[2], spacing[0] * spacing[2], spacing[0] * spacing[1]};
    // Counted in whole voxels and faces, a range of slices per core, so the
    // result does not depend on how the slices were shared out.
    struct Counts {
        std::vector<uint64_t> voxels, faces[3], border[3];
    };
    constexpr std::size_t kSlabSlices = 8;
    std::vector<Counts> parts(range_parts(static_cast<std::size_t>(nz), kSlabSlices));
    for_ranges(static_cast<std::size_t>(nz), kSlabSlices, [&](std::size_t k0, std::size_t k1, std::size_t part) {
        Counts &c = parts[part];
        c.voxels.assign(label_count, 0);
        for (auto &f : c.faces)
            f.assign(label_count, 0);
        for (auto &f : c.border)
            f.assign(label_count, 0);
        for (int64_t k = static_cast<int64_t>(k0); k < static_cast<int64_t>(k1); ++k)
            for (int64_t j = 0; j < ny; ++j)
                for (int64_t i = 0; i < nx; ++i) {
                    const std::size_t v = static_cast<std::size_t>(i + nx * (j + ny * k));
                    const uint32_t l = labels[v];
                    ++c.voxels[l];
                    // Each face between two labels, once, for both sides.
                    const auto boundary = [&](std::size_t u, int axis) {
                        if (labels[u] != l) {
                            ++c.faces[axis][l];
                            ++c.faces[axis][labels[u]];
                        }
                    };
                    // Faces on the grid's own border: where the scan was cut.
                    c.border[0][l] += (i == 0) + (i == nx - 1);
                    c.border[1][l] += (j == 0) + (j == ny - 1);
                    c.border[2][l] += (k == 0) + (k == nz - 1);
                    if (i + 1 < nx)
                        boundary(v + 1, 0);
                    if (j + 1 < ny)
                        boundary(v + static_cast<std::size_t>(nx), 1);
                    if (k + 1 < nz)
                        boundary(v + static_cast<std::size_t>(nx * ny), 2);
                }
    });
    std::vector<double> volume(label_count, 0.0), area(label_count, 0.0), cut(label_count, 0.0);
    for (uint32_t l = 0; l < label_count; ++l) {
        uint64_t voxels = 0, faces[3] = {0, 0, 0}, border[3] = {0, 0, 0};
        for (const Counts &p : parts) {
            voxels += p.voxels[l];
            for (int a = 0; a < 3; ++a) {
                faces[a] += p.faces[a][l];
                border[a] += p.border[a][l];
            }
        }
        volume[l] = static_cast<double>(voxels) * voxel;
        for (int a = 0; a < 3; ++a) {
            area[l] += static_cast<double>(faces[a]) * face[a];
            cut[l] += static_cast<double>(border[a]) * face[a];
        }
    }
    constexpr double kStaircase = 1.5; // voxel faces over the smooth surface they approximate
    std::vector<LabelShape> out(label_count);
    for (uint32_t l = 0; l < label_count; ++l) {
        if (volume[l] <= 0)
            continue;
        const double size = std::cbrt(volume[l]);
        out[l].thickness_mm = area[l] > 0 ? kStaircase * 2.0 * volume[l] / area[l] : size;
        out[l].compactness = out[l].thickness_mm / size;
        out[l].cut_fraction = cut[l] + area[l] > 0 ? cut[l] / (cut[l] + area[l]) : 0.0;
    }
    return out;
}

} // namespace arbor::topology
