// grid_neighbors.hpp - the vertex neighbourhoods of the Freudenthal
// triangulation of a regular grid, as TTK's implicit triangulation splits
// each cube into six tetrahedra.
//
// Vertex (i, j, k) has the 14 neighbours (+-1,0,0) (0,+-1,0) (0,0,+-1)
// +-(-1,1,0) +-(0,1,1) +-(-1,0,1) +-(-1,1,1); the diagonals run along
// (-1,1,1), not (1,1,1).  Using TTK's split makes the piecewise-linear field,
// and so every persistence pair, identical to TTK's.  Boundary vertices simply
// have fewer neighbours (no virtual vertex at infinity).
#pragma once

#include <array>
#include <cstdint>

namespace arbor::topology {

struct NeighborOffset {
    int8_t di, dj, dk;
};

inline constexpr std::array<NeighborOffset, 14> kFreudenthalOffsets{{
    {1, 0, 0},  {-1, 0, 0}, {0, 1, 0},  {0, -1, 0}, {0, 0, 1},   {0, 0, -1}, {-1, 1, 0},
    {1, -1, 0}, {0, 1, 1},  {0, -1, -1}, {-1, 0, 1}, {1, 0, -1}, {-1, 1, 1}, {1, -1, -1},
}};

// Neighbour enumeration for one grid.  Interior vertices use precomputed
// linear offsets; boundary vertices check each offset against the grid.
class GridNeighbors {
public:
    GridNeighbors(int64_t nx, int64_t ny, int64_t nz)
        : nx_(nx), ny_(ny), nz_(nz), inv_nx_(reciprocal(nx)), inv_nxy_(reciprocal(nx * ny))
    {
        for (std::size_t n = 0; n < kFreudenthalOffsets.size(); ++n) {
            const NeighborOffset &o = kFreudenthalOffsets[n];
            linear_[n] = o.di + nx * (o.dj + ny * o.dk);
        }
    }

    int64_t size() const { return nx_ * ny_ * nz_; }
    int64_t nx() const { return nx_; }
    int64_t ny() const { return ny_; }
    int64_t nz() const { return nz_; }
    // Linear id offset of neighbour n (kFreudenthalOffsets[n]).
    int64_t offset(std::size_t n) const { return linear_[n]; }

    // Calls f(neighbour vertex id) for every neighbour of vertex v.
    template <class F>
    void for_each(int64_t v, F &&f) const
    {
        for_each_indexed(v, [&f](std::size_t, int64_t w) { f(w); });
    }

    // Calls f(n, neighbour vertex id) for every neighbour of vertex v, where
    // n indexes kFreudenthalOffsets.
    template <class F>
    void for_each_indexed(int64_t v, F &&f) const
    {
        // Vertex ids fit in 32 bits: divide by multiplying with precomputed
        // reciprocals (exact for 32-bit operands), not with the slow divider.
        const uint32_t x = static_cast<uint32_t>(v);
        const int64_t row = divide(x, inv_nx_), k = divide(x, inv_nxy_);
        const int64_t i = v - row * nx_;
        const int64_t j = row - k * ny_;
        if (i > 0 && i + 1 < nx_ && j > 0 && j + 1 < ny_ && k > 0 && k + 1 < nz_) {
            for (std::size_t n = 0; n < linear_.size(); ++n)
                f(n, v + linear_[n]);
            return;
        }
        for (std::size_t n = 0; n < kFreudenthalOffsets.size(); ++n) {
            const NeighborOffset &o = kFreudenthalOffsets[n];
            const int64_t a = i + o.di, b = j + o.dj, c = k + o.dk;
            if (a >= 0 && a < nx_ && b >= 0 && b < ny_ && c >= 0 && c < nz_)
                f(n, v + linear_[n]);
        }
    }

private:
    // ceil(2^64 / d); 0 stands for d = 1.
    static uint64_t reciprocal(int64_t d) { return ~uint64_t{0} / static_cast<uint64_t>(d) + 1; }
    static int64_t divide(uint32_t x, uint64_t reciprocal)
    {
        if (reciprocal == 0)
            return x;
        return static_cast<int64_t>((static_cast<unsigned __int128>(reciprocal) * x) >> 64);
    }

    int64_t nx_, ny_, nz_;
    uint64_t inv_nx_, inv_nxy_;
    std::array<int64_t, 14> linear_{};
};

} // namespace arbor::topology
