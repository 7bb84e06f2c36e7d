#include "tf_generator_classes.hpp"

#include <algorithm>
#include <array>

namespace arbor::tf {

std::pair<double, double> branch_domain(const sdk::BranchTreeView &tree, const arbor_tf_request &request, uint32_t b)
{
    if (b == 0)
        return {request.value_range[0], request.value_range[1]};
    const double s = tree.saddle_value(b), e = tree.extremum_value(b);
    return {std::min(s, e), std::max(s, e)};
}

void bake_lut(arbor_tf_set &out, uint32_t b, std::pair<double, double> domain,
              const std::function<std::array<float, 4>(double value)> &rgba)
{
    out.domain[2 * b] = domain.first;
    out.domain[2 * b + 1] = domain.second;
    float *lut = out.lut + std::size_t{b} * out.lut_size * 4;
    for (uint32_t i = 0; i < out.lut_size; ++i) {
        const double value = domain.first + (domain.second - domain.first) * i / (out.lut_size - 1.0);
        const std::array<float, 4> c = rgba(value);
        for (int k = 0; k < 4; ++k)
            lut[4 * i + k] = std::clamp(c[k], 0.0f, 1.0f);
    }
}

} // namespace arbor::tf
