// series_volume.hpp - one regular volume from one DICOM series.
//
// Planning (the constructor) reads headers only: it leaves out localizers and
// repeated copies of an instance, checks that the images agree in size,
// orientation and pixel format, orders frames along the slice normal and
// plans the stack (slice_stack.hpp).  Reading decodes the pixels and applies
// MONOCHROME1 inversion, pixel padding and the planned resampling.
//
// Values: when every frame shares one rescale mapping and pixel format, the
// volume keeps the stored integers and carries the mapping (slope, intercept,
// unit); otherwise voxels are physical values in 32-bit floats.  MONOCHROME1
// data is inverted so that larger values are brighter, with the mapping
// negated so physical values keep their meaning.
#pragma once

#include "folder_scan.hpp"
#include "slice_stack.hpp"

#include <arbor/volume.h>

#include <array>
#include <string>
#include <vector>

namespace arbor::dicom {

struct VolumeLayout {
    std::array<int64_t, 3> dims{};
    std::array<double, 3> spacing{};
    std::array<double, 3> origin{};
    std::array<double, 9> direction{}; // row-major, column c = LPS unit vector of axis c
    arbor_voxel_type type = ARBOR_VOXEL_UNKNOWN;
    double value_scale = 1.0;
    double value_offset = 0.0;
    std::string unit;
};

class SeriesVolume {
public:
    // Throws std::runtime_error naming the series and the problem when the
    // series cannot become one volume under `policy`.
    SeriesVolume(const Series &series, const StackPolicy &policy);

    const VolumeLayout &layout() const { return layout_; }
    // Corrections and assumptions made while planning, in words.
    const std::vector<std::string> &notes() const { return notes_; }
    std::size_t image_count() const { return images_.size(); }

    // Fills `voxels` (contiguous, i fastest, of layout().type).  Returns what
    // reading corrected (pixel padding replaced).  Throws with the file named
    // when a file cannot be decoded.
    std::vector<std::string> read(void *voxels, const ScanProgress &progress = {}) const;

private:
    struct FrameRef {
        const ImageRecord *image;
        uint32_t frame;
    };

    void select_images(const Series &series);
    void check_consistency() const;
    std::vector<Vec3> frame_positions(std::array<double, 6> &orientation);
    void choose_values();
    class FrameReader;

    std::string name_;
    std::vector<const ImageRecord *> images_;
    std::vector<FrameRef> frames_;
    SliceStack stack_;
    VolumeLayout layout_;
    std::vector<std::string> notes_;
    bool physical_ = false; // voxels are physical values (f32)
    bool invert_ = false;   // MONOCHROME1
};

} // namespace arbor::dicom
