#include "tree_cache_entry.hpp"

#include "tree_check.hpp"

#include "core/atomic_file.hpp"

#include <xxhash.h>

#include <algorithm>
#include <array>
#include <cerrno>
#include <cstring>
#include <memory>
#include <stdexcept>
#include <string_view>
#include <type_traits>

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

namespace arbor::pipeline {

namespace {

using topology::ContourTree;

static_assert(sizeof(topology::NodeKind) == 1, "node kinds are stored as one byte each");

constexpr std::array<unsigned, kTreeArrayCount> kElementBytes{4, 4, 4, 4, 4, 4, 1, 1, 1};

// Large reads: one system call per 8 MiB, and cancellation is noticed within
// one chunk's read (milliseconds from the page cache, well under a second
// from a slow disk).
constexpr std::size_t kChunkBytes = std::size_t{8} << 20;

template <class Byte>
struct ArrayBytes {
    Byte *data;
    uint64_t bytes;
};

// The tree's arrays in file order, as bytes (const for writing, mutable for
// reading): the one place that ties TreeArray to ContourTree's members.
template <class Tree>
auto array_bytes(Tree &t)
{
    using Byte = std::conditional_t<std::is_const_v<Tree>, const std::byte, std::byte>;
    const auto bytes = [](auto &v) {
        return ArrayBytes<Byte>{reinterpret_cast<Byte *>(v.data()), uint64_t{v.size()} * sizeof(v[0])};
    };
    return std::array<ArrayBytes<Byte>, kTreeArrayCount>{
        bytes(t.node_vertex), bytes(t.arc_lo),   bytes(t.arc_hi),    bytes(t.node_arc_offsets), bytes(t.node_arcs),
        bytes(t.vertex_arc),  bytes(t.node_up),  bytes(t.node_down), bytes(t.node_kind)};
}

// The array lengths the counts call for.
std::array<uint64_t, kTreeArrayCount> expected_lengths(uint64_t vertices, uint64_t nodes, uint64_t arcs)
{
    std::array<uint64_t, kTreeArrayCount> n{};
    n[kNodeVertex] = n[kNodeUp] = n[kNodeDown] = n[kNodeKind] = nodes;
    n[kArcLo] = n[kArcHi] = arcs;
    n[kNodeArcOffsets] = nodes + 1;
    n[kNodeArcs] = 2 * arcs;
    n[kVertexArc] = vertices;
    return n;
}

struct StateFree {
    void operator()(XXH3_state_t *s) const { XXH3_freeState(s); }
};
using HashState = std::unique_ptr<XXH3_state_t, StateFree>;

HashState new_hash_state()
{
    HashState state(XXH3_createState());
    if (!state || XXH3_128bits_reset(state.get()) != XXH_OK)
        throw std::bad_alloc();
    return state;
}

std::string str(uint64_t v)
{
    return std::to_string(v);
}

// Reads exactly `bytes` into `dst` in chunks, hashing each one and polling
// `stop` between them.
class ChunkReader {
public:
    enum class Result { Ok, Short, Failed, Cancelled };

    ChunkReader(int fd, XXH3_state_t *hash, std::stop_token stop) : fd_(fd), hash_(hash), stop_(std::move(stop)) {}

    Result read(void *dst, uint64_t bytes)
    {
        auto *p = static_cast<std::byte *>(dst);
        while (bytes > 0) {
            if (stop_.stop_requested())
                return Result::Cancelled;
            const std::size_t want = static_cast<std::size_t>(std::min<uint64_t>(bytes, kChunkBytes));
            std::size_t got = 0;
            while (got < want) {
                const ssize_t r = ::read(fd_, p + got, want - got);
                if (r < 0 && errno == EINTR)
                    continue;
                if (r < 0) {
                    error_ = errno;
                    return Result::Failed;
                }
                if (r == 0)
                    return Result::Short;
                got += static_cast<std::size_t>(r);
            }
            if (hash_)
                XXH3_128bits_update(hash_, p, want);
            p += want;
            bytes -= want;
        }
        return Result::Ok;
    }

    int error() const { return error_; }

private:
    int fd_;
    XXH3_state_t *hash_;
    std::stop_token stop_;
    int error_ = 0;
};

TreeEntryRead rejected(std::string why)
{
    TreeEntryRead r;
    r.status = TreeEntryRead::Status::Rejected;
    r.why_not = std::move(why);
    return r;
}

// Everything about the header that can be checked without the arrays; empty
// when it describes a file of exactly `file_bytes` bytes.
std::string check_header(const TreeEntryHeader &h, const std::string &key, uint64_t vertex_count,
                         uint64_t file_bytes)
{
    if (std::memcmp(h.magic, kTreeEntryMagic, sizeof h.magic) != 0)
        return "not a contour-tree cache entry (wrong magic)";
    if (h.byte_order != kTreeEntryByteOrder)
        return h.byte_order == __builtin_bswap32(kTreeEntryByteOrder)
                   ? "written on a machine of the other byte order"
                   : "damaged header (byte-order mark " + str(h.byte_order) + ")";
    if (h.version != kTreeCacheFormatVersion)
        return "format version " + str(h.version) + ", this build reads version " + str(kTreeCacheFormatVersion);
    if (std::string_view(h.key, sizeof h.key) != key)
        return "the entry holds key " + std::string(h.key, sizeof h.key) + ", not " + key;
    if (h.vertex_count != vertex_count)
        return "the entry is for " + str(h.vertex_count) + " vertices, the volume has " + str(vertex_count);
    // Vertex ids are 32-bit; a tree has at most one node per vertex and one arc
    // fewer than nodes.  This also bounds every length below, so the sums
    // cannot overflow.
    if (h.vertex_count == 0 || h.vertex_count > UINT32_MAX)
        return "the entry is for " + str(h.vertex_count) + " vertices (1 to " + str(UINT32_MAX) + " allowed)";
    if (h.node_count == 0 || h.node_count > h.vertex_count)
        return "the entry has " + str(h.node_count) + " nodes for " + str(h.vertex_count) + " vertices";
    if (h.arc_count + 1 != h.node_count)
        return "the entry has " + str(h.node_count) + " nodes and " + str(h.arc_count) +
               " arcs; a tree has one arc fewer than nodes";
    const auto expected = expected_lengths(h.vertex_count, h.node_count, h.arc_count);
    uint64_t total = sizeof(TreeEntryHeader) + kTreeEntryChecksumBytes;
    for (std::size_t i = 0; i < kTreeArrayCount; ++i) {
        if (h.lengths[i] != expected[i])
            return std::string("array ") + tree_array_name(static_cast<TreeArray>(i)) + " has length " +
                   str(h.lengths[i]) + " where the counts call for " + str(expected[i]);
        total += expected[i] * kElementBytes[i];
    }
    if (file_bytes < total)
        return "truncated: the header describes " + str(total) + " bytes, the file has " + str(file_bytes);
    if (file_bytes > total)
        return "the file has " + str(file_bytes - total) + " bytes more than the " + str(total) +
               " its header describes";
    return {};
}

std::string read_failure(ChunkReader::Result result, const ChunkReader &reader, const char *what)
{
    if (result == ChunkReader::Result::Short)
        return std::string("truncated while reading ") + what;
    return std::string("cannot read ") + what + ": " + std::strerror(reader.error());
}

} // namespace

const char *tree_array_name(TreeArray array)
{
    switch (array) {
    case kNodeVertex: return "node_vertex";
    case kArcLo: return "arc_lo";
    case kArcHi: return "arc_hi";
    case kNodeArcOffsets: return "node_arc_offsets";
    case kNodeArcs: return "node_arcs";
    case kVertexArc: return "vertex_arc";
    case kNodeUp: return "node_up";
    case kNodeDown: return "node_down";
    case kNodeKind: return "node_kind";
    case kTreeArrayCount: break;
    }
    return "?";
}

uint64_t tree_entry_bytes(const ContourTree &tree)
{
    uint64_t total = sizeof(TreeEntryHeader) + kTreeEntryChecksumBytes;
    for (const auto &a : array_bytes(tree))
        total += a.bytes;
    return total;
}

void write_tree_entry(const std::filesystem::path &file, const std::string &key, const ContourTree &tree)
{
    if (key.size() != kTreeCacheKeyLength)
        throw std::invalid_argument("a tree cache key has " + str(kTreeCacheKeyLength) + " characters, not " +
                                    str(key.size()));
    TreeEntryHeader h;
    std::memset(&h, 0, sizeof h);
    std::memcpy(h.magic, kTreeEntryMagic, sizeof h.magic);
    h.version = kTreeCacheFormatVersion;
    h.byte_order = kTreeEntryByteOrder;
    std::memcpy(h.key, key.data(), sizeof h.key);
    h.vertex_count = tree.vertex_arc.size();
    h.node_count = tree.node_count();
    h.arc_count = tree.arc_count();
    const auto arrays = array_bytes(tree);
    for (std::size_t i = 0; i < kTreeArrayCount; ++i)
        h.lengths[i] = arrays[i].bytes / kElementBytes[i];

    HashState hash = new_hash_state();
    AtomicFile out(file);
    XXH3_128bits_update(hash.get(), &h, sizeof h);
    out.write(&h, sizeof h);
    for (const auto &a : arrays) {
        XXH3_128bits_update(hash.get(), a.data, a.bytes);
        out.write(a.data, a.bytes);
    }
    XXH128_canonical_t sum;
    XXH128_canonicalFromHash(&sum, XXH3_128bits_digest(hash.get()));
    out.write(&sum, sizeof sum);
    out.commit();
}

TreeEntryRead read_tree_entry(int fd, const std::string &key, uint64_t vertex_count, std::stop_token stop)
{
    struct stat st;
    if (::fstat(fd, &st) != 0)
        return rejected(std::string("cannot inspect the file: ") + std::strerror(errno));
    const uint64_t file_bytes = static_cast<uint64_t>(st.st_size);
    if (file_bytes == 0)
        return rejected("empty file");
    if (file_bytes < sizeof(TreeEntryHeader) + kTreeEntryChecksumBytes)
        return rejected("truncated: " + str(file_bytes) + " bytes, less than a header and checksum (" +
                        str(sizeof(TreeEntryHeader) + kTreeEntryChecksumBytes) + ")");
    ::posix_fadvise(fd, 0, 0, POSIX_FADV_SEQUENTIAL);

    HashState hash = new_hash_state();
    ChunkReader reader(fd, hash.get(), stop);
    TreeEntryHeader h;
    ChunkReader::Result result = reader.read(&h, sizeof h);
    if (result == ChunkReader::Result::Cancelled)
        return {TreeEntryRead::Status::Cancelled, {}, "cancelled"};
    if (result != ChunkReader::Result::Ok)
        return rejected(read_failure(result, reader, "the header"));
    if (std::string why = check_header(h, key, vertex_count, file_bytes); !why.empty())
        return rejected(std::move(why));

    // Sizes now agree with the file: allocating them is bounded by its size.
    TreeEntryRead r;
    ContourTree &t = r.tree;
    t.node_vertex.resize(h.node_count);
    t.node_up.resize(h.node_count);
    t.node_down.resize(h.node_count);
    t.node_kind.resize(h.node_count);
    t.arc_lo.resize(h.arc_count);
    t.arc_hi.resize(h.arc_count);
    t.node_arc_offsets.resize(h.node_count + 1);
    t.node_arcs.resize(2 * h.arc_count);
    t.vertex_arc = topology::UninitializedBuffer<uint32_t>(h.vertex_count);
    const auto arrays = array_bytes(t);
    for (std::size_t i = 0; i < kTreeArrayCount; ++i) {
        result = reader.read(arrays[i].data, arrays[i].bytes);
        if (result == ChunkReader::Result::Cancelled)
            return {TreeEntryRead::Status::Cancelled, {}, "cancelled"};
        if (result != ChunkReader::Result::Ok)
            return rejected(read_failure(result, reader, tree_array_name(static_cast<TreeArray>(i))));
    }

    XXH128_canonical_t stored, computed;
    ChunkReader trailer(fd, nullptr, {});
    result = trailer.read(&stored, sizeof stored);
    if (result != ChunkReader::Result::Ok)
        return rejected(read_failure(result, trailer, "the checksum"));
    XXH128_canonicalFromHash(&computed, XXH3_128bits_digest(hash.get()));
    if (std::memcmp(&stored, &computed, sizeof stored) != 0)
        return rejected("checksum mismatch: the file is damaged");

    if (std::string defect = find_tree_defect(t, vertex_count); !defect.empty())
        return rejected("the stored tree is inconsistent: " + defect);
    r.status = TreeEntryRead::Status::Loaded;
    return r;
}

} // namespace arbor::pipeline
