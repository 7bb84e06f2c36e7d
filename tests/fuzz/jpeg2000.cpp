// jpeg2000.cpp - fuzzes the JPEG 2000 frame decoder (dicom/jpeg2000_codestream
// on OpenJPEG), which reads the frames of JPEG 2000 DICOM files.
//
// Input: the image size the DICOM header would give (columns, then rows,
// 16-bit little endian each), then the frame: a J2K codestream or a JP2 file.
#include "fuzz_support.hpp"

#include "dicom/jpeg2000_codestream.hpp"

#include <stdexcept>
#include <vector>

namespace {

// The host admits at most this many samples per frame before decoding (64
// MiB of 32-bit values); a DICOM header claiming more is refused there.
constexpr uint64_t kMaxSamples = uint64_t{16} << 20;

} // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t *data, std::size_t size)
{
    if (size < 4)
        return 0;
    const uint32_t columns = data[0] | uint32_t{data[1]} << 8;
    const uint32_t rows = data[2] | uint32_t{data[3]} << 8;
    if (uint64_t{columns} * rows > kMaxSamples)
        return 0;
    std::vector<int32_t> samples;
    try {
        arbor::dicom::decode_jpeg2000_frame(data + 4, size - 4, columns, rows, samples);
    } catch (const std::runtime_error &) {
        return 0; // refused with OpenJPEG's reason
    } catch (...) {
        arbor::fuzz::unexpected_exception(std::current_exception());
    }
    if (samples.size() != uint64_t{columns} * rows)
        arbor::fuzz::finding("decoded " + std::to_string(samples.size()) + " samples for a " +
                             std::to_string(columns) + "x" + std::to_string(rows) + " frame");
    return 0;
}
