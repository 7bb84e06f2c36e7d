// independent_decode.hpp - decoders for the test of the VTK-based importers
// that share no code with VTK: gzip via zlib, the NIfTI-1 header fields, the
// zlib-compressed data blocks of VTK XML files (appended raw and inline
// base64), so that every voxel the importers produce can be compared with
// the file's own bytes.
#pragma once

#include <zlib.h>

#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <stdexcept>
#include <string>

namespace arbor::test::decode {

inline std::string file_bytes(const std::filesystem::path &path)
{
    std::ifstream in(path, std::ios::binary);
    if (!in)
        throw std::runtime_error("cannot open " + path.string());
    return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

inline std::string gunzip_file(const std::filesystem::path &path)
{
    gzFile f = gzopen(path.c_str(), "rb");
    if (!f)
        throw std::runtime_error("gzopen failed for " + path.string());
    std::string out;
    char buf[1 << 16];
    int n = 0;
    while ((n = gzread(f, buf, sizeof buf)) > 0)
        out.append(buf, static_cast<std::size_t>(n));
    gzclose(f);
    if (n < 0)
        throw std::runtime_error("gzread failed for " + path.string());
    return out;
}

template <class T>
T little_endian_at(const std::string &bytes, std::size_t offset)
{
    if (offset + sizeof(T) > bytes.size())
        throw std::runtime_error("read past the end of the data");
    T v;
    std::memcpy(&v, bytes.data() + offset, sizeof(T)); // the test host is little endian
    return v;
}

// The NIfTI-1 fields the tests compare (offsets from nifti1.h).
struct Nifti1Header {
    int16_t dim[8];
    int16_t datatype;
    int16_t bitpix;
    float pixdim[8];
    float vox_offset;
    float scl_slope;
    float scl_inter;
    int16_t qform_code;
    int16_t sform_code;
    float srow[3][4];
    std::string magic;
};

inline Nifti1Header nifti1_header(const std::string &bytes)
{
    if (little_endian_at<int32_t>(bytes, 0) != 348)
        throw std::runtime_error("not a little-endian NIfTI-1 header");
    Nifti1Header h{};
    for (int i = 0; i < 8; ++i) {
        h.dim[i] = little_endian_at<int16_t>(bytes, 40 + 2 * i);
        h.pixdim[i] = little_endian_at<float>(bytes, 76 + 4 * i);
    }
    h.datatype = little_endian_at<int16_t>(bytes, 70);
    h.bitpix = little_endian_at<int16_t>(bytes, 72);
    h.vox_offset = little_endian_at<float>(bytes, 108);
    h.scl_slope = little_endian_at<float>(bytes, 112);
    h.scl_inter = little_endian_at<float>(bytes, 116);
    h.qform_code = little_endian_at<int16_t>(bytes, 252);
    h.sform_code = little_endian_at<int16_t>(bytes, 254);
    for (int r = 0; r < 3; ++r)
        for (int c = 0; c < 4; ++c)
            h.srow[r][c] = little_endian_at<float>(bytes, 280 + 16 * r + 4 * c);
    h.magic = bytes.substr(344, 3);
    return h;
}

inline std::string inflate_block(const char *data, std::size_t size, std::size_t expected)
{
    std::string out(expected, '\0');
    uLongf got = static_cast<uLongf>(expected);
    if (uncompress(reinterpret_cast<Bytef *>(out.data()), &got,
                   reinterpret_cast<const Bytef *>(data), static_cast<uLong>(size)) != Z_OK ||
        got != expected)
        throw std::runtime_error("zlib block does not inflate to its declared size");
    return out;
}

// VTK's compressed-data layout: header {nblocks, block size, last block size,
// compressed size of each block} in `Word` integers, then the zlib blocks.
template <class Word>
std::string inflate_vtk_blocks(const std::string &header_and_blocks, std::size_t header_offset,
                               std::size_t blocks_offset)
{
    const auto word = [&](std::size_t i) {
        return static_cast<std::size_t>(
            little_endian_at<Word>(header_and_blocks, header_offset + i * sizeof(Word)));
    };
    const std::size_t nblocks = word(0), block = word(1), last = word(2);
    std::string out;
    std::size_t at = blocks_offset;
    for (std::size_t b = 0; b < nblocks; ++b) {
        const std::size_t compressed = word(3 + b);
        const std::size_t expected = (b + 1 == nblocks && last != 0) ? last : block;
        if (at + compressed > header_and_blocks.size())
            throw std::runtime_error("VTK data block runs past the end of the file");
        out += inflate_block(header_and_blocks.data() + at, compressed, expected);
        at += compressed;
    }
    return out;
}

// The first array of a .vti written with <AppendedData encoding="raw">,
// header_type UInt64, vtkZLibDataCompressor, at offset 0.
inline std::string vti_appended_raw_array(const std::filesystem::path &path)
{
    const std::string file = file_bytes(path);
    const std::size_t tag = file.find("<AppendedData encoding=\"raw\">");
    if (tag == std::string::npos)
        throw std::runtime_error("no raw appended data in " + path.string());
    const std::size_t start = file.find('_', tag) + 1;
    const std::size_t nblocks = little_endian_at<uint64_t>(file, start);
    return inflate_vtk_blocks<uint64_t>(file, start, start + (3 + nblocks) * 8);
}

inline std::string base64_decode(const std::string &text)
{
    std::string out;
    uint32_t acc = 0;
    int bits = 0;
    for (char ch : text) {
        int v;
        if (ch >= 'A' && ch <= 'Z') v = ch - 'A';
        else if (ch >= 'a' && ch <= 'z') v = ch - 'a' + 26;
        else if (ch >= '0' && ch <= '9') v = ch - '0' + 52;
        else if (ch == '+') v = 62;
        else if (ch == '/') v = 63;
        else continue; // padding and white space
        acc = (acc << 6) | static_cast<uint32_t>(v);
        bits += 6;
        if (bits >= 8) {
            bits -= 8;
            out.push_back(static_cast<char>((acc >> bits) & 0xff));
        }
    }
    return out;
}

// The first <DataArray format="binary"> of a .vti with header_type UInt32
// and zlib compression: the header and the blocks are base64-encoded
// separately, one after the other.
inline std::string vti_inline_base64_array(const std::filesystem::path &path)
{
    const std::string file = file_bytes(path);
    const std::size_t array = file.find("<DataArray");
    const std::size_t open = file.find('>', array) + 1;
    const std::size_t close = file.find("</DataArray>", open);
    std::string text;
    for (std::size_t i = open; i < close; ++i)
        if (file[i] > ' ')
            text.push_back(file[i]);
    const std::string first = base64_decode(text.substr(0, 8));
    const std::size_t nblocks = little_endian_at<uint32_t>(first, 0);
    const std::size_t header_bytes = (3 + nblocks) * 4;
    const std::size_t header_chars = (header_bytes + 2) / 3 * 4;
    const std::string header = base64_decode(text.substr(0, header_chars));
    const std::string blocks = base64_decode(text.substr(header_chars));
    return inflate_vtk_blocks<uint32_t>(header + blocks, 0, header.size());
}

} // namespace arbor::test::decode
