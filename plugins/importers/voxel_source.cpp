// voxel_source.cpp - see voxel_source.hpp.
#include "voxel_source.hpp"

#include "ascii_values.hpp"
#include "byte_order.hpp"
#include "zlib_inflate.hpp"

#include <arbor/sdk/error.hpp>

#include <algorithm>
#include <vector>

namespace arbor::importers {

namespace {

// Large enough for fast reads, small enough to report progress and notice a
// cancel request several times a second.
constexpr uint64_t kReadChunk = uint64_t{4} << 20;

uint64_t skip_lines(const DataFile &file, uint64_t offset, uint64_t lines, const sdk::Task &task)
{
    std::vector<char> chunk(64 * 1024);
    uint64_t at = offset;
    uint64_t left = lines;
    while (left > 0) {
        const std::size_t got = file.read_at(at, chunk.data(), chunk.size());
        if (got == 0)
            sdk::fail(ARBOR_ERROR_FORMAT, file.name() + " ends before the " +
                                              std::to_string(lines) +
                                              " lines its header says to skip");
        for (std::size_t i = 0; i < got; ++i)
            if (chunk[i] == '\n' && --left == 0)
                return at + i + 1;
        at += got;
        task.throw_if_cancelled();
    }
    return at;
}

[[noreturn]] void fail_size(const DataFile &file, const VoxelSource &source, uint64_t start,
                            uint64_t bytes)
{
    const uint64_t available = file.size() > start ? file.size() - start : 0;
    const std::string where = start > 0 ? " from byte " + std::to_string(start) + " on" : "";
    const bool longer = available > bytes;
    sdk::fail(ARBOR_ERROR_FORMAT, file.name() + " has " + std::to_string(available) +
                                      " bytes of voxel data" + where + ", " + source.needs +
                                      (longer ? " exactly " : " ") + std::to_string(bytes) +
                                      (longer ? " (check dims, type and header offset)" : ""));
}

void read_raw(const DataFile &file, uint64_t start, unsigned char *dest, uint64_t bytes,
              uint32_t element_size, bool swap, const sdk::Task &task)
{
    for (uint64_t done = 0; done < bytes;) {
        const uint64_t want = std::min(kReadChunk, bytes - done);
        const std::size_t got =
            file.read_at(start + done, dest + done, static_cast<std::size_t>(want));
        if (got != want)
            sdk::fail(ARBOR_ERROR_IO, file.name() + " became shorter while it was read");
        if (swap)
            swap_byte_order(dest + done, want / element_size, element_size);
        done += want;
        task.progress(static_cast<double>(done) / static_cast<double>(bytes), "reading");
    }
}

void swap_in_chunks(unsigned char *data, uint64_t bytes, uint32_t element_size,
                    const sdk::Task &task)
{
    for (uint64_t done = 0; done < bytes;) {
        const uint64_t n = std::min(kReadChunk * 4, bytes - done);
        swap_byte_order(data + done, n / element_size, element_size);
        done += n;
        task.throw_if_cancelled();
    }
}

} // namespace

uint64_t raw_data_start(const DataFile &file, const VoxelSource &source, uint64_t bytes)
{
    if (source.at_end) {
        if (file.size() < bytes || file.size() - bytes < source.offset)
            fail_size(file, source, source.offset, bytes);
        return file.size() - bytes;
    }
    uint64_t start = 0;
    if (__builtin_add_overflow(source.offset, source.byte_skip, &start))
        fail_size(file, source, file.size(), bytes);
    if (start > file.size() || file.size() - start < bytes ||
        (source.exact_size && file.size() - start != bytes))
        fail_size(file, source, start, bytes);
    return start;
}

void check_data_fits(const VoxelSource &source, const VoxelGrid &grid)
{
    const std::optional<uint64_t> bytes = voxel_bytes(grid);
    if (!bytes)
        sdk::fail(ARBOR_ERROR_TOO_LARGE, grid_text(grid) + " voxels do not fit in memory");
    const DataFile file(source.file);
    if (source.encoding == VoxelEncoding::raw) {
        // Line skips only move the start further; check the most lenient case.
        VoxelSource lenient = source;
        lenient.exact_size = source.exact_size && source.line_skip == 0;
        raw_data_start(file, lenient, *bytes);
        return;
    }
    const uint64_t available = file.size() > source.offset ? file.size() - source.offset : 0;
    if (source.encoding == VoxelEncoding::ascii) {
        const uint64_t values = *bytes / arbor_voxel_size(grid.type);
        if (available / 2 + 1 < values)
            sdk::fail(ARBOR_ERROR_FORMAT, file.name() + " has " + std::to_string(available) +
                                              " bytes of text, too few for the " +
                                              std::to_string(values) + " values " + source.needs);
        return;
    }
    const uint64_t compressed = std::min(available, source.compressed_size.value_or(available));
    constexpr uint64_t kMaxDeflateRatio = 1032;
    if (compressed < (*bytes + source.byte_skip) / kMaxDeflateRatio)
        sdk::fail(ARBOR_ERROR_FORMAT,
                  file.name() + " has " + std::to_string(compressed) + " bytes of " +
                      source.compression + " data, which cannot expand to the " +
                      std::to_string(*bytes) + " bytes " + source.needs +
                      " (truncated or corrupt)");
}

void read_voxel_data(const VoxelSource &source, const VoxelGrid &grid, void *dest,
                     const sdk::Task &task)
{
    const std::optional<uint64_t> bytes = voxel_bytes(grid);
    if (!bytes)
        sdk::fail(ARBOR_ERROR_TOO_LARGE, grid_text(grid) + " voxels do not fit in memory");
    const uint32_t element_size = arbor_voxel_size(grid.type);
    const bool swap = element_size > 1 && needs_swap(source.byte_order);
    auto *out = static_cast<unsigned char *>(dest);

    DataFile file(source.file);
    VoxelSource at = source;
    if (source.line_skip > 0)
        at.offset = skip_lines(file, source.offset, source.line_skip, task);

    switch (source.encoding) {
    case VoxelEncoding::raw:
        read_raw(file, raw_data_start(file, at, *bytes), out, *bytes, element_size, swap, task);
        return;
    case VoxelEncoding::zlib: {
        CompressedRange range;
        range.offset = at.offset;
        range.size = source.compressed_size;
        range.skip = source.byte_skip;
        range.format = source.compression;
        range.needs = source.needs.c_str();
        inflate_into(file, range, out, *bytes, task);
        if (swap)
            swap_in_chunks(out, *bytes, element_size, task);
        return;
    }
    case VoxelEncoding::ascii: {
        uint64_t start = 0;
        if (__builtin_add_overflow(at.offset, source.byte_skip, &start))
            start = file.size();
        read_ascii_values(file, start, grid.type, out, *bytes / element_size, task);
        return;
    }
    }
}

} // namespace arbor::importers
