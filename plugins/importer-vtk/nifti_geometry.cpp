// nifti_geometry.cpp - NIfTI sform / qform / pixdim to LPS geometry, following
// the NIfTI-1 standard's three methods (nifti1.h, nifti1_io.c).
#include "nifti_geometry.hpp"

#include <cmath>
#include <optional>

namespace arbor::importer_vtk {

namespace {

struct Affine {
    std::array<double, 9> matrix{}; // row-major, columns are the grid steps
    std::array<double, 3> translation{};
};

double determinant(const std::array<double, 9> &m)
{
    return m[0] * (m[4] * m[8] - m[5] * m[7]) - m[1] * (m[3] * m[8] - m[5] * m[6]) +
           m[2] * (m[3] * m[7] - m[4] * m[6]);
}

bool usable(const Affine &a)
{
    for (double v : a.matrix)
        if (!std::isfinite(v))
            return false;
    for (double v : a.translation)
        if (!std::isfinite(v))
            return false;
    return determinant(a.matrix) != 0.0;
}

// Pixel sizes the quaternion and pixdim methods use: nifti1_io treats a
// non-positive (or, here, non-finite) size as 1.
double positive_size(double v)
{
    return std::isfinite(v) && v > 0.0 ? v : 1.0;
}

Affine from_sform(const NiftiSpace &s)
{
    Affine a;
    for (int r = 0; r < 3; ++r) {
        for (int c = 0; c < 3; ++c)
            a.matrix[3 * r + c] = s.srow[r][c];
        a.translation[r] = s.srow[r][3];
    }
    return a;
}

// Method 2 of nifti1.h: rotation from the quaternion (b, c, d), a computed,
// pixel sizes from pixdim, and qfac = pixdim[0] flipping the k axis.
Affine from_qform(const NiftiSpace &s)
{
    double b = s.quatern[0], c = s.quatern[1], d = s.quatern[2];
    double a = 1.0 - (b * b + c * c + d * d);
    if (a < 1.e-7) {
        // A 180-degree rotation stored with rounding: renormalise (b, c, d).
        a = 1.0 / std::sqrt(b * b + c * c + d * d);
        b *= a;
        c *= a;
        d *= a;
        a = 0.0;
    } else {
        a = std::sqrt(a);
    }
    const double r[9] = {a * a + b * b - c * c - d * d, 2 * (b * c - a * d), 2 * (b * d + a * c),
                         2 * (b * c + a * d), a * a + c * c - b * b - d * d, 2 * (c * d - a * b),
                         2 * (b * d - a * c), 2 * (c * d + a * b), a * a + d * d - c * c - b * b};
    const double qfac = s.pixdim[0] < 0.0 ? -1.0 : 1.0;
    const double step[3] = {positive_size(s.pixdim[1]), positive_size(s.pixdim[2]),
                            qfac * positive_size(s.pixdim[3])};
    Affine out;
    for (int row = 0; row < 3; ++row)
        for (int col = 0; col < 3; ++col)
            out.matrix[3 * row + col] = r[3 * row + col] * step[col];
    out.translation = s.qoffset;
    return out;
}

// Method 1 of nifti1.h: no orientation, only pixel sizes.
Affine from_pixdim(const NiftiSpace &s)
{
    Affine a;
    for (int c = 0; c < 3; ++c)
        a.matrix[4 * c] = positive_size(s.pixdim[c + 1]);
    return a;
}

// xyzt_units bits 0-2: 1 metre, 2 millimetre, 3 micron; 0 (unknown) is
// taken as millimetres, what nearly every writer means.
double millimetres_per_unit(int xyzt_units)
{
    switch (xyzt_units & 0x07) {
    case 1: return 1000.0;
    case 3: return 0.001;
    default: return 1.0;
    }
}

} // namespace

NiftiPlacement place_nifti(const NiftiSpace &space)
{
    std::optional<Affine> chosen;
    const char *source = "pixdim";
    if (space.sform_code > 0) {
        if (Affine a = from_sform(space); usable(a)) {
            chosen = a;
            source = "sform";
        }
    }
    if (!chosen && space.qform_code > 0) {
        if (Affine a = from_qform(space); usable(a)) {
            chosen = a;
            source = "qform";
        }
    }
    if (!chosen)
        chosen = from_pixdim(space);

    Affine lps = *chosen;
    const double unit = millimetres_per_unit(space.xyzt_units);
    for (int r = 0; r < 3; ++r) {
        // RAS -> LPS: x and y change sign, z stays.
        const double flip = r < 2 ? -1.0 : 1.0;
        for (int c = 0; c < 3; ++c)
            lps.matrix[3 * r + c] *= flip * unit;
        lps.translation[r] *= flip * unit;
    }
    return {geometry_from_affine(lps.matrix, lps.translation), source};
}

NiftiValueMapping nifti_value_mapping(double scl_slope, double scl_inter)
{
    NiftiValueMapping m;
    if (std::isfinite(scl_slope) && scl_slope != 0.0) {
        m.scale = scl_slope;
        m.offset = std::isfinite(scl_inter) ? scl_inter : 0.0;
    }
    return m;
}

} // namespace arbor::importer_vtk
