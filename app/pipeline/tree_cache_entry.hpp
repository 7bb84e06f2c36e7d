// tree_cache_entry.hpp - one entry of the contour-tree cache on disk: its file
// format, the writer, and a reader that trusts nothing it reads.
//
// An entry holds a whole topology::ContourTree, segmentation included, in
// host byte order:
//   TreeEntryHeader (144 bytes): magic, format version, byte-order mark, the
//     cache key, vertex, node and arc counts, and every array's length;
//   the arrays back to back in TreeArray order (the 4-byte arrays first, so
//     each starts aligned);
//   the XXH3-128 checksum of everything before it (canonical form, 16 bytes).
// The reader checks each header field, then the sizes against the file's own
// size before it allocates anything (no file can make it allocate more than
// the file holds), reads the arrays straight into the tree's memory in large
// chunks (hashing each chunk while it is in cache, polling for cancellation
// between chunks), compares the checksum, and finally checks the tree's
// indices (tree_check.hpp).
#pragma once

#include "topology/contour_tree.hpp"

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <stop_token>
#include <string>

namespace arbor::pipeline {

// Bump whenever the layout below or the meaning of a stored tree changes (a
// different tie-break, node order or segmentation rule in the topology core):
// the version is part of every key, so old entries simply stop matching.
inline constexpr uint32_t kTreeCacheFormatVersion = 1;

// Keys are XXH3-128 digests written as lowercase hex.
inline constexpr std::size_t kTreeCacheKeyLength = 32;

inline constexpr char kTreeEntryMagic[8] = {'A', 'r', 'b', 'o', 'r', 'C', 'T', '\n'};
inline constexpr uint32_t kTreeEntryByteOrder = 0x01020304u;
inline constexpr std::size_t kTreeEntryChecksumBytes = 16;

// The arrays of an entry, in file order.
enum TreeArray : std::size_t {
    kNodeVertex,
    kArcLo,
    kArcHi,
    kNodeArcOffsets,
    kNodeArcs,
    kVertexArc,
    kNodeUp,
    kNodeDown,
    kNodeKind,
    kTreeArrayCount
};

// Name of an array as in topology::ContourTree, for messages.
const char *tree_array_name(TreeArray array);

struct TreeEntryHeader {
    char magic[8];
    uint32_t version;
    uint32_t byte_order; // kTreeEntryByteOrder as written by the writer
    char key[kTreeCacheKeyLength];
    uint64_t vertex_count;
    uint64_t node_count;
    uint64_t arc_count;
    uint64_t lengths[kTreeArrayCount]; // elements, in TreeArray order
};
static_assert(sizeof(TreeEntryHeader) == 144, "the header is written as is: no padding");

// Size in bytes of the entry file for `tree`.
uint64_t tree_entry_bytes(const topology::ContourTree &tree);

// Writes `tree` under `key` (kTreeCacheKeyLength characters) to `file`
// atomically (AtomicFile).  Writes what it is given: callers check the tree
// first (TreeCache::store does).  Throws std::runtime_error when the file
// cannot be written.
void write_tree_entry(const std::filesystem::path &file, const std::string &key,
                      const topology::ContourTree &tree);

struct TreeEntryRead {
    enum class Status {
        Loaded,    // `tree` is the entry's tree
        Rejected,  // the entry is unusable; `why_not` says why
        Cancelled, // `stop` was requested before the read finished
    };
    Status status = Status::Rejected;
    topology::ContourTree tree;
    std::string why_not;
};

// Reads the entry open on `fd` (from its start), which must hold the tree of
// a volume of `vertex_count` voxels with key `key`.
TreeEntryRead read_tree_entry(int fd, const std::string &key, uint64_t vertex_count, std::stop_token stop = {});

} // namespace arbor::pipeline
