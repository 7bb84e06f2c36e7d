// pixel_frames.hpp - decoding one DICOM file's pixel data (uncompressed and
// deflated, JPEG, JPEG-LS and RLE through DCMTK's decoders, JPEG 2000 through
// OpenJPEG) and reading its frames as stored values: masked to Bits Stored,
// sign-extended.
#pragma once

#include "image_record.hpp"

#include <memory>
#include <string>
#include <vector>

class DcmFileFormat;

namespace arbor::dicom {

class DecodedImage {
public:
    // Loads and decodes `record.path`.  Throws std::runtime_error naming the
    // file and the cause: unreadable, no pixel data, a transfer syntax no
    // decoder handles (named with its UID), or too few bytes for the frames.
    explicit DecodedImage(const ImageRecord &record);
    ~DecodedImage();
    DecodedImage(const DecodedImage &) = delete;
    DecodedImage &operator=(const DecodedImage &) = delete;

    // Stored values of frame `frame`, row by row (rows x columns of them).
    void stored_values(uint32_t frame, double *out) const;

private:
    const ImageRecord &record_;
    std::unique_ptr<DcmFileFormat> file_;
    const uint8_t *bytes8_ = nullptr;
    const uint16_t *words16_ = nullptr;
    std::vector<int32_t> decoded_; // JPEG 2000 samples, all frames
};

// Whether Arbor can decode pixel data in transfer syntax `uid`.
bool can_decode_transfer_syntax(const std::string &uid);

// "pixel data is compressed as <name> (<uid>), which Arbor cannot decode ...".
std::string undecodable_syntax_message(const std::string &uid);

// Preference among duplicate copies of an image: lower is better (native,
// then lossless, then lossy compression, then syntaxes nothing decodes).
int transfer_syntax_rank(const std::string &uid);

} // namespace arbor::dicom
