#include "window_level.hpp"

#include <algorithm>
#include <cmath>

namespace arbor::workstation {

const std::vector<WindowPreset> &ct_presets()
{
    static const std::vector<WindowPreset> presets = {
        {"brain", {100, 50}},        {"bone", {1000, 400}}, {"lung", {1400, -500}},
        {"soft-tissue", {400, 40}}, {"abdomen", {350, 40}},
    };
    return presets;
}

std::optional<WindowLevel> ct_preset(const std::string &name)
{
    for (const WindowPreset &p : ct_presets())
        if (p.name == name)
            return p.window;
    return std::nullopt;
}

WindowLevel auto_window(const Volume &volume, std::optional<double> background)
{
    // A strided sample of at most ~1M voxels is plenty for percentiles.
    const int64_t n = volume.voxel_count();
    const int64_t stride = std::max<int64_t>(1, n / (1 << 20));
    std::vector<double> values;
    values.reserve(static_cast<std::size_t>(n / stride + 1));
    for (int64_t v = 0; v < n; v += stride) {
        const double x = volume.mapping().physical(volume.value(v));
        if (std::isfinite(x) && (!background || x > *background))
            values.push_back(x);
    }
    if (values.size() < 16) {
        values.clear();
        for (int64_t v = 0; v < n; v += stride) {
            const double x = volume.mapping().physical(volume.value(v));
            if (std::isfinite(x))
                values.push_back(x);
        }
    }
    if (values.empty())
        return {};
    auto at = [&](double q) {
        const std::size_t k = static_cast<std::size_t>(q * static_cast<double>(values.size() - 1));
        std::nth_element(values.begin(), values.begin() + static_cast<std::ptrdiff_t>(k), values.end());
        return values[k];
    };
    const double lo = at(0.01), hi = at(0.99);
    WindowLevel w;
    w.width = std::max(hi - lo, 1e-6);
    w.level = (lo + hi) / 2;
    return w;
}

WindowLevel default_window(const Volume &volume, std::optional<double> background)
{
    if (volume.mapping().unit == "HU")
        return *ct_preset("soft-tissue");
    return auto_window(volume, background);
}

} // namespace arbor::workstation
