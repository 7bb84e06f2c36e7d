#include "jpeg2000_codestream.hpp"

#include <openjpeg.h>

#include <algorithm>
#include <cstring>
#include <memory>
#include <stdexcept>
#include <string>

namespace arbor::dicom {

namespace {

struct MemoryStream {
    const uint8_t *data;
    std::size_t size;
    std::size_t pos = 0;
};

OPJ_SIZE_T read_bytes(void *buffer, OPJ_SIZE_T n, void *user)
{
    auto &m = *static_cast<MemoryStream *>(user);
    if (m.pos >= m.size)
        return static_cast<OPJ_SIZE_T>(-1);
    const std::size_t count = std::min<std::size_t>(n, m.size - m.pos);
    std::memcpy(buffer, m.data + m.pos, count);
    m.pos += count;
    return count;
}

OPJ_OFF_T skip_bytes(OPJ_OFF_T n, void *user)
{
    auto &m = *static_cast<MemoryStream *>(user);
    const auto target = std::clamp<OPJ_OFF_T>(static_cast<OPJ_OFF_T>(m.pos) + n, 0, static_cast<OPJ_OFF_T>(m.size));
    const OPJ_OFF_T moved = target - static_cast<OPJ_OFF_T>(m.pos);
    m.pos = static_cast<std::size_t>(target);
    return moved;
}

OPJ_BOOL seek_bytes(OPJ_OFF_T n, void *user)
{
    auto &m = *static_cast<MemoryStream *>(user);
    if (n < 0 || static_cast<std::size_t>(n) > m.size)
        return OPJ_FALSE;
    m.pos = static_cast<std::size_t>(n);
    return OPJ_TRUE;
}

void keep_error(const char *message, void *user)
{
    auto &text = *static_cast<std::string *>(user);
    if (text.empty() && message) {
        text = message;
        while (!text.empty() && (text.back() == '\n' || text.back() == ' '))
            text.pop_back();
    }
}

void ignore_message(const char *, void *) {}

bool is_jp2(const uint8_t *d, std::size_t size)
{
    static const uint8_t signature[] = {0, 0, 0, 0x0C, 'j', 'P', ' ', ' '};
    return size >= sizeof signature && std::memcmp(d, signature, sizeof signature) == 0;
}

} // namespace

bool starts_jpeg2000_frame(const uint8_t *data, std::size_t size)
{
    return (size >= 4 && data[0] == 0xFF && data[1] == 0x4F && data[2] == 0xFF && data[3] == 0x51) ||
           is_jp2(data, size);
}

void decode_jpeg2000_frame(const uint8_t *data, std::size_t size, uint32_t columns, uint32_t rows,
                           std::vector<int32_t> &out)
{
    if (!starts_jpeg2000_frame(data, size))
        throw std::runtime_error("the frame is not a JPEG 2000 codestream");
    MemoryStream memory{data, size};
    std::unique_ptr<opj_stream_t, void (*)(opj_stream_t *)> stream(opj_stream_create(1 << 16, OPJ_TRUE),
                                                                    &opj_stream_destroy);
    std::unique_ptr<opj_codec_t, void (*)(opj_codec_t *)> codec(
        opj_create_decompress(is_jp2(data, size) ? OPJ_CODEC_JP2 : OPJ_CODEC_J2K), &opj_destroy_codec);
    if (!stream || !codec)
        throw std::runtime_error("OpenJPEG could not start a decoder");
    opj_stream_set_user_data(stream.get(), &memory, nullptr);
    opj_stream_set_user_data_length(stream.get(), size);
    opj_stream_set_read_function(stream.get(), &read_bytes);
    opj_stream_set_skip_function(stream.get(), &skip_bytes);
    opj_stream_set_seek_function(stream.get(), &seek_bytes);

    std::string error;
    opj_set_error_handler(codec.get(), &keep_error, &error);
    opj_set_warning_handler(codec.get(), &ignore_message, nullptr);
    opj_set_info_handler(codec.get(), &ignore_message, nullptr);
    opj_dparameters_t parameters;
    opj_set_default_decoder_parameters(&parameters);
    if (!opj_setup_decoder(codec.get(), &parameters))
        throw std::runtime_error("OpenJPEG refused the decoder set-up: " + error);

    opj_image_t *raw_image = nullptr;
    const bool header = opj_read_header(stream.get(), codec.get(), &raw_image);
    std::unique_ptr<opj_image_t, void (*)(opj_image_t *)> image(raw_image, &opj_image_destroy);
    if (!header || !image)
        throw std::runtime_error("corrupt JPEG 2000 header" + (error.empty() ? "" : " (" + error + ")"));
    // Check the size before decoding, so a hostile header cannot make
    // OpenJPEG allocate more than the image the DICOM header describes.
    const uint32_t w = image->x1 - image->x0, h = image->y1 - image->y0;
    if (w != columns || h != rows)
        throw std::runtime_error("the JPEG 2000 image is " + std::to_string(w) + "x" + std::to_string(h) +
                                 " but the DICOM header says " + std::to_string(columns) + "x" +
                                 std::to_string(rows));
    if (image->numcomps != 1)
        throw std::runtime_error("the JPEG 2000 image has " + std::to_string(image->numcomps) +
                                 " components; Arbor reads greyscale images only");
    if (!opj_decode(codec.get(), stream.get(), image.get()) || !opj_end_decompress(codec.get(), stream.get()))
        throw std::runtime_error("corrupt JPEG 2000 data" + (error.empty() ? "" : " (" + error + ")"));
    const opj_image_comp_t &c = image->comps[0];
    if (!c.data || c.w != columns || c.h != rows)
        throw std::runtime_error("the JPEG 2000 component does not cover the image");
    out.assign(c.data, c.data + std::size_t{columns} * rows);
}

} // namespace arbor::dicom
