#include "ct_tissue.hpp"

#include <limits>

namespace arbor {

const std::vector<CtTissue> &ct_tissues()
{
    constexpr double inf = std::numeric_limits<double>::infinity();
    static const std::vector<CtTissue> bins = {{"air", -inf, -900},         {"lung", -900, -200},
                                               {"fat", -200, -20},          {"soft tissue", -20, 120},
                                               {"contrast", 120, 350},      {"bone", 350, inf}};
    return bins;
}

std::vector<std::string> ct_tissues_spanned(double low_hu, double high_hu)
{
    std::vector<std::string> out;
    for (const CtTissue &t : ct_tissues())
        if (low_hu < t.high_hu && high_hu >= t.low_hu)
            out.push_back(t.name);
    return out;
}

} // namespace arbor
