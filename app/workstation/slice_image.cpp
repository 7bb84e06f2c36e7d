#include "slice_image.hpp"

#include "core/voxel_type.hpp"

#include <algorithm>
#include <array>

namespace arbor::workstation {

SliceImage slice_image(const Volume &volume, const SliceGeometry &s, int64_t slice, const WindowLevel &window,
                       const LabelOverlay &overlay)
{
    SliceImage out;
    slice_image(volume, s, slice, window, overlay, out);
    return out;
}

// One switch on the voxel type per image, not per pixel, and a pixel's
// voxel one stride further along its row: the slice views redraw all three
// images at every step of a window/level drag.
void slice_image(const Volume &volume, const SliceGeometry &s, int64_t slice, const WindowLevel &window,
                 const LabelOverlay &overlay, SliceImage &out)
{
    out.width = s.width;
    out.height = s.height;
    out.rgba.resize(static_cast<std::size_t>(s.width * s.height * 4));
    const auto &dims = volume.geometry().dims;
    slice = std::clamp<int64_t>(slice, 0, s.count - 1);
    const bool labelled = !overlay.labels.empty() && overlay.colors &&
                          overlay.labels.size() == static_cast<std::size_t>(volume.voxel_count());
    const auto index = [&](int64_t x, int64_t y) {
        const auto ijk = s.voxel(x, y, slice);
        return ijk[0] + dims[0] * (ijk[1] + dims[1] * ijk[2]);
    };
    const ValueMapping &mapping = volume.mapping();
    dispatch_voxel_type(volume.type(), [&](auto type) {
        using T = decltype(type);
        const T *voxels = volume.as<T>();
        for (int64_t y = 0; y < s.height; ++y) {
            const int64_t first = index(0, y), stride = s.width > 1 ? index(1, y) - first : 0;
            uint8_t *p = &out.rgba[static_cast<std::size_t>(y * s.width * 4)];
            for (int64_t x = 0; x < s.width; ++x, p += 4) {
                const int64_t v = first + x * stride;
                const double g = window.grey(mapping.physical(static_cast<double>(voxels[v])));
                std::array<double, 3> c{g, g, g};
                if (labelled) {
                    const uint32_t l = overlay.labels[static_cast<std::size_t>(v)];
                    // The root (label 0) is everything not kept: left uncoloured.
                    const bool hidden = overlay.hidden && l < overlay.hidden->size() && (*overlay.hidden)[l];
                    if (l > 0 && l < overlay.colors->size() && !hidden) {
                        double alpha = overlay.opacity;
                        if (overlay.selected)
                            alpha = *overlay.selected == l ? std::min(0.85, 2 * alpha) : 0.5 * alpha;
                        for (int k = 0; k < 3; ++k)
                            c[k] = (1 - alpha) * c[k] + alpha * (*overlay.colors)[l][k];
                    }
                }
                for (int k = 0; k < 3; ++k)
                    p[k] = static_cast<uint8_t>(std::clamp(c[k], 0.0, 1.0) * 255 + 0.5);
                p[3] = 255;
            }
        }
    });
}

} // namespace arbor::workstation
