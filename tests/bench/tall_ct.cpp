#include "tall_ct.hpp"

#include "plugin_fixture.hpp"

#include "io/nrrd_writer.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace arbor::bench {

std::filesystem::path tall_ct(const std::filesystem::path &dicom, int factor, const std::filesystem::path &out)
{
    if (std::filesystem::exists(out))
        return out;
    const Volume v = test::import(dicom);
    Geometry g = v.geometry();
    const int64_t nz = (g.dims[2] - 1) * factor + 1, plane = g.dims[0] * g.dims[1];
    g.dims[2] = nz;
    g.spacing[2] /= factor;
    Volume r = Volume::allocate(v.type(), g, v.mapping(), uint64_t{1} << 32);
    if (v.type() != ARBOR_VOXEL_U16)
        throw std::runtime_error("the CT head is expected as u16");
    const uint16_t *src = v.as<uint16_t>();
    uint16_t *dst = r.as<uint16_t>();
    for (int64_t k = 0; k < nz; ++k) {
        const int64_t k0 = k / factor, k1 = std::min(k0 + 1, v.geometry().dims[2] - 1);
        const double f = static_cast<double>(k % factor) / factor;
        for (int64_t p = 0; p < plane; ++p)
            dst[k * plane + p] =
                static_cast<uint16_t>(std::lround((1 - f) * src[k0 * plane + p] + f * src[k1 * plane + p]));
    }
    io::write_nrrd(r, out);
    return out;
}

} // namespace arbor::bench
