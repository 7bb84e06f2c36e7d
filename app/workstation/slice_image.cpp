#include "slice_image.hpp"

#include <algorithm>
#include <cmath>

namespace arbor::workstation {

SliceImage slice_image(const Volume &volume, const SliceGeometry &s, int64_t slice, const WindowLevel &window,
                       const LabelOverlay &overlay)
{
    SliceImage out;
    slice_image(volume, s, slice, window, overlay, out);
    return out;
}

void slice_image(const Volume &volume, const SliceGeometry &s, int64_t slice, const WindowLevel &window,
                 const LabelOverlay &overlay, SliceImage &out)
{
    out.width = s.width;
    out.height = s.height;
    out.rgba.assign(static_cast<std::size_t>(s.width * s.height * 4), 255);
    const auto &dims = volume.geometry().dims;
    slice = std::clamp<int64_t>(slice, 0, s.count - 1);
    const bool labelled = overlay.labels && overlay.colors &&
                          overlay.labels->size() == static_cast<std::size_t>(volume.voxel_count());
    for (int64_t y = 0; y < s.height; ++y)
        for (int64_t x = 0; x < s.width; ++x) {
            const auto ijk = s.voxel(x, y, slice);
            const int64_t v = ijk[0] + dims[0] * (ijk[1] + dims[1] * ijk[2]);
            const double g = window.grey(volume.mapping().physical(volume.value(v)));
            std::array<double, 3> c{g, g, g};
            if (labelled) {
                const uint32_t l = (*overlay.labels)[static_cast<std::size_t>(v)];
                // The root (label 0) is everything not kept: left uncoloured.
                const bool hidden = overlay.hidden && l < overlay.hidden->size() && (*overlay.hidden)[l];
                if (l > 0 && l < overlay.colors->size() && !hidden) {
                    double a = overlay.opacity;
                    if (overlay.selected)
                        a = *overlay.selected == l ? std::min(0.85, 2 * a) : 0.5 * a;
                    for (int k = 0; k < 3; ++k)
                        c[k] = (1 - a) * c[k] + a * (*overlay.colors)[l][k];
                }
            }
            uint8_t *p = &out.rgba[static_cast<std::size_t>((y * s.width + x) * 4)];
            for (int k = 0; k < 3; ++k)
                p[k] = static_cast<uint8_t>(std::lround(std::clamp(c[k], 0.0, 1.0) * 255));
        }
}

} // namespace arbor::workstation
