#include "local_occlusion.hpp"

#include <algorithm>
#include <cmath>

namespace arbor::raycast {

void LocalOcclusion::build(const VoxelGrid &g, const arbor_tf_set &tf)
{
    static constexpr int kAxes[kDirections][3] = {{1, 0, 0},  {-1, 0, 0},  {0, 1, 0},   {0, -1, 0},  {0, 0, 1},
                                                  {0, 0, -1}, {1, 1, 1},   {1, 1, -1},  {1, -1, 1},  {1, -1, -1},
                                                  {-1, 1, 1}, {-1, 1, -1}, {-1, -1, 1}, {-1, -1, -1}};
    const double step_mm = kStepVoxels * g.min_spacing;
    for (int d = 0; d < kDirections; ++d) {
        const double length = std::sqrt(static_cast<double>(kAxes[d][0] * kAxes[d][0] + kAxes[d][1] * kAxes[d][1] +
                                                            kAxes[d][2] * kAxes[d][2]));
        const Vec3 u{kAxes[d][0] / length, kAxes[d][1] / length, kAxes[d][2] / length};
        const Vec3 v = mul(g.to_voxel, {u[0] * step_mm, u[1] * step_mm, u[2] * step_mm});
        for (int a = 0; a < 3; ++a) {
            world_[static_cast<std::size_t>(d)][static_cast<std::size_t>(a)] = static_cast<float>(u[a]);
            steps_[static_cast<std::size_t>(d)][static_cast<std::size_t>(a)] = static_cast<float>(v[a]);
        }
    }
    table_.build(tf, step_mm);
}

float LocalOcclusion::visibility(const VoxelGrid &g, const BoundaryEmphasis &boundaries, const double p[3],
                                 const float n[3], float jitter) const
{
    const VoxelGrid::Strides corners = g.strides();
    const float last[3] = {static_cast<float>(std::max<int64_t>(g.nx - 2, 0)),
                           static_cast<float>(std::max<int64_t>(g.ny - 2, 0)),
                           static_cast<float>(std::max<int64_t>(g.nz - 2, 0))};
    const float high[3] = {static_cast<float>(g.nx - 1), static_cast<float>(g.ny - 1), static_cast<float>(g.nz - 1)};
    const float start[3] = {static_cast<float>(p[0]), static_cast<float>(p[1]), static_cast<float>(p[2])};
    const bool labelled = !g.label.empty();
    float sum = 0.0f, weight = 0.0f;
    for (std::size_t d = 0; d < kDirections; ++d) {
        const float cosine = world_[d][0] * n[0] + world_[d][1] * n[1] + world_[d][2] * n[2];
        if (cosine <= 0.0f)
            continue;
        float transmittance = 1.0f;
        for (int s = 1; s <= kSteps; ++s) {
            float q[3], cell[3];
            bool inside = true;
            for (int a = 0; a < 3; ++a) {
                q[a] = start[a] + (static_cast<float>(s) - jitter) * steps_[d][static_cast<std::size_t>(a)];
                inside = inside && q[a] >= 0.0f && q[a] <= high[a];
                cell[a] = std::min(std::floor(q[a]), last[a]);
            }
            if (!inside) // beyond the field of view: nothing occludes
                break;
            const std::size_t base =
                g.index(static_cast<int64_t>(cell[0]), static_cast<int64_t>(cell[1]), static_cast<int64_t>(cell[2]));
            const Cell c(g, base, corners, q[0] - cell[0], q[1] - cell[1], q[2] - cell[2]);
            float a = table_.lookup(labelled ? g.label.word(base) >> 1 : 0u, c.value())[3];
            if (boundaries.active())
                a *= boundaries.factor(g.surface[base].gradient);
            transmittance *= 1.0f - a;
        }
        sum += cosine * transmittance;
        weight += cosine;
    }
    return weight > 0.0f ? std::max(kFloor, sum / weight) : 1.0f;
}

} // namespace arbor::raycast
