#include "tall_ct.hpp"

#include "plugin_fixture.hpp"

#include "io/nrrd_writer.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <vector>

namespace arbor::bench {

namespace {

// Along one axis at a time: out-of-place, (n - 1) * f + 1 samples.
template <typename T>
std::vector<T> along(const std::vector<T> &src, std::array<int64_t, 3> &dims, int axis, int f)
{
    std::array<int64_t, 3> out = dims;
    out[axis] = (dims[axis] - 1) * f + 1;
    std::vector<T> dst(static_cast<std::size_t>(out[0] * out[1] * out[2]));
    const int64_t stride_in[3] = {1, dims[0], dims[0] * dims[1]}, stride_out[3] = {1, out[0], out[0] * out[1]};
    for (int64_t k = 0; k < out[2]; ++k)
        for (int64_t j = 0; j < out[1]; ++j)
            for (int64_t i = 0; i < out[0]; ++i) {
                const int64_t at[3] = {i, j, k};
                const int64_t a0 = at[axis] / f, a1 = std::min(a0 + 1, dims[axis] - 1);
                const double w = static_cast<double>(at[axis] % f) / f;
                int64_t base = 0;
                for (int a = 0; a < 3; ++a)
                    base += a == axis ? 0 : at[a] * stride_in[a];
                const double v = (1 - w) * src[static_cast<std::size_t>(base + a0 * stride_in[axis])] +
                                 w * src[static_cast<std::size_t>(base + a1 * stride_in[axis])];
                dst[static_cast<std::size_t>(i * stride_out[0] + j * stride_out[1] + k * stride_out[2])] =
                    static_cast<T>(std::lround(v));
            }
    dims = out;
    return dst;
}

template <typename T>
void resample(const Volume &v, const std::array<int, 3> &factor, Volume &r)
{
    std::array<int64_t, 3> dims = v.geometry().dims;
    std::vector<T> data(v.as<T>(), v.as<T>() + v.voxel_count());
    for (int a = 0; a < 3; ++a)
        if (factor[a] > 1)
            data = along(data, dims, a, factor[a]);
    std::copy(data.begin(), data.end(), r.as<T>());
}

} // namespace

std::filesystem::path upsampled(const std::filesystem::path &in, const std::array<int, 3> &factor,
                                const std::filesystem::path &out)
{
    if (std::filesystem::exists(out))
        return out;
    const Volume v = test::import(in);
    Geometry g = v.geometry();
    for (int a = 0; a < 3; ++a) {
        g.dims[a] = (g.dims[a] - 1) * factor[a] + 1;
        g.spacing[a] /= factor[a];
    }
    Volume r = Volume::allocate(v.type(), g, v.mapping(), uint64_t{1} << 32);
    if (v.type() == ARBOR_VOXEL_U16)
        resample<uint16_t>(v, factor, r);
    else if (v.type() == ARBOR_VOXEL_U8)
        resample<uint8_t>(v, factor, r);
    else
        throw std::runtime_error(in.string() + ": upsampling takes 8- or 16-bit unsigned voxels");
    io::write_nrrd(r, out);
    return out;
}

} // namespace arbor::bench
