// dicom_file.cpp - fuzzes reading one DICOM file with the DICOM library:
// its header (dicom/image_record: identity, pixel format, per-frame geometry
// of classic and enhanced objects) and its pixel data (pixel_frames: native,
// deflated, JPEG, JPEG-LS, RLE and JPEG 2000), every frame's stored values.
// The input is one file, written as input.dcm.
#include "fuzz_support.hpp"

#include "dicom/image_record.hpp"
#include "dicom/pixel_frames.hpp"

#include <stdexcept>
#include <vector>

namespace {

// The host admits a volume of at most this many voxels before any pixel is
// decoded (64 MiB of 32-bit values); a bigger header is refused there.
constexpr uint64_t kMaxSamples = uint64_t{16} << 20;

void read_file(const std::filesystem::path &path)
{
    const arbor::dicom::ImageRecord record = arbor::dicom::read_image_record(path);
    if (!record.is_image())
        return;
    const uint64_t plane = uint64_t{record.rows} * record.columns;
    if (plane * record.frames.size() > kMaxSamples)
        return;
    const arbor::dicom::DecodedImage image(record);
    std::vector<double> values(plane);
    for (uint32_t f = 0; f < record.frames.size(); ++f)
        image.stored_values(f, values.data());
}

} // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t *data, std::size_t size)
{
    const auto path = arbor::fuzz::write_input("input.dcm", data, size);
    try {
        read_file(path);
    } catch (const std::runtime_error &) {
        // Refused with a message naming the file and the problem.
    } catch (...) {
        arbor::fuzz::unexpected_exception(std::current_exception());
    }
    return 0;
}
