// voxel_source.hpp - where and how a file stores its voxels (which file, at
// which offset, raw / zlib / ASCII, byte order), and the one routine that
// reads them into the host's buffer for all three importers.
#pragma once

#include "data_file.hpp"
#include "voxel_grid.hpp"

#include <arbor/sdk/task.hpp>

#include <bit>
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>

namespace arbor::importers {

enum class VoxelEncoding { raw, zlib, ascii };

struct VoxelSource {
    std::filesystem::path file;
    uint64_t offset = 0;    // where the data (or the lines to skip) begin
    uint64_t line_skip = 0; // text lines to skip from `offset` on
    // raw, ascii: file bytes to skip after the lines; zlib: decoded bytes.
    uint64_t byte_skip = 0;
    bool at_end = false; // raw: the voxels are the last bytes of the file
    // raw: the file must end right after the voxels.  Without a header the
    // file size is the only check of dims, type and offset given by hand.
    bool exact_size = false;
    VoxelEncoding encoding = VoxelEncoding::raw;
    std::optional<uint64_t> compressed_size; // zlib: stream length when known
    const char *compression = "gzip";        // zlib: "gzip" or "zlib", for messages
    std::endian byte_order = std::endian::little;
    // Who asks for the data, for messages: "the header needs", "the
    // parameters (dims 2 x 2 x 2, type u8) need".
    std::string needs = "the header needs";
};

// Offset of the first voxel byte of raw data in `file` (without line skip),
// after checking that the file holds all `bytes` of them (and no more, for
// exact_size); throws ARBOR_ERROR_FORMAT ("scan.raw has N bytes of voxel
// data, the header needs M") otherwise.  Reads nothing but the file size.
uint64_t raw_data_start(const DataFile &file, const VoxelSource &source, uint64_t bytes);

// Checks, before the host allocates anything, that the file can hold the
// grid's voxels: raw data must fit in what follows the offset, ASCII needs
// two characters a value, and zlib/gzip data cannot expand by more than
// deflate's maximum ratio of 1032:1.  So a few bytes claiming gigabytes are
// refused at the header.  Throws ARBOR_ERROR_FORMAT.
void check_data_fits(const VoxelSource &source, const VoxelGrid &grid);

// Fills `dest` with the grid's voxels in this machine's byte order.
void read_voxel_data(const VoxelSource &source, const VoxelGrid &grid, void *dest,
                     const sdk::Task &task);

} // namespace arbor::importers
