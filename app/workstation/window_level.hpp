// window_level.hpp - the grey-value window of the slice views: the presets
// radiologists know on CT (3D Slicer's and Horos' values, in HU) and, on MR
// or any volume without HU, a window from the histogram (the 1st to 99th
// percentile of the values above the background), as Slicer's auto W/L.
#pragma once

#include "core/volume.hpp"

#include <optional>
#include <string>
#include <vector>

namespace arbor::workstation {

struct WindowLevel {
    double width = 400, level = 40; // physical units (HU on CT)
    // Grey in [0, 1] for a physical value.
    double grey(double value) const
    {
        const double g = (value - (level - width / 2)) / (width > 0 ? width : 1);
        return g < 0 ? 0 : g > 1 ? 1 : g;
    }
};

struct WindowPreset {
    std::string name; // "brain"
    WindowLevel window;
};

// CT: brain, bone, lung, soft tissue, abdomen.
const std::vector<WindowPreset> &ct_presets();
std::optional<WindowLevel> ct_preset(const std::string &name);

// From the values (physical units): 1st to 99th percentile above `background`
// (nullopt: of every value).
WindowLevel auto_window(const Volume &volume, std::optional<double> background = std::nullopt);

// The default: soft tissue on CT (unit "HU"), the histogram's otherwise.
WindowLevel default_window(const Volume &volume, std::optional<double> background = std::nullopt);

} // namespace arbor::workstation
