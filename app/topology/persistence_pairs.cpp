#include "persistence_pairs.hpp"

#include "core/voxel_type.hpp"

#include <algorithm>
#include <charconv>
#include <ostream>
#include <string>
#include <type_traits>

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
    // std::to_chars, not snprintf: a noisy CT has millions of pairs, and
    // parsing the format string for each was most of the writing.  Fixed
    // with 0 decimals and general with 9 digits are printf's %.0f and %.9g.
    const bool integers = is_integer_voxel_type(type);
    std::string text;
    text.reserve(std::size_t{1} << 20);
    char field[64];
    const auto put = [&](auto x) {
        std::to_chars_result r;
        if constexpr (std::is_floating_point_v<decltype(x)>)
            r = integers ? std::to_chars(field, field + sizeof field, x, std::chars_format::fixed, 0)
                         : std::to_chars(field, field + sizeof field, x, std::chars_format::general, 9);
        else
            r = std::to_chars(field, field + sizeof field, x);
        text.append(field, r.ptr);
    };
    for (const PersistencePair &p : pairs) {
        const int64_t coords[6] = {p.birth % nx, (p.birth / nx) % ny, p.birth / (nx * ny),
                                   p.death % nx, (p.death / nx) % ny, p.death / (nx * ny)};
        put(p.type);
        text += ' ';
        put(p.birth);
        text += ' ';
        put(p.death);
        for (const double v : {p.birth_value, p.death_value, p.persistence()}) {
            text += ' ';
            put(v);
        }
        for (const int64_t c : coords) {
            text += ' ';
            put(c);
        }
        text += '\n';
        if (text.size() > (std::size_t{1} << 20) - 256) {
            out << text;
            text.clear();
        }
    }
    out << text;
}

} // namespace arbor::topology
