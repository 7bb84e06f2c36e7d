// image_record.hpp - what Arbor needs to know about one DICOM file before it
// decodes any pixels: identity (patient, study, series, instance), the pixel
// format, and the geometry and value mapping of each of its frames.
//
// Enhanced multi-frame objects (Enhanced CT/MR) keep per-frame geometry in
// functional group sequences; classic single-frame images keep it at the top
// level.  Both are read into one Frame per frame, so later stages never care
// which kind a file was.
#pragma once

#include <array>
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

namespace arbor::dicom {

// Geometry of one frame in patient coordinates (LPS, mm).
struct FrameGeometry {
    std::optional<std::array<double, 3>> position;    // Image Position (Patient)
    std::optional<std::array<double, 6>> orientation; // row cosines, then column cosines
    std::optional<std::array<double, 2>> pixel_spacing; // between rows, between columns
};

// Stored -> physical values: physical = stored * slope + intercept.
struct RescaleMapping {
    double slope = 1.0;
    double intercept = 0.0;
    std::string unit; // "HU", or "" when unknown
    bool operator==(const RescaleMapping &) const = default;
};

struct Frame {
    FrameGeometry geometry;
    RescaleMapping mapping;
};

struct ImageRecord {
    std::filesystem::path path;
    std::string transfer_syntax_uid;
    std::string transfer_syntax_name;

    std::string sop_class_uid;
    std::string sop_instance_uid;
    std::string study_uid;
    std::string series_uid;
    std::string frame_of_reference_uid;
    std::string patient_name;
    std::string patient_id;
    std::string study_date;
    std::string study_description;
    std::string series_description;
    std::string series_number;
    std::string modality;
    std::vector<std::string> image_type;
    int64_t instance_number = 0;

    // Pixel format (rows == 0: the object has no image, e.g. an RT plan).
    uint32_t rows = 0;
    uint32_t columns = 0;
    uint32_t samples_per_pixel = 1;
    uint32_t bits_allocated = 0;
    uint32_t bits_stored = 0;
    uint32_t high_bit = 0;
    bool is_signed = false;
    std::string photometric;
    bool has_pixel_data = false;
    std::optional<int64_t> padding_value;       // Pixel Padding Value, in stored units
    std::optional<int64_t> padding_range_limit; // Pixel Padding Range Limit

    // Distance between frames of a multi-frame object without per-frame
    // positions (Spacing Between Slices, else Slice Thickness); 0 if unknown.
    double frame_spacing = 0.0;
    bool per_frame_positions = false; // positions came from functional groups
    std::vector<Frame> frames;        // Number of Frames entries (1 for classic images)

    bool is_localizer() const;
    bool is_image() const { return rows > 0 && columns > 0 && has_pixel_data; }
};

// Reads the header of `path` (pixel data is located but not loaded).  Throws
// std::runtime_error with a message that names the file and the problem when
// it is not a DICOM file DCMTK can parse or its image attributes are invalid.
ImageRecord read_image_record(const std::filesystem::path &path);

// True when the first bytes look like DICOM: "DICM" at offset 128, or a
// dataset without preamble that starts with a group 0x0002 or 0x0008 tag.
bool looks_like_dicom(const uint8_t *head, std::size_t size);
bool looks_like_dicom(const std::filesystem::path &path);

} // namespace arbor::dicom
