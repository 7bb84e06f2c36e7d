// nifti_magic.cpp - NIfTI magic strings at their header offsets, through zlib
// for .nii.gz.
#include "nifti_magic.hpp"

#include <zlib.h>

#include <array>
#include <cstring>

namespace arbor::importer_vtk {

namespace {

// NIfTI-1: sizeof_hdr 348 at offset 0, magic "n+1\0" / "ni1\0" at 344.
// NIfTI-2: sizeof_hdr 540 at offset 0, magic "n+2\0\r\n\032\n" at 4.
constexpr std::size_t kNifti1MagicOffset = 344;
constexpr std::size_t kNifti2MagicOffset = 4;
constexpr std::size_t kBytesNeeded = kNifti1MagicOffset + 4;

bool sizeof_hdr_is(const uint8_t *p, uint32_t expected)
{
    const uint32_t le = uint32_t(p[0]) | uint32_t(p[1]) << 8 | uint32_t(p[2]) << 16 |
                        uint32_t(p[3]) << 24;
    const uint32_t be = uint32_t(p[3]) | uint32_t(p[2]) << 8 | uint32_t(p[1]) << 16 |
                        uint32_t(p[0]) << 24;
    return le == expected || be == expected;
}

NiftiMagic magic_in_plain(const uint8_t *p, std::size_t size)
{
    if (size >= kNifti2MagicOffset + 8 && sizeof_hdr_is(p, 540)) {
        const uint8_t *m = p + kNifti2MagicOffset;
        if (m[0] == 'n' && (m[1] == '+' || m[1] == 'i') && m[2] == '2' && m[3] == 0)
            return m[1] == '+' ? NiftiMagic::single_file : NiftiMagic::pair_header;
    }
    if (size >= kBytesNeeded && sizeof_hdr_is(p, 348)) {
        const uint8_t *m = p + kNifti1MagicOffset;
        if (m[0] == 'n' && (m[1] == '+' || m[1] == 'i') && m[2] == '1' && m[3] == 0)
            return m[1] == '+' ? NiftiMagic::single_file : NiftiMagic::pair_header;
    }
    return NiftiMagic::none;
}

// Inflates the start of a gzip stream into `out`; returns the bytes produced.
// A truncated stream is fine: the header is all we need.
std::size_t inflate_start(const uint8_t *gz, std::size_t size, uint8_t *out, std::size_t room)
{
    z_stream z{};
    if (inflateInit2(&z, 16 + MAX_WBITS) != Z_OK)
        return 0;
    z.next_in = const_cast<Bytef *>(gz);
    z.avail_in = static_cast<uInt>(size);
    z.next_out = out;
    z.avail_out = static_cast<uInt>(room);
    int status = Z_OK;
    while (status == Z_OK && z.avail_out > 0 && z.avail_in > 0)
        status = inflate(&z, Z_SYNC_FLUSH);
    const std::size_t produced = room - z.avail_out;
    inflateEnd(&z);
    return produced;
}

} // namespace

NiftiMagic find_nifti_magic(const uint8_t *head, uint64_t size)
{
    if (!head)
        return NiftiMagic::none;
    if (size >= 2 && head[0] == 0x1f && head[1] == 0x8b) {
        std::array<uint8_t, kBytesNeeded> header{};
        // Enough compressed input for any header; a larger head adds nothing.
        const std::size_t input = size < 65536 ? static_cast<std::size_t>(size) : 65536;
        const std::size_t got = inflate_start(head, input, header.data(), header.size());
        return magic_in_plain(header.data(), got);
    }
    return magic_in_plain(head, static_cast<std::size_t>(size));
}

} // namespace arbor::importer_vtk
