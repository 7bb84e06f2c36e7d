#include "coarse_lattice.hpp"
#include "ray_geometry.hpp"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>

namespace arbor::raycast {

CoarseLattice::CoarseLattice(const arbor_render_request_v2 &request, double pixels)
    : f_(pixels), region_x_(request.region_x), region_y_(request.region_y)
{
    const auto count = [&](uint32_t side) { return std::max<int64_t>(1, static_cast<int64_t>(std::ceil(side / f_))); };
    frame_columns_ = count(request.frame_width);
    frame_rows_ = count(request.frame_height);
    m0_ = static_cast<int64_t>(lattice(request.region_x + 0.5, frame_columns_));
    const int64_t m1 = std::min<int64_t>(
        frame_columns_ - 1, static_cast<int64_t>(lattice(request.region_x + request.region_width - 0.5, frame_columns_)) + 1);
    n0_ = static_cast<int64_t>(lattice(request.region_y + 0.5, frame_rows_));
    const int64_t n1 = std::min<int64_t>(
        frame_rows_ - 1, static_cast<int64_t>(lattice(request.region_y + request.region_height - 0.5, frame_rows_)) + 1);
    w_ = m1 - m0_ + 1;
    h_ = n1 - n0_ + 1;
}

// The ray lattice position of frame pixel centre p: (p - f / 2) / f.
double CoarseLattice::lattice(double p, int64_t n) const
{
    return std::clamp((p - f_ / 2) / f_, 0.0, static_cast<double>(n - 1));
}

void CoarseLattice::interpolate(const std::vector<Sample> &rays, arbor_image &out) const
{
    const int64_t depth_stride = depth_stride_of(out), w = w_, h = h_;
    tbb::parallel_for(tbb::blocked_range<uint32_t>(0, out.height, 8), [&](const tbb::blocked_range<uint32_t> &r) {
        for (uint32_t y = r.begin(); y != r.end(); ++y) {
            const double v = lattice(region_y_ + y + 0.5, frame_rows_) - static_cast<double>(n0_);
            const int64_t b = std::min<int64_t>(static_cast<int64_t>(v), h - 1), b1 = std::min<int64_t>(b + 1, h - 1);
            const float fy = static_cast<float>(v - static_cast<double>(b));
            float *row = out.rgba + static_cast<int64_t>(y) * out.row_stride;
            for (uint32_t x = 0; x < out.width; ++x) {
                const double u = lattice(region_x_ + x + 0.5, frame_columns_) - static_cast<double>(m0_);
                const int64_t a = std::min<int64_t>(static_cast<int64_t>(u), w - 1), a1 = std::min<int64_t>(a + 1, w - 1);
                const float fx = static_cast<float>(u - static_cast<double>(a));
                const Sample &s00 = rays[static_cast<std::size_t>(b * w + a)], &s10 = rays[static_cast<std::size_t>(b * w + a1)],
                             &s01 = rays[static_cast<std::size_t>(b1 * w + a)], &s11 = rays[static_cast<std::size_t>(b1 * w + a1)];
                for (int c = 0; c < 4; ++c) {
                    const float top = s00.rgba[c] + fx * (s10.rgba[c] - s00.rgba[c]);
                    const float bottom = s01.rgba[c] + fx * (s11.rgba[c] - s01.rgba[c]);
                    row[4 * x + c] = std::clamp(top + fy * (bottom - top), 0.0f, 1.0f);
                }
                if (out.depth)
                    out.depth[static_cast<int64_t>(y) * depth_stride + x] =
                        (fy < 0.5f ? (fx < 0.5f ? s00 : s10) : (fx < 0.5f ? s01 : s11)).depth;
            }
        }
    });
}

} // namespace arbor::raycast
