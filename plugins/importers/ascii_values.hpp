// ascii_values.hpp - voxel values written as text (NRRD "ascii" encoding,
// MetaImage BinaryData = False), parsed from a file in chunks straight into
// the host's buffer.
#pragma once

#include "data_file.hpp"

#include <arbor/sdk/task.hpp>
#include <arbor/volume.h>

#include <cstdint>

namespace arbor::importers {

// Reads `count` numbers separated by white space or commas from `offset` on
// and stores them as `type` in this machine's byte order.  Throws
// ARBOR_ERROR_FORMAT for a word that is not a number of that type, and when
// the file holds fewer than `count` numbers.  Text after them is ignored.
void read_ascii_values(const DataFile &file, uint64_t offset, arbor_voxel_type type, void *dest,
                       uint64_t count, const sdk::Task &task);

} // namespace arbor::importers
