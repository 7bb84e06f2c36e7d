// relation_wheel.hpp - the X-type relation wheel of the neighbouring
// depiction (thesis §5.3.2): two opposite sectors of 93.6 degrees, the
// children in one and the siblings in the other, and the selected branch and
// its parent at the centres of the two gaps between them.
#pragma once

#include <cmath>
#include <cstddef>

namespace arbor::depictors {

struct RelationWheel {
    static constexpr double kSectorWidth = 93.6;
    double rotation = 0.0; // hue of the children sector's centre, degrees

    static double wrap(double hue) { return hue - 360.0 * std::floor(hue / 360.0); }
    double children_centre() const { return wrap(rotation); }
    double siblings_centre() const { return wrap(rotation + 180.0); }
    double selected_hue() const { return wrap(rotation + 90.0); }
    double parent_hue() const { return wrap(rotation + 270.0); }
    // k of n spread evenly inside a sector, away from its edges.
    static double in_sector(double centre, std::size_t k, std::size_t n)
    {
        return wrap(centre - kSectorWidth / 2 + kSectorWidth * (static_cast<double>(k) + 0.5) / static_cast<double>(n));
    }
    double child_hue(std::size_t k, std::size_t n) const { return in_sector(children_centre(), k, n); }
    double sibling_hue(std::size_t k, std::size_t n) const { return in_sector(siblings_centre(), k, n); }
};

} // namespace arbor::depictors
