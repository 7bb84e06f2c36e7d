// coarse_lattice.hpp - the coarse pass's rays: one per n x n block of the
// frame, at the block's centre (so tiles of one frame agree), and each
// pixel of a region bilinear between the four rays around it.
#pragma once

#include <arbor/renderer.h>

#include <cstdint>
#include <vector>

namespace arbor::raycast {

// One ray's result.
struct Sample {
    float rgba[4];
    float depth; // mm from the camera to where opacity reached 1/2; infinity if never
};

class CoarseLattice {
public:
    // The rays a region of the frame needs, at `pixels` per ray along each side.
    CoarseLattice(const arbor_render_request_v2 &request, double pixels);

    int64_t columns() const { return w_; } // rays across the region
    int64_t rows() const { return h_; }
    // Frame position of ray (m, n) of the region's lattice.
    double x(int64_t m) const { return static_cast<double>(m0_ + m) * f_ + f_ / 2; }
    double y(int64_t n) const { return static_cast<double>(n0_ + n) * f_ + f_ / 2; }
    // The first ray's lattice indices in the frame's lattice.
    int64_t first_column() const { return m0_; }
    int64_t first_row() const { return n0_; }

    // Writes the region's pixels from `rays` (rows() x columns(), row-major):
    // colours bilinear, depth of the nearest ray (depths do not
    // interpolate across edges).
    void interpolate(const std::vector<Sample> &rays, arbor_image &out) const;

private:
    double lattice(double p, int64_t n) const;

    double f_;
    uint32_t region_x_, region_y_;
    int64_t frame_columns_, frame_rows_;
    int64_t m0_, n0_, w_, h_;
};

} // namespace arbor::raycast
