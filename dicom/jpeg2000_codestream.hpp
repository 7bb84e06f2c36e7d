// jpeg2000_codestream.hpp - decoding one JPEG 2000 frame (a raw J2K
// codestream or a JP2 file, as DICOM encapsulates them) with OpenJPEG.
// DCMTK 3.6.7 has no JPEG 2000 decoder, so pixel_frames uses this one for
// the two JPEG 2000 transfer syntaxes.
#pragma once

#include <cstdint>
#include <cstddef>
#include <vector>

namespace arbor::dicom {

// True when `data` starts a JPEG 2000 codestream (SOC, SIZ) or a JP2 file.
bool starts_jpeg2000_frame(const uint8_t *data, std::size_t size);

// Decodes a single-component image of exactly columns x rows samples into
// `out` (row by row, as the codestream's integers).  Throws
// std::runtime_error with OpenJPEG's reason when the stream is corrupt, has
// another size, or has more than one component.
void decode_jpeg2000_frame(const uint8_t *data, std::size_t size, uint32_t columns, uint32_t rows,
                           std::vector<int32_t> &out);

} // namespace arbor::dicom
