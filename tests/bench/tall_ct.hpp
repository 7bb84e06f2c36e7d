// tall_ct.hpp - a chest CT's size from a real scan: the shared CT head
// DICOM (512 x 512 x 108) with `factor` times as many slices, linear
// between them, written once as NRRD (the renderer benchmarks' large input;
// resampling keeps the scan's own noise in-plane).
#pragma once

#include <filesystem>

namespace arbor::bench {

// The resampled CT at `out`, made from the DICOM series at `dicom` unless
// it is there already.
std::filesystem::path tall_ct(const std::filesystem::path &dicom, int factor, const std::filesystem::path &out);

} // namespace arbor::bench
