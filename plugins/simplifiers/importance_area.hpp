// importance_area.hpp - the importance formulas of the thesis' attribute
// space (ch. 4.5): measures, each relative to the root branch, are the
// coordinates of a point; importance is an area spanned by it.
#pragma once

#include <cmath>
#include <cstddef>

namespace arbor::simplifiers {

// ITri (thesis eq. 4.7): the area of the triangle whose corners are the
// point's projections on the three axes p, v and hv.
inline double importance_triangle(double p, double v, double hv)
{
    return 0.5 * std::sqrt((hv * p) * (hv * p) + (v * p) * (v * p) + (hv * v) * (hv * v));
}

// The n-measure generalisation (eq. 4.9) for n >= 2 measures m[0..n):
// 1/(n-1) * sqrt(sum over k of the product over j != k of m_j^2), the
// "area" of the hypotenuse face of the simplex cut off by the point's
// projections.  For n = 3 it is importance_triangle.
inline double hypotenuse_face_area(const double *m, std::size_t n)
{
    double sum = 0.0;
    for (std::size_t k = 0; k < n; ++k) {
        double product = 1.0;
        for (std::size_t j = 0; j < n; ++j)
            if (j != k)
                product *= m[j] * m[j];
        sum += product;
    }
    return std::sqrt(sum) / static_cast<double>(n - 1);
}

} // namespace arbor::simplifiers
