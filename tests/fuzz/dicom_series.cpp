// dicom_series.cpp - fuzzes reading a folder of DICOM files as one volume:
// the folder scan and series grouping (dicom/folder_scan), every file's
// header (image_record), slice stacking (slice_stack, series_volume) and
// decoding (pixel_frames), through the DICOM importer plugin and the host's
// import flow.
//
// Input: one byte choosing the importer's policies (bit 0: refuse irregular
// gaps, bit 1: interpolate missing slices, bit 2: refuse gantry tilt; 0 is
// the default), then the files of the folder separated by kFileSeparator.
#include "fuzz_support.hpp"
#include "host_import.hpp"

#include <cstdio>
#include <filesystem>
#include <fstream>

namespace {

constexpr std::string_view kFileSeparator = "ARBOR-FUZZ-NEXT-FILE";
// More files make slower runs, not new code paths.
constexpr std::size_t kMaxFiles = 16;

} // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t *data, std::size_t size)
{
    if (size < 1)
        return 0;
    const uint8_t policy = data[0];
    namespace fs = std::filesystem;
    const fs::path folder = arbor::fuzz::scratch_folder() / "series";
    fs::remove_all(folder);
    fs::create_directories(folder);
    const auto files = arbor::fuzz::split_input(data + 1, size - 1, kFileSeparator);
    for (std::size_t i = 0; i < files.size() && i < kMaxFiles; ++i) {
        char name[16];
        std::snprintf(name, sizeof name, "%03zu.dcm", i);
        std::ofstream(folder / name, std::ios::binary).write(files[i].data(), static_cast<std::streamsize>(files[i].size()));
    }
    arbor::fuzz::ImportCheck check;
    check.params = {{"irregular-slices", policy & 1 ? "refuse" : "resample"},
                    {"missing-slices", policy & 2 ? "interpolate" : "refuse"},
                    {"gantry-tilt", policy & 4 ? "refuse" : "correct"}};
    arbor::fuzz::import_through_host("org.arbor.importer.dicom", folder, check);
    return 0;
}
