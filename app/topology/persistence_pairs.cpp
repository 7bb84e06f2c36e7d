#include "persistence_pairs.hpp"

#include "core/voxel_type.hpp"

#include <algorithm>
#include <cstdio>
#include <ostream>

namespace arbor::topology {

std::vector<PersistencePair> persistence_pairs(const ContourTree &tree, const BranchDecomposition &d,
                                               const FieldView &field)
{
    std::vector<PersistencePair> pairs;
    pairs.reserve(d.branches.size());
    for (const Branch &b : d.branches) {
        const uint32_t e = tree.node_vertex[b.extremum_node];
        const uint32_t s = tree.node_vertex[b.saddle_node];
        switch (b.kind) {
        case BranchKind::Root: pairs.push_back({-1, s, e, field.value(s), field.value(e)}); break;
        case BranchKind::Minimum: pairs.push_back({0, e, s, field.value(e), field.value(s)}); break;
        case BranchKind::Maximum: pairs.push_back({2, s, e, field.value(s), field.value(e)}); break;
        }
    }
    std::sort(pairs.begin(), pairs.end(), [](const PersistencePair &a, const PersistencePair &b) {
        if (a.persistence() != b.persistence())
            return a.persistence() < b.persistence();
        if (a.type != b.type)
            return a.type < b.type;
        if (a.birth != b.birth)
            return a.birth < b.birth;
        return a.death < b.death;
    });
    return pairs;
}

void write_persistence_pairs(std::ostream &out, const std::vector<PersistencePair> &pairs,
                             const Geometry &grid, arbor_voxel_type type, const std::string &source)
{
    const int64_t nx = grid.dims[0], ny = grid.dims[1];
    out << "# Arbor persistence pairs (branch decomposition of the contour tree, persistence)\n";
    out << "# data=" << source << " dims=" << grid.dims[0] << " " << grid.dims[1] << " " << grid.dims[2]
        << " type=" << arbor_voxel_type_name(type) << "\n";
    out << "# vertex id = x + nx*(y + ny*z); ties in value broken by vertex id (lower id = lower)\n";
    out << "# type: 0 = (minimum, join saddle), 2 = (split saddle, maximum), -1 = (global min, global max)\n";
    out << "# sorted by persistence ascending, then type, then birth and death vertex\n";
    out << "# type birth_vertex death_vertex birth_value death_value persistence bx by bz dx dy dz\n";
    const bool integers = is_integer_voxel_type(type);
    char line[512];
    for (const PersistencePair &p : pairs) {
        const auto coord = [&](uint32_t v, int axis) {
            return axis == 0 ? v % nx : axis == 1 ? (v / nx) % ny : v / (nx * ny);
        };
        if (integers)
            std::snprintf(line, sizeof line, "%d %u %u %.0f %.0f %.0f %lld %lld %lld %lld %lld %lld\n", p.type,
                          p.birth, p.death, p.birth_value, p.death_value, p.persistence(),
                          static_cast<long long>(coord(p.birth, 0)), static_cast<long long>(coord(p.birth, 1)),
                          static_cast<long long>(coord(p.birth, 2)), static_cast<long long>(coord(p.death, 0)),
                          static_cast<long long>(coord(p.death, 1)), static_cast<long long>(coord(p.death, 2)));
        else
            std::snprintf(line, sizeof line, "%d %u %u %.9g %.9g %.9g %lld %lld %lld %lld %lld %lld\n", p.type,
                          p.birth, p.death, p.birth_value, p.death_value, p.persistence(),
                          static_cast<long long>(coord(p.birth, 0)), static_cast<long long>(coord(p.birth, 1)),
                          static_cast<long long>(coord(p.birth, 2)), static_cast<long long>(coord(p.death, 0)),
                          static_cast<long long>(coord(p.death, 1)), static_cast<long long>(coord(p.death, 2)));
        out << line;
    }
}

} // namespace arbor::topology
