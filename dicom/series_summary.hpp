// series_summary.hpp - what reading a series as one volume would give (its
// layout: size, spacing, type) and what it would correct (irregular gaps
// resampled, padding replaced...) or why it would refuse, without reading
// the pixels: what `arbor dicom ls` prints and the workstation's DICOM
// browser shows before a person chooses a series.
#pragma once

#include "dicom/folder_scan.hpp"
#include "dicom/series_volume.hpp"

#include <optional>
#include <string>
#include <vector>

namespace arbor::dicom {

struct SeriesSummary {
    const Series *series = nullptr;
    std::optional<VolumeLayout> layout; // none when refused
    std::vector<std::string> notes;     // what reading would correct
    std::string refusal;                // why it cannot be one volume ("" when it can)
};

SeriesSummary summarise_series(const Series &series);

} // namespace arbor::dicom
