// folder_scan.hpp - finding the DICOM files under a folder and grouping them
// into series (by Series Instance UID) of studies and patients.
//
// Every file is looked at; a file that is not DICOM, or is DICOM but cannot
// be parsed, is listed with the reason and never stops the scan.
#pragma once

#include "image_record.hpp"

#include <filesystem>
#include <functional>
#include <string>
#include <vector>

namespace arbor::dicom {

struct SkippedFile {
    std::filesystem::path path;
    std::string reason;
};

struct Series {
    // Series Instance UID; "" when the files have none.  Some anonymisers
    // and test exports drop it (a type-1 attribute): such images are grouped
    // by study, series number, frame of reference, orientation, size and
    // pixel format instead (`grouped` then counts them).
    std::string uid;
    std::size_t grouped = 0;
    std::vector<ImageRecord> images; // in path order

    const ImageRecord &first() const { return images.front(); }
    std::size_t frame_count() const;
};

struct FolderScan {
    std::filesystem::path root;
    std::vector<Series> series; // by patient, study date, study, series number
    std::vector<SkippedFile> unreadable;            // DICOM-looking files that failed
    std::vector<std::filesystem::path> not_dicom;   // files without DICOM content
};

// Called with the fraction done; may throw to cancel.
using ScanProgress = std::function<void(double)>;

// Scans `path`: a folder (recursively, following no symbolic links to
// folders) or a single file.  Throws only when `path` does not exist.
FolderScan scan_dicom(const std::filesystem::path &path, const ScanProgress &progress = {});

// How many distinct images of series `series_uid` (by position, else SOP
// Instance UID) lie in the folder of `file`, `file` included (the folder
// only, not below it).
std::size_t series_images_beside(const std::filesystem::path &file, const std::string &series_uid);

// The series a selector names: its Series Instance UID, or its 1-based row
// number in the scan's order.  An empty selector picks the only series with
// images.  Throws with the choices listed when there is no unique match.
const Series &select_series(const FolderScan &scan, const std::string &selector);

} // namespace arbor::dicom
