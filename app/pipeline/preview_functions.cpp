#include "preview_functions.hpp"

#include "core/volume_statistics.hpp"

#include <algorithm>
#include <cmath>
#include <vector>

namespace arbor::pipeline {

std::unique_ptr<TransferFunctions> preview_functions(const FilterResult &filtered, uint32_t lut_size)
{
    const Volume &v = *filtered.volume;
    const VolumeStatistics stats = compute_statistics(v, 256);
    const double lo = stats.min, hi = stats.max > stats.min ? stats.max : stats.min + 1;
    const auto &spacing = v.geometry().spacing;
    const double min_spacing = std::min({spacing[0], spacing[1], spacing[2]});
    auto tf = std::make_unique<TransferFunctions>(1, lut_size, 8 * min_spacing);
    const double background = filtered.background ? filtered.background->level : lo;
    const ValueMapping &m = v.mapping();
    const bool ct = m.unit == "HU";
    const double top = stats.quantile(0.99) > background ? stats.quantile(0.99) : hi;
    std::vector<float> lut(std::size_t{lut_size} * 4, 0.0f);
    for (uint32_t i = 0; i < lut_size; ++i) {
        const double stored = lo + (hi - lo) * i / (lut_size - 1);
        float *e = &lut[std::size_t{i} * 4];
        if (stored <= background)
            continue; // transparent
        if (ct) {
            const double hu = m.physical(stored);
            if (hu < -200)
                continue; // air and lung
            if (hu < 300) { // soft tissue: a faint skin-toned veil
                e[0] = 0.85f, e[1] = 0.62f, e[2] = 0.52f, e[3] = 0.02f;
            } else { // bone
                const float t = static_cast<float>(std::clamp((hu - 300) / 700, 0.0, 1.0));
                e[0] = 0.95f, e[1] = 0.92f, e[2] = 0.84f, e[3] = 0.25f + 0.55f * t;
            }
        } else {
            const float t = static_cast<float>(std::clamp((stored - background) / (top - background), 0.0, 1.0));
            e[0] = 0.9f, e[1] = 0.85f, e[2] = 0.78f, e[3] = 0.4f * t * t;
        }
    }
    tf->assign(0, {lo, hi}, lut.data());
    return tf;
}

} // namespace arbor::pipeline
