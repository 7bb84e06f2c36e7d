#include "persistence_diagram.hpp"

#include <algorithm>
#include <set>
#include <stdexcept>
#include <string>

namespace arbor::topology {

int grid_dimension(const Geometry &grid)
{
    int d = 0;
    for (int64_t n : grid.dims)
        d += n > 1 ? 1 : 0;
    return d == 0 ? 3 : d;
}

int pair_dimension(int pair_type, int grid_dim)
{
    switch (pair_type) {
    case -1:
    case 0: return 0;
    case 1: return 1; // saddle-saddle pairs, as TTK writes them for volumes
    case 2: return std::max(grid_dim - 1, 0);
    default: throw std::invalid_argument("unknown pair type " + std::to_string(pair_type));
    }
}

PersistenceDiagram diagram_of_pairs(const std::vector<PersistencePair> &pairs, int grid_dim)
{
    PersistenceDiagram d;
    d.points.reserve(pairs.size());
    for (const PersistencePair &p : pairs)
        d.points.push_back({p.birth_value, p.death_value, pair_dimension(p.type, grid_dim), p.type == -1});
    return d;
}

std::vector<int> diagram_dimensions(const PersistenceDiagram &a, const PersistenceDiagram &b)
{
    std::set<int> dims;
    for (const PersistenceDiagram *d : {&a, &b})
        for (const DiagramPoint &p : d->points)
            dims.insert(p.dimension);
    return {dims.begin(), dims.end()};
}

} // namespace arbor::topology
