#include "pixel_frames.hpp"

#include "dcmtk_setup.hpp"
#include "jpeg2000_codestream.hpp"

#include <dcmtk/config/osconfig.h>
#include <dcmtk/dcmdata/dcpixseq.h>
#include <dcmtk/dcmdata/dcpxitem.h>
#include <dcmtk/dcmdata/dctk.h>

#include <stdexcept>

namespace arbor::dicom {

namespace {

bool is_lossy(E_TransferSyntax xfer)
{
    switch (xfer) {
    case EXS_JPEGProcess1:
    case EXS_JPEGProcess2_4:
    case EXS_JPEGProcess6_8:
    case EXS_JPEGProcess10_12:
    case EXS_JPEGLSLossy:
    case EXS_JPEG2000:
        return true;
    default:
        return false;
    }
}

bool is_jpeg2000(E_TransferSyntax xfer)
{
    return xfer == EXS_JPEG2000LosslessOnly || xfer == EXS_JPEG2000;
}

bool decodable(E_TransferSyntax xfer)
{
    const DcmXfer x(xfer);
    if (!x.isEncapsulated())
        return xfer != EXS_Unknown;
    switch (xfer) {
    case EXS_JPEGProcess1:
    case EXS_JPEGProcess2_4:
    case EXS_JPEGProcess6_8:
    case EXS_JPEGProcess10_12:
    case EXS_JPEGProcess14:
    case EXS_JPEGProcess14SV1:
    case EXS_JPEGLSLossless:
    case EXS_JPEGLSLossy:
    case EXS_RLELossless:
        return true;
    default:
        return is_jpeg2000(xfer);
    }
}

std::string syntax_text(E_TransferSyntax xfer)
{
    const DcmXfer x(xfer);
    return std::string(x.getXferName()) + " (" + x.getXferID() + ")";
}

// All frames of encapsulated JPEG 2000 pixel data, decoded with OpenJPEG.
std::vector<int32_t> decode_jpeg2000(DcmDataset &ds, E_TransferSyntax xfer, const ImageRecord &record)
{
    const std::string name = record.path.string();
    DcmElement *element = nullptr;
    DcmPixelSequence *fragments = nullptr;
    if (ds.findAndGetElement(DCM_PixelData, element).bad() || !element ||
        static_cast<DcmPixelData *>(element)->getEncapsulatedRepresentation(xfer, nullptr, fragments).bad() ||
        !fragments)
        throw std::runtime_error(name + ": cannot read its encapsulated JPEG 2000 pixel data");
    // Item 0 is the offset table; a frame may span several fragments, and
    // each frame starts with a JPEG 2000 signature.
    std::vector<std::vector<uint8_t>> frames;
    for (unsigned long i = 1; i < fragments->card(); ++i) {
        DcmPixelItem *item = nullptr;
        Uint8 *bytes = nullptr;
        if (fragments->getItem(item, i).bad() || !item || item->getUint8Array(bytes).bad())
            throw std::runtime_error(name + ": cannot read JPEG 2000 fragment " + std::to_string(i));
        const std::size_t size = item->getLength();
        if (size == 0 || !bytes)
            continue;
        if (frames.empty() || starts_jpeg2000_frame(bytes, size))
            frames.emplace_back();
        frames.back().insert(frames.back().end(), bytes, bytes + size);
    }
    if (frames.size() != record.frames.size())
        throw std::runtime_error(name + ": its JPEG 2000 pixel data holds " + std::to_string(frames.size()) +
                                 " frame(s), the header says " + std::to_string(record.frames.size()));
    const std::size_t plane = std::size_t{record.rows} * record.columns;
    std::vector<int32_t> decoded(plane * frames.size());
    std::vector<int32_t> one;
    for (std::size_t f = 0; f < frames.size(); ++f) {
        try {
            decode_jpeg2000_frame(frames[f].data(), frames[f].size(), record.columns, record.rows, one);
        } catch (const std::runtime_error &e) {
            throw std::runtime_error(name + ": frame " + std::to_string(f + 1) + " of its " +
                                     syntax_text(xfer) + " pixel data: " + e.what());
        }
        std::copy(one.begin(), one.end(), decoded.begin() + static_cast<std::ptrdiff_t>(f * plane));
    }
    return decoded;
}

} // namespace

bool can_decode_transfer_syntax(const std::string &uid)
{
    return decodable(DcmXfer(uid.c_str()).getXfer());
}

std::string undecodable_syntax_message(const std::string &uid)
{
    const DcmXfer x(uid.c_str());
    const std::string name = x.getXfer() == EXS_Unknown ? "an unknown transfer syntax (" + uid + ")"
                                                         : syntax_text(x.getXfer());
    return "pixel data is compressed as " + name +
           ", which Arbor cannot decode (it decodes JPEG baseline, extended and lossless, JPEG-LS "
           "and RLE with DCMTK, and JPEG 2000 with OpenJPEG)";
}

int transfer_syntax_rank(const std::string &uid)
{
    const DcmXfer x(uid.c_str());
    if (!decodable(x.getXfer()))
        return 3;
    if (!x.isEncapsulated())
        return 0;
    return is_lossy(x.getXfer()) ? 2 : 1;
}

DecodedImage::DecodedImage(const ImageRecord &record) : record_(record), file_(std::make_unique<DcmFileFormat>())
{
    ensure_dcmtk_ready();
    const std::string name = record.path.string();
    const OFCondition loaded = file_->loadFile(OFFilename(record.path.c_str()));
    if (loaded.bad())
        throw std::runtime_error(name + ": cannot read the file (" + loaded.text() + ")");
    DcmDataset &ds = *file_->getDataset();
    if (!ds.tagExists(DCM_PixelData))
        throw std::runtime_error(name + ": has no Pixel Data");
    const E_TransferSyntax xfer = ds.getOriginalXfer();
    if (!decodable(xfer))
        throw std::runtime_error(name + ": " + undecodable_syntax_message(DcmXfer(xfer).getXferID()));
    if (is_jpeg2000(xfer)) {
        decoded_ = decode_jpeg2000(ds, xfer, record);
        return;
    }
    const OFCondition decoded = ds.chooseRepresentation(EXS_LittleEndianExplicit, nullptr);
    if (decoded.bad() || !ds.canWriteXfer(EXS_LittleEndianExplicit))
        throw std::runtime_error(name + ": decoding its " + syntax_text(xfer) + " pixel data failed (" +
                                 (decoded.bad() ? decoded.text() : "no decoder took it") + ")");

    const uint64_t per_frame = uint64_t{record.rows} * record.columns * (record.bits_allocated / 8);
    const uint64_t needed = per_frame * record.frames.size();
    unsigned long count = 0;
    uint64_t have = 0;
    if (record.bits_allocated == 8) {
        const Uint8 *p = nullptr;
        if (ds.findAndGetUint8Array(DCM_PixelData, p, &count).bad() || !p)
            throw std::runtime_error(name + ": cannot read its Pixel Data");
        bytes8_ = p;
        have = count;
    } else {
        if (record.bits_allocated == 32 && DcmXfer(xfer).getByteOrder() == EBO_BigEndian)
            throw std::runtime_error(name + ": 32-bit big-endian pixel data is not supported");
        const Uint16 *p = nullptr;
        if (ds.findAndGetUint16Array(DCM_PixelData, p, &count).bad() || !p)
            throw std::runtime_error(name + ": cannot read its Pixel Data");
        words16_ = p;
        have = uint64_t{count} * 2;
    }
    if (have < needed)
        throw std::runtime_error(name + ": Pixel Data holds " + std::to_string(have) + " bytes but " +
                                 std::to_string(record.frames.size()) + " frame(s) of " +
                                 std::to_string(record.columns) + "x" + std::to_string(record.rows) +
                                 " need " + std::to_string(needed) + " (truncated file?)");
}

DecodedImage::~DecodedImage() = default;


void DecodedImage::stored_values(uint32_t frame, double *out) const
{
    const uint64_t n = uint64_t{record_.rows} * record_.columns;
    const uint32_t bits = record_.bits_stored;
    const uint32_t shift = record_.high_bit + 1 - bits;
    const uint64_t mask = bits >= 64 ? ~uint64_t{0} : (uint64_t{1} << bits) - 1;
    const uint64_t sign = uint64_t{1} << (bits - 1);
    const bool is_signed = record_.is_signed;
    auto value = [&](uint64_t word) {
        const uint64_t v = (word >> shift) & mask;
        if (is_signed && (v & sign))
            return static_cast<double>(static_cast<int64_t>(v) - static_cast<int64_t>(mask) - 1);
        return static_cast<double>(v);
    };
    const uint64_t first = n * frame;
    if (!decoded_.empty()) {
        // JPEG 2000 samples are values, not words: no High Bit shift; the
        // mask and sign follow the header, as pydicom does when a
        // codestream's signedness disagrees with Pixel Representation.
        for (uint64_t i = 0; i < n; ++i)
            out[i] = value(static_cast<uint64_t>(static_cast<int64_t>(decoded_[first + i])) << shift);
    } else if (record_.bits_allocated == 8) {
        for (uint64_t i = 0; i < n; ++i)
            out[i] = value(bytes8_[first + i]);
    } else if (record_.bits_allocated == 16) {
        for (uint64_t i = 0; i < n; ++i)
            out[i] = value(words16_[first + i]);
    } else {
        for (uint64_t i = 0; i < n; ++i) {
            const uint64_t lo = words16_[2 * (first + i)], hi = words16_[2 * (first + i) + 1];
            out[i] = value(lo | (hi << 16));
        }
    }
}

} // namespace arbor::dicom
