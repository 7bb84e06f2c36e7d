// The contour-tree cache: keys follow the field's content, a stored tree comes
// back array for array, every kind of damaged or inconsistent entry is
// refused with a reason and deleted, the folder stays under its bound by
// dropping the least recently used entries, concurrent writers leave one whole
// entry, and the folder follows $ARBOR_CACHE_DIR and the XDG rules.
#include "pipeline/tree_cache.hpp"
#include "pipeline/tree_cache_entry.hpp"

#include "io/phantom.hpp"
#include "core/stopwatch.hpp"
#include "plugin_fixture.hpp"
#include "test_paths.hpp"
#include "topology/topology_pipeline.hpp"

#include <gtest/gtest.h>
#include <xxhash.h>

#include <atomic>
#include <cstddef>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <iostream>
#include <latch>
#include <optional>
#include <thread>

namespace arbor::pipeline {
namespace {

namespace fs = std::filesystem;
using topology::ContourTree;

Volume noisy_phantom(int64_t size, uint64_t seed)
{
    io::PhantomOptions options;
    options.size = size;
    options.noise_sigma = 25.0;
    options.seed = seed;
    return io::make_phantom(io::builtin_phantom("head"), options);
}

Volume copy_of(const Volume &v)
{
    Volume c = Volume::allocate(v.type(), v.geometry(), v.mapping(), v.byte_size());
    std::memcpy(c.data(), v.data(), v.byte_size());
    return c;
}

ContourTree tree_of(const Volume &v)
{
    return topology::compute_contour_tree(v).tree;
}

ContourTree clone(const ContourTree &t)
{
    ContourTree c;
    c.node_vertex = t.node_vertex;
    c.node_up = t.node_up;
    c.node_down = t.node_down;
    c.node_kind = t.node_kind;
    c.arc_lo = t.arc_lo;
    c.arc_hi = t.arc_hi;
    c.node_arc_offsets = t.node_arc_offsets;
    c.node_arcs = t.node_arcs;
    c.vertex_arc = topology::UninitializedBuffer<uint32_t>(t.vertex_arc.size());
    std::memcpy(c.vertex_arc.data(), t.vertex_arc.data(), t.vertex_arc.size() * sizeof(uint32_t));
    return c;
}

void expect_same_tree(const ContourTree &a, const ContourTree &b)
{
    EXPECT_EQ(a.node_vertex, b.node_vertex);
    EXPECT_EQ(a.node_up, b.node_up);
    EXPECT_EQ(a.node_down, b.node_down);
    EXPECT_EQ(a.node_kind, b.node_kind);
    EXPECT_EQ(a.arc_lo, b.arc_lo);
    EXPECT_EQ(a.arc_hi, b.arc_hi);
    EXPECT_EQ(a.node_arc_offsets, b.node_arc_offsets);
    EXPECT_EQ(a.node_arcs, b.node_arcs);
    ASSERT_EQ(a.vertex_arc.size(), b.vertex_arc.size());
    EXPECT_EQ(std::memcmp(a.vertex_arc.data(), b.vertex_arc.data(), a.vertex_arc.size() * sizeof(uint32_t)), 0);
}

std::string read_bytes(const fs::path &p)
{
    std::ifstream in(p, std::ios::binary);
    return std::string(std::istreambuf_iterator<char>(in), {});
}

void write_bytes(const fs::path &p, const std::string &bytes)
{
    std::ofstream out(p, std::ios::binary | std::ios::trunc);
    out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
}

// Recomputes the trailing checksum, so that a deliberate change is seen by
// the checks after it rather than by the checksum.
void reseal(std::string &bytes)
{
    const std::size_t body = bytes.size() - kTreeEntryChecksumBytes;
    XXH128_canonical_t sum;
    XXH128_canonicalFromHash(&sum, XXH3_128bits(bytes.data(), body));
    std::memcpy(bytes.data() + body, &sum, sizeof sum);
}

TreeEntryHeader header_of(const std::string &bytes)
{
    TreeEntryHeader h;
    std::memcpy(&h, bytes.data(), sizeof h);
    return h;
}

void set_header(std::string &bytes, const TreeEntryHeader &h)
{
    std::memcpy(bytes.data(), &h, sizeof h);
}

std::size_t tree_files(const fs::path &folder)
{
    std::size_t n = 0;
    for (const auto &e : fs::directory_iterator(folder))
        n += e.path().extension() == ".tree";
    return n;
}

// Sets (or unsets, with nullopt) an environment variable for one scope.
class ScopedEnv {
public:
    ScopedEnv(const char *name, std::optional<std::string> value) : name_(name)
    {
        if (const char *old = std::getenv(name))
            old_ = old;
        if (value)
            ::setenv(name, value->c_str(), 1);
        else
            ::unsetenv(name);
    }
    ~ScopedEnv()
    {
        if (old_)
            ::setenv(name_, old_->c_str(), 1);
        else
            ::unsetenv(name_);
    }
    ScopedEnv(const ScopedEnv &) = delete;
    ScopedEnv &operator=(const ScopedEnv &) = delete;

private:
    const char *name_;
    std::optional<std::string> old_;
};

constexpr uint64_t kLarge = uint64_t{1} << 40;

// ---------------------------------------------------------------- keys

TEST(TreeCacheKey, IsStableHexAndFollowsTheContent)
{
    const Volume a = noisy_phantom(24, 1);
    const std::string key = tree_cache_key(a);
    EXPECT_EQ(key.size(), kTreeCacheKeyLength);
    EXPECT_EQ(key.find_first_not_of("0123456789abcdef"), std::string::npos) << key;
    EXPECT_EQ(tree_cache_key(noisy_phantom(24, 1)), key) << "the same field must give the same key";

    Volume b = copy_of(a);
    b.as<uint16_t>()[1234] ^= 1;
    EXPECT_NE(tree_cache_key(b), key) << "one voxel changed";

    // The same bytes as another grid shape or voxel type are another field.
    Volume reshaped = copy_of(a);
    reshaped.geometry().dims = {a.geometry().dims[0] * 2, a.geometry().dims[1] / 2, a.geometry().dims[2]};
    EXPECT_NE(tree_cache_key(reshaped), key);
    Volume retyped = Volume::allocate(ARBOR_VOXEL_I16, a.geometry(), a.mapping(), a.byte_size());
    std::memcpy(retyped.data(), a.data(), a.byte_size());
    EXPECT_NE(tree_cache_key(retyped), key);

    // The value mapping and the geometry in space do not change the tree.
    Volume rescaled = copy_of(a);
    rescaled.mapping().scale = 2.0;
    rescaled.geometry().spacing = {0.5, 0.5, 3.0};
    EXPECT_EQ(tree_cache_key(rescaled), key);

    EXPECT_THROW(tree_cache_key(Volume{}), std::invalid_argument);
}

// A 512x512x275 int16 CT is hashed well within a tenth of a second (fastest of
// three, so a busy machine does not fail the test by chance).
TEST(TreeCacheKey, HashesALargeCtQuickly)
{
    Geometry g;
    g.dims = {512, 512, 275};
    Volume ct = Volume::allocate(ARBOR_VOXEL_I16, g, {}, uint64_t{1} << 30);
    int16_t *v = ct.as<int16_t>();
    for (int64_t i = 0; i < ct.voxel_count(); ++i)
        v[i] = static_cast<int16_t>((i * 2654435761u) >> 20);
    double best = 1e9;
    std::string key;
    for (int run = 0; run < 3; ++run) {
        Stopwatch watch;
        key = tree_cache_key(ct);
        best = std::min(best, watch.lap());
    }
    std::cout << "tree_cache_key of 512x512x275 i16 (" << ct.byte_size() / 1e6 << " MB): " << best * 1e3 << " ms\n";
    RecordProperty("hash_ms", std::to_string(best * 1e3));
    EXPECT_LT(best, 0.1);
}

// ---------------------------------------------------------------- round trips

TEST(TreeCache, MissesInAnEmptyOrAbsentFolder)
{
    const fs::path dir = test::scratch_dir();
    const Volume v = noisy_phantom(16, 1);
    std::string why;
    TreeCache absent(dir / "not" / "there", kLarge);
    EXPECT_FALSE(absent.load(tree_cache_key(v), v.voxel_count(), &why));
    EXPECT_EQ(why, "not in the cache");
    EXPECT_FALSE(fs::exists(dir / "not")) << "a load must not create the folder";

    TreeCache empty(dir, kLarge);
    why.clear();
    EXPECT_FALSE(empty.load(tree_cache_key(v), v.voxel_count(), &why));
    EXPECT_EQ(why, "not in the cache");
    EXPECT_FALSE(empty.load(tree_cache_key(v), v.voxel_count())) << "why_not is optional";
}

TEST(TreeCache, StoreThenLoadGivesTheSameTreeOnANoisyPhantom)
{
    const fs::path dir = test::scratch_dir() / "created" / "on" / "store";
    const Volume v = noisy_phantom(40, 7);
    const ContourTree tree = tree_of(v);
    ASSERT_GT(tree.node_count(), 100u) << "the noise should give a tree with many nodes";
    TreeCache cache(dir, kLarge);
    const std::string key = tree_cache_key(v);
    ASSERT_TRUE(cache.store(key, tree));
    EXPECT_TRUE(fs::is_regular_file(dir / (key + ".tree")));
    EXPECT_EQ(fs::file_size(dir / (key + ".tree")), tree_entry_bytes(tree));

    std::string why = "stale";
    const std::optional<ContourTree> loaded = cache.load(key, v.voxel_count(), &why);
    ASSERT_TRUE(loaded) << why;
    EXPECT_TRUE(why.empty());
    expect_same_tree(*loaded, tree);

    // Storing again replaces the entry with an equal one.
    ASSERT_TRUE(cache.store(key, tree));
    EXPECT_EQ(tree_files(dir), 1u);
    ASSERT_TRUE(cache.load(key, v.voxel_count()));
}

TEST(TreeCache, StoreThenLoadGivesTheSameTreeOnARealVolume)
{
    const Volume v = test::import(test::shared_data("walnut/walnut.nhdr"));
    ASSERT_EQ(v.voxel_count(), 128 * 96 * 114);
    Stopwatch watch;
    const topology::TopologyResult built = topology::compute_contour_tree(v);
    const double build_s = watch.lap();
    const std::string key = tree_cache_key(v);
    const double key_s = watch.lap();

    TreeCache cache(test::scratch_dir(), kLarge);
    ASSERT_TRUE(cache.store(key, built.tree));
    const double store_s = watch.lap();
    std::string why;
    const std::optional<ContourTree> loaded = cache.load(key, v.voxel_count(), &why);
    const double load_s = watch.lap();
    ASSERT_TRUE(loaded) << why;
    expect_same_tree(*loaded, built.tree);

    const uint64_t bytes = tree_entry_bytes(built.tree);
    std::cout << "walnut 128x96x114 u16, " << built.tree.node_count() << " nodes: build " << build_s * 1e3
              << " ms, key " << key_s * 1e3 << " ms, store " << store_s * 1e3 << " ms, load " << load_s * 1e3
              << " ms, entry " << bytes << " bytes (" << static_cast<double>(bytes) / v.voxel_count()
              << " per voxel)\n";
    RecordProperty("build_ms", std::to_string(build_s * 1e3));
    RecordProperty("load_ms", std::to_string(load_s * 1e3));
}

TEST(TreeCache, ADifferentVolumeMisses)
{
    TreeCache cache(test::scratch_dir(), kLarge);
    const Volume v = noisy_phantom(24, 3);
    ASSERT_TRUE(cache.store(tree_cache_key(v), tree_of(v)));
    Volume changed = copy_of(v);
    changed.as<uint16_t>()[v.voxel_count() / 2] += 1;
    std::string why;
    EXPECT_FALSE(cache.load(tree_cache_key(changed), changed.voxel_count(), &why));
    EXPECT_EQ(why, "not in the cache");
    EXPECT_TRUE(cache.load(tree_cache_key(v), v.voxel_count()));
}

TEST(TreeCache, RefusesMalformedKeysAndInconsistentTrees)
{
    const fs::path dir = test::scratch_dir();
    TreeCache cache(dir, kLarge);
    const Volume v = noisy_phantom(16, 1);
    const ContourTree tree = tree_of(v);
    for (const std::string bad : {"", "../../etc/passwd", "0123456789ABCDEF0123456789abcdef",
                                  "0123456789abcdef0123456789abcde", "0123456789abcdef0123456789abcdef0"}) {
        EXPECT_THROW(cache.load(bad, v.voxel_count()), std::invalid_argument) << bad;
        EXPECT_THROW(cache.store(bad, tree), std::invalid_argument) << bad;
    }
    ContourTree broken = clone(tree);
    broken.arc_hi[0] = static_cast<uint32_t>(broken.node_count());
    try {
        cache.store(tree_cache_key(v), broken);
        ADD_FAILURE() << "an inconsistent tree was stored";
    } catch (const std::invalid_argument &e) {
        EXPECT_NE(std::string(e.what()).find("arc 0 joins nodes"), std::string::npos) << e.what();
    }
    EXPECT_FALSE(fs::exists(dir / (tree_cache_key(v) + ".tree")));
}

TEST(TreeCache, CancelledLoadKeepsTheEntry)
{
    TreeCache cache(test::scratch_dir(), kLarge);
    const Volume v = noisy_phantom(24, 5);
    const std::string key = tree_cache_key(v);
    ASSERT_TRUE(cache.store(key, tree_of(v)));
    std::stop_source stop;
    stop.request_stop();
    std::string why;
    EXPECT_FALSE(cache.load(key, v.voxel_count(), &why, stop.get_token()));
    EXPECT_EQ(why, "cancelled");
    EXPECT_TRUE(fs::exists(cache.entry_path(key)));
    EXPECT_TRUE(cache.load(key, v.voxel_count(), &why, std::stop_source().get_token())) << why;
}

// ---------------------------------------------------------------- damaged entries

// One stored entry, and a way to put other bytes under its name and see the
// cache refuse them.
class DamagedEntry : public ::testing::Test {
protected:
    void SetUp() override
    {
        volume_ = noisy_phantom(24, 11);
        tree_ = tree_of(volume_);
        key_ = tree_cache_key(volume_);
        cache_.emplace(test::scratch_dir(), kLarge);
        ASSERT_TRUE(cache_->store(key_, tree_));
        file_ = cache_->entry_path(key_);
        good_ = read_bytes(file_);
        ASSERT_EQ(good_.size(), tree_entry_bytes(tree_));
    }

    // Loads `bytes` as the entry: expects a refusal that deletes the file, and
    // returns the reason.
    std::string refusal(const std::string &bytes, uint64_t vertex_count = 0)
    {
        write_bytes(file_, bytes);
        std::string why;
        const auto loaded = cache_->load(key_, vertex_count ? vertex_count : volume_.voxel_count(), &why);
        EXPECT_FALSE(loaded) << "damaged entry accepted";
        EXPECT_FALSE(fs::exists(file_)) << "damaged entry not deleted: " << why;
        EXPECT_NE(why.find("deleted"), std::string::npos) << why;
        return why;
    }

    // The same for a tree written with a valid checksum.
    std::string refusal(const ContourTree &tree)
    {
        write_tree_entry(file_, key_, tree);
        return refusal(read_bytes(file_));
    }

    std::size_t array_offset(TreeArray which) const
    {
        const TreeEntryHeader h = header_of(good_);
        const unsigned element[kTreeArrayCount] = {4, 4, 4, 4, 4, 4, 1, 1, 1};
        std::size_t at = sizeof(TreeEntryHeader);
        for (std::size_t i = 0; i < which; ++i)
            at += h.lengths[i] * element[i];
        return at;
    }

    Volume volume_;
    ContourTree tree_;
    std::string key_;
    std::optional<TreeCache> cache_;
    fs::path file_;
    std::string good_;
};

#define EXPECT_MENTIONS(text, part) EXPECT_NE((text).find(part), std::string::npos) << (text)

TEST_F(DamagedEntry, TheUndamagedEntryLoads)
{
    std::string why;
    const auto loaded = cache_->load(key_, volume_.voxel_count(), &why);
    ASSERT_TRUE(loaded) << why;
    expect_same_tree(*loaded, tree_);
}

TEST_F(DamagedEntry, ZeroLengthFile)
{
    EXPECT_MENTIONS(refusal(""), "empty file");
}

TEST_F(DamagedEntry, TruncatedAnywhere)
{
    const std::size_t header = sizeof(TreeEntryHeader);
    for (const std::size_t cut : {std::size_t{1}, std::size_t{10}, header - 1, header, header + 1,
                                  array_offset(kVertexArc) + 5, good_.size() / 2,
                                  good_.size() - kTreeEntryChecksumBytes, good_.size() - 1}) {
        SCOPED_TRACE("cut at " + std::to_string(cut) + " of " + std::to_string(good_.size()));
        EXPECT_MENTIONS(refusal(good_.substr(0, cut)), "truncated");
    }
}

TEST_F(DamagedEntry, TrailingBytes)
{
    EXPECT_MENTIONS(refusal(good_ + "x"), "bytes more than");
}

TEST_F(DamagedEntry, FlippedPayloadByte)
{
    for (const std::size_t at : {sizeof(TreeEntryHeader), array_offset(kArcHi) + 2, array_offset(kVertexArc) + 999,
                                 array_offset(kNodeKind), good_.size() - kTreeEntryChecksumBytes - 1,
                                 good_.size() - 1}) {
        SCOPED_TRACE("byte " + std::to_string(at));
        std::string bytes = good_;
        bytes[at] ^= 0x10;
        EXPECT_MENTIONS(refusal(bytes), "checksum mismatch");
    }
}

TEST_F(DamagedEntry, FlippedHeaderByte)
{
    // Every byte of the header matters: each flip is refused, by the field
    // check it breaks or else by the checksum.
    for (std::size_t at = 0; at < sizeof(TreeEntryHeader); ++at) {
        SCOPED_TRACE("byte " + std::to_string(at));
        std::string bytes = good_;
        bytes[at] ^= 0x01;
        refusal(bytes);
    }
    std::string bytes = good_;
    bytes[0] ^= 0x01;
    EXPECT_MENTIONS(refusal(bytes), "wrong magic");
    bytes = good_;
    bytes[offsetof(TreeEntryHeader, key)] ^= 0x01;
    EXPECT_MENTIONS(refusal(bytes), "holds key");
    bytes = good_;
    bytes[offsetof(TreeEntryHeader, node_count)] ^= 0x01;
    EXPECT_MENTIONS(refusal(bytes), "arcs; a tree has one arc fewer");
    bytes = good_;
    bytes[offsetof(TreeEntryHeader, lengths) + 8 * kNodeArcs] ^= 0x01;
    EXPECT_MENTIONS(refusal(bytes), "array node_arcs has length");
}

TEST_F(DamagedEntry, WrongVersionOrByteOrder)
{
    std::string bytes = good_;
    TreeEntryHeader h = header_of(bytes);
    h.version = kTreeCacheFormatVersion + 1;
    set_header(bytes, h);
    reseal(bytes);
    EXPECT_MENTIONS(refusal(bytes), "format version " + std::to_string(kTreeCacheFormatVersion + 1));

    bytes = good_;
    h = header_of(bytes);
    h.byte_order = __builtin_bswap32(h.byte_order);
    set_header(bytes, h);
    reseal(bytes);
    EXPECT_MENTIONS(refusal(bytes), "other byte order");
}

TEST_F(DamagedEntry, WrongKeyOrVertexCount)
{
    // An entry copied under another key's name.
    const Volume other = noisy_phantom(24, 12);
    const std::string other_key = tree_cache_key(other);
    write_bytes(cache_->entry_path(other_key), good_);
    std::string why;
    EXPECT_FALSE(cache_->load(other_key, other.voxel_count(), &why));
    EXPECT_MENTIONS(why, "holds key " + key_);
    EXPECT_FALSE(fs::exists(cache_->entry_path(other_key)));

    EXPECT_MENTIONS(refusal(good_, volume_.voxel_count() + 1), "vertices");
}

TEST_F(DamagedEntry, HugeCountsAreRefusedBeforeAllocating)
{
    // A header that claims a four-billion-vertex tree, consistent in itself:
    // only the file size tells, and it must tell before any allocation.
    std::string bytes = good_;
    TreeEntryHeader h = header_of(bytes);
    const uint64_t n = 4000000000u;
    h.vertex_count = h.node_count = n;
    h.arc_count = n - 1;
    for (std::size_t i = 0; i < kTreeArrayCount; ++i)
        h.lengths[i] = n;
    h.lengths[kArcLo] = h.lengths[kArcHi] = n - 1;
    h.lengths[kNodeArcOffsets] = n + 1;
    h.lengths[kNodeArcs] = 2 * (n - 1);
    set_header(bytes, h);
    reseal(bytes);
    EXPECT_MENTIONS(refusal(bytes, n), "truncated: the header describes");
}

TEST_F(DamagedEntry, ValidChecksumButIndicesOutOfRange)
{
    {
        ContourTree t = clone(tree_);
        t.vertex_arc[7] = static_cast<uint32_t>(t.arc_count());
        EXPECT_MENTIONS(refusal(t), "vertex 7 lies on arc " + std::to_string(t.arc_count()));
    }
    {
        ContourTree t = clone(tree_);
        t.arc_lo[3] = static_cast<uint32_t>(t.node_count() + 5);
        EXPECT_MENTIONS(refusal(t), "arc 3 joins nodes");
    }
    {
        ContourTree t = clone(tree_);
        std::swap(t.arc_lo[4], t.arc_hi[4]);
        EXPECT_MENTIONS(refusal(t), "arc 4 does not run upwards");
    }
    {
        ContourTree t = clone(tree_);
        t.node_arc_offsets[1] = t.node_arc_offsets[2] + 1;
        EXPECT_MENTIONS(refusal(t), "not monotone");
    }
    {
        ContourTree t = clone(tree_);
        t.node_arcs[0] = static_cast<uint32_t>(t.arc_count());
        EXPECT_MENTIONS(refusal(t), "node 0 lists arc");
    }
    {
        ContourTree t = clone(tree_);
        t.node_vertex[2] = static_cast<uint32_t>(volume_.voxel_count());
        EXPECT_MENTIONS(refusal(t), "node 2 lies on vertex");
    }
    {
        ContourTree t = clone(tree_);
        t.node_kind[0] = static_cast<topology::NodeKind>(200);
        EXPECT_MENTIONS(refusal(t), "node 0 has kind 200");
    }
    {
        ContourTree t = clone(tree_);
        t.node_up[0] += 1;
        EXPECT_MENTIONS(refusal(t), "node 0 has");
    }
}

TEST_F(DamagedEntry, NonEntryFileIsLeftAlone)
{
    fs::remove(file_);
    fs::create_directory(file_);
    std::string why;
    EXPECT_FALSE(cache_->load(key_, volume_.voxel_count(), &why));
    EXPECT_MENTIONS(why, "not a regular file");
    EXPECT_TRUE(fs::is_directory(file_));
}

// ---------------------------------------------------------------- the bound

// Four entries of distinct volumes, with modification times one minute apart
// in storing order (the oldest first).
struct FourEntries {
    fs::path dir;
    std::vector<std::string> keys;
    std::vector<uint64_t> bytes;
    std::vector<uint64_t> voxels;
    std::vector<ContourTree> trees;

    explicit FourEntries(const fs::path &folder) : dir(folder)
    {
        for (uint64_t seed = 1; seed <= 4; ++seed) {
            const Volume v = noisy_phantom(20, seed);
            keys.push_back(tree_cache_key(v));
            voxels.push_back(static_cast<uint64_t>(v.voxel_count()));
            trees.push_back(tree_of(v));
            bytes.push_back(tree_entry_bytes(trees.back()));
        }
    }
    fs::path file(std::size_t i) const { return dir / (keys[i] + ".tree"); }
    void age(std::size_t i, int minutes_ago) const
    {
        fs::last_write_time(file(i), fs::file_time_type::clock::now() - std::chrono::minutes(minutes_ago));
    }
};

TEST(TreeCacheBound, EvictsTheLeastRecentlyUsedFirst)
{
    const fs::path dir = test::scratch_dir();
    FourEntries e(dir);
    TreeCache unbounded(dir, kLarge);
    for (std::size_t i = 0; i < 3; ++i) {
        ASSERT_TRUE(unbounded.store(e.keys[i], e.trees[i]));
        e.age(i, 30 - 10 * static_cast<int>(i)); // 0 oldest, then 1, then 2
    }
    // Not ours: neither counted nor deleted, however large.
    write_bytes(dir / "notes.txt", std::string(1 << 20, 'n'));
    write_bytes(dir / "abc.tree", "not a key");
    // A leftover of a writer that died two hours ago, and one of a live one.
    write_bytes(dir / (e.keys[3] + ".tree.partial-1-0"), "stale");
    fs::last_write_time(dir / (e.keys[3] + ".tree.partial-1-0"),
                        fs::file_time_type::clock::now() - std::chrono::hours(2));
    write_bytes(dir / (e.keys[3] + ".tree.partial-2-0"), "live");

    // Using entry 0 makes entry 1 the least recently used.
    ASSERT_TRUE(unbounded.load(e.keys[0], e.voxels[0]));

    // Room for three entries: storing the fourth evicts entry 1 only.
    TreeCache three(dir, e.bytes[0] + e.bytes[2] + e.bytes[3] + 100);
    ASSERT_TRUE(three.store(e.keys[3], e.trees[3]));
    EXPECT_TRUE(fs::exists(e.file(0)));
    EXPECT_FALSE(fs::exists(e.file(1)));
    EXPECT_TRUE(fs::exists(e.file(2)));
    EXPECT_TRUE(fs::exists(e.file(3)));
    EXPECT_TRUE(fs::exists(dir / "notes.txt"));
    EXPECT_TRUE(fs::exists(dir / "abc.tree"));
    EXPECT_FALSE(fs::exists(dir / (e.keys[3] + ".tree.partial-1-0")));
    EXPECT_TRUE(fs::exists(dir / (e.keys[3] + ".tree.partial-2-0")));

    // Room for one: storing entry 2 again keeps it alone.
    e.age(0, 5);
    TreeCache one(dir, std::max(e.bytes[2], e.bytes[3]) + 100);
    ASSERT_TRUE(one.store(e.keys[2], e.trees[2]));
    EXPECT_FALSE(fs::exists(e.file(0)));
    EXPECT_TRUE(fs::exists(e.file(2)));
    EXPECT_FALSE(fs::exists(e.file(3)));
    EXPECT_TRUE(one.load(e.keys[2], e.voxels[2]));
}

TEST(TreeCacheBound, AnEntryLargerThanTheBoundIsNotKept)
{
    const fs::path dir = test::scratch_dir();
    FourEntries e(dir);
    // A small entry (a tiny volume) that fits, then a large one that does not.
    const Volume small = noisy_phantom(8, 1);
    const ContourTree small_tree = tree_of(small);
    const uint64_t bound = tree_entry_bytes(small_tree) + 100;
    ASSERT_LT(bound, e.bytes[0]);
    TreeCache cache(dir, bound);
    ASSERT_TRUE(cache.store(tree_cache_key(small), small_tree));
    EXPECT_FALSE(cache.store(e.keys[0], e.trees[0]));
    EXPECT_FALSE(fs::exists(e.file(0)));
    EXPECT_TRUE(cache.load(tree_cache_key(small), small.voxel_count()));

    // An old copy that no longer fits goes too.
    TreeCache unbounded(dir, kLarge);
    ASSERT_TRUE(unbounded.store(e.keys[1], e.trees[1]));
    EXPECT_FALSE(cache.store(e.keys[1], e.trees[1]));
    EXPECT_FALSE(fs::exists(e.file(1)));
}

TEST(TreeCacheBound, FolderStaysUnderTheBound)
{
    const fs::path dir = test::scratch_dir();
    FourEntries e(dir);
    const uint64_t bound = e.bytes[0] + e.bytes[1] + 100;
    TreeCache cache(dir, bound);
    for (int round = 0; round < 3; ++round)
        for (std::size_t i = 0; i < 4; ++i) {
            ASSERT_TRUE(cache.store(e.keys[i], e.trees[i]));
            uint64_t total = 0;
            for (const auto &f : fs::directory_iterator(dir))
                total += f.file_size();
            EXPECT_LE(total, bound);
            EXPECT_TRUE(fs::exists(e.file(i))) << "the entry just written must stay";
        }
}

// ---------------------------------------------------------------- concurrency

TEST(TreeCacheConcurrency, StoresOfOneKeyLeaveOneWholeEntry)
{
    const fs::path dir = test::scratch_dir();
    const Volume v = noisy_phantom(32, 21);
    const ContourTree tree = tree_of(v);
    const std::string key = tree_cache_key(v);
    constexpr int kRounds = 20;
    std::latch start(3);
    std::atomic<int> refusals{0}, write_failures{0};
    std::string refusal, write_failure;
    const auto writer = [&] {
        TreeCache cache(dir, kLarge); // as if in its own process
        start.arrive_and_wait();
        for (int i = 0; i < kRounds; ++i) {
            try {
                cache.store(key, tree);
            } catch (const std::exception &e) {
                if (write_failures++ == 0)
                    write_failure = e.what();
            }
        }
    };
    // A reader meanwhile sees either no entry or a whole one, never a torn one.
    const auto reader = [&] {
        const TreeCache cache(dir, kLarge);
        start.arrive_and_wait();
        for (int i = 0; i < 4 * kRounds; ++i) {
            std::string why;
            if (!cache.load(key, v.voxel_count(), &why) && why != "not in the cache" && refusals++ == 0)
                refusal = why;
        }
    };
    std::thread a(writer), b(writer), c(reader);
    a.join();
    b.join();
    c.join();
    EXPECT_EQ(write_failures.load(), 0) << write_failure;
    EXPECT_EQ(refusals.load(), 0) << refusal;
    std::vector<std::string> names;
    for (const auto &f : fs::directory_iterator(dir))
        names.push_back(f.path().filename().string());
    ASSERT_EQ(names.size(), 1u) << "temporary files left behind";
    EXPECT_EQ(names[0], key + ".tree");
    std::string why;
    const auto loaded = TreeCache(dir, kLarge).load(key, v.voxel_count(), &why);
    ASSERT_TRUE(loaded) << why;
    expect_same_tree(*loaded, tree);
}

// ---------------------------------------------------------------- configuration

TEST(TreeCacheConfiguration, FolderFollowsArborCacheDirThenXdgThenHome)
{
    ScopedEnv arbor("ARBOR_CACHE_DIR", "/srv/arbor-cache");
    ScopedEnv xdg("XDG_CACHE_HOME", "/xdg/cache");
    ScopedEnv home("HOME", "/home/someone");
    EXPECT_EQ(TreeCache::default_folder(), fs::path("/srv/arbor-cache"));
    {
        ScopedEnv unset("ARBOR_CACHE_DIR", std::nullopt);
        EXPECT_EQ(TreeCache::default_folder(), fs::path("/xdg/cache/arbor/contour-trees"));
    }
    {
        ScopedEnv empty("ARBOR_CACHE_DIR", "");
        EXPECT_EQ(TreeCache::default_folder(), fs::path("/xdg/cache/arbor/contour-trees"));
        // The XDG rules: an empty or relative XDG_CACHE_HOME is ignored.
        ScopedEnv xdg_empty("XDG_CACHE_HOME", "");
        EXPECT_EQ(TreeCache::default_folder(), fs::path("/home/someone/.cache/arbor/contour-trees"));
        ScopedEnv xdg_relative("XDG_CACHE_HOME", "relative/cache");
        EXPECT_EQ(TreeCache::default_folder(), fs::path("/home/someone/.cache/arbor/contour-trees"));
        ScopedEnv no_xdg("XDG_CACHE_HOME", std::nullopt);
        EXPECT_EQ(TreeCache::default_folder(), fs::path("/home/someone/.cache/arbor/contour-trees"));
        ScopedEnv no_home("HOME", std::nullopt);
        EXPECT_THROW(TreeCache::default_folder(), std::runtime_error);
    }
}

TEST(TreeCacheConfiguration, MaxBytesFollowsArborCacheMaxMb)
{
    {
        ScopedEnv unset("ARBOR_CACHE_MAX_MB", std::nullopt);
        EXPECT_EQ(TreeCache::default_max_bytes(), uint64_t{4} << 30);
    }
    {
        ScopedEnv set("ARBOR_CACHE_MAX_MB", "100");
        EXPECT_EQ(TreeCache::default_max_bytes(), uint64_t{100} << 20);
    }
    {
        ScopedEnv zero("ARBOR_CACHE_MAX_MB", "0");
        EXPECT_EQ(TreeCache::default_max_bytes(), 0u);
    }
    for (const char *bad : {"12abc", "-1", " 5", "1.5", "99999999999999999999", "17592186044416"}) {
        ScopedEnv set("ARBOR_CACHE_MAX_MB", bad);
        EXPECT_THROW(TreeCache::default_max_bytes(), std::invalid_argument) << bad;
    }
}

} // namespace
} // namespace arbor::pipeline
