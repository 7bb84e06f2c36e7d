#include "link_components.hpp"

#include <stdexcept>

namespace arbor::topology {

namespace {

// Bit b of adjacency[a]: neighbours a and b are joined by an edge (their
// offsets differ by a Freudenthal offset).
std::array<uint16_t, 14> link_adjacency()
{
    std::array<uint16_t, 14> adjacency{};
    for (std::size_t a = 0; a < 14; ++a)
        for (std::size_t b = 0; b < 14; ++b) {
            const NeighborOffset &p = kFreudenthalOffsets[a], &q = kFreudenthalOffsets[b];
            for (const NeighborOffset &o : kFreudenthalOffsets)
                if (q.di - p.di == o.di && q.dj - p.dj == o.dj && q.dk - p.dk == o.dk)
                    adjacency[a] |= static_cast<uint16_t>(1u << b);
        }
    return adjacency;
}

std::vector<LinkComponents> build_table()
{
    const std::array<uint16_t, 14> adjacency = link_adjacency();
    std::vector<LinkComponents> table(std::size_t{1} << 14);
    for (uint32_t mask = 0; mask < table.size(); ++mask) {
        LinkComponents &entry = table[mask];
        uint32_t reached = 0;
        for (uint8_t start = 0; start < 14; ++start) {
            if (!((mask >> start) & 1u) || ((reached >> start) & 1u))
                continue;
            if (entry.count == entry.first.size())
                throw std::logic_error("a Freudenthal link piece has more than 6 components");
            entry.first[entry.count++] = start;
            uint32_t frontier = 1u << start;
            reached |= frontier;
            while (frontier) {
                const int a = __builtin_ctz(frontier);
                frontier &= frontier - 1;
                const uint32_t next = adjacency[a] & mask & ~reached;
                reached |= next;
                frontier |= next;
            }
        }
    }
    return table;
}

} // namespace

const std::vector<LinkComponents> &link_components_table()
{
    static const std::vector<LinkComponents> table = build_table();
    return table;
}

} // namespace arbor::topology
