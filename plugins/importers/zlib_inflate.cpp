// zlib_inflate.cpp - see zlib_inflate.hpp.
#include "zlib_inflate.hpp"

#include <arbor/sdk/error.hpp>

#include <zlib.h>

#include <algorithm>
#include <string>
#include <vector>

namespace arbor::importers {

namespace {

// Owns a z_stream set up for inflation; windowBits 15 + 32 makes zlib detect
// a zlib or a gzip wrapper by itself.
class Inflater {
public:
    Inflater()
    {
        if (inflateInit2(&z_, 15 + 32) != Z_OK)
            sdk::fail(ARBOR_ERROR_OUT_OF_MEMORY, "zlib could not start decompressing");
    }
    ~Inflater() { inflateEnd(&z_); }
    Inflater(const Inflater &) = delete;
    Inflater &operator=(const Inflater &) = delete;
    z_stream &stream() { return z_; }

private:
    z_stream z_{};
};

constexpr std::size_t kInputChunk = std::size_t{1} << 20;
constexpr uint64_t kOutputChunk = uint64_t{4} << 20;
constexpr std::size_t kSkipChunk = 64 * 1024;

// The voxels are complete; when the stream ends right after them, finish it
// so that zlib checks its checksum (corruption that still decodes to the
// right length is caught there).  Streams that carry more data, or whose
// file ends before the checksum, are left as they are: the voxels are there.
void verify_stream_end(const DataFile &file, z_stream &z, std::vector<unsigned char> &input,
                       uint64_t input_at, uint64_t input_left, const std::string &what)
{
    unsigned char extra[4096];
    for (int round = 0; round < 16; ++round) {
        if (z.avail_in == 0) {
            if (input_left == 0)
                return;
            const std::size_t want =
                static_cast<std::size_t>(std::min<uint64_t>(input.size(), input_left));
            const std::size_t got = file.read_at(input_at, input.data(), want);
            if (got == 0)
                return;
            input_at += got;
            input_left = got < want ? 0 : input_left - got;
            z.next_in = input.data();
            z.avail_in = static_cast<uInt>(got);
        }
        z.next_out = extra;
        z.avail_out = sizeof extra;
        const int status = inflate(&z, Z_NO_FLUSH);
        if (status == Z_STREAM_END || z.avail_out < sizeof extra)
            return;
        if (status == Z_DATA_ERROR)
            sdk::fail(ARBOR_ERROR_FORMAT,
                      what + " is corrupt: " + (z.msg ? z.msg : "bad checksum"));
        if (status != Z_OK && status != Z_BUF_ERROR)
            return;
    }
}

} // namespace

void inflate_into(const DataFile &file, const CompressedRange &range, void *dest, uint64_t size,
                  const sdk::Task &task)
{
    const std::string what = std::string("the ") + range.format + " data of " + file.name();
    const uint64_t target = range.skip + size;
    const auto ended_early = [&](uint64_t decoded) {
        sdk::fail(ARBOR_ERROR_FORMAT,
                  what + " ends after " +
                      std::to_string(decoded > range.skip ? decoded - range.skip : 0) +
                      " decoded bytes of voxel data, " + range.needs + " " + std::to_string(size));
    };
    if (range.offset > file.size())
        ended_early(0);
    uint64_t input_left = file.size() - range.offset;
    if (range.size && *range.size < input_left)
        input_left = *range.size;
    uint64_t input_at = range.offset;

    Inflater inflater;
    z_stream &z = inflater.stream();
    std::vector<unsigned char> input(static_cast<std::size_t>(
        std::min<uint64_t>(kInputChunk, std::max<uint64_t>(input_left, 1))));
    std::vector<unsigned char> discard(range.skip > 0 ? kSkipChunk : 0);
    auto *out = static_cast<unsigned char *>(dest);
    uint64_t decoded = 0;

    while (decoded < target) {
        if (z.avail_in == 0) {
            if (input_left == 0)
                ended_early(decoded);
            const std::size_t want =
                static_cast<std::size_t>(std::min<uint64_t>(input.size(), input_left));
            const std::size_t got = file.read_at(input_at, input.data(), want);
            if (got == 0)
                ended_early(decoded);
            input_at += got;
            input_left = got < want ? 0 : input_left - got;
            z.next_in = input.data();
            z.avail_in = static_cast<uInt>(got);
        }
        unsigned char *window;
        uint64_t window_size;
        if (decoded < range.skip) {
            window = discard.data();
            window_size = std::min<uint64_t>(discard.size(), range.skip - decoded);
        } else {
            window = out + (decoded - range.skip);
            window_size = std::min<uint64_t>(kOutputChunk, target - decoded);
        }
        z.next_out = window;
        z.avail_out = static_cast<uInt>(window_size);
        const int status = inflate(&z, Z_NO_FLUSH);
        decoded += window_size - z.avail_out;
        if (status == Z_STREAM_END) {
            // Another gzip member may follow (concatenated streams).
            if (decoded < target) {
                if (z.avail_in == 0 && input_left == 0)
                    ended_early(decoded);
                if (inflateReset(&z) != Z_OK)
                    sdk::fail(ARBOR_ERROR_INTERNAL, "zlib could not restart on " + file.name());
            }
        } else if (status == Z_BUF_ERROR) {
            if (z.avail_in != 0)
                sdk::fail(ARBOR_ERROR_INTERNAL, "zlib made no progress on " + file.name());
        } else if (status == Z_MEM_ERROR) {
            sdk::fail(ARBOR_ERROR_OUT_OF_MEMORY,
                      "zlib ran out of memory while decoding " + file.name());
        } else if (status != Z_OK) {
            const uint64_t voxel_bytes = decoded > range.skip ? decoded - range.skip : 0;
            sdk::fail(ARBOR_ERROR_FORMAT,
                      what + " is corrupt after " + std::to_string(voxel_bytes) +
                          " decoded bytes of voxel data (zlib: " +
                          (z.msg ? std::string(z.msg) : "error " + std::to_string(status)) + ")");
        }
        task.progress(static_cast<double>(decoded) / static_cast<double>(target), "decompressing");
    }
    verify_stream_end(file, inflater.stream(), input, input_at, input_left, what);
}

} // namespace arbor::importers
