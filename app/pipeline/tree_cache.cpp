#include "tree_cache.hpp"

#include "tree_cache_entry.hpp"
#include "tree_check.hpp"

#include <xxhash.h>

#include <algorithm>
#include <cerrno>
#include <charconv>
#include <chrono>
#include <cstdlib>
#include <cstring>
#include <stdexcept>
#include <string_view>
#include <vector>

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

namespace arbor::pipeline {

namespace fs = std::filesystem;

namespace {

constexpr uint64_t kDefaultMaxBytes = uint64_t{4} << 30;
constexpr std::string_view kEntrySuffix = ".tree";
constexpr std::string_view kPartialInfix = ".tree.partial-";
// A temporary file this old is left over from a writer that died (a store
// takes seconds): it is deleted, so crashes cannot fill the disk unbounded.
constexpr auto kStalePartialAge = std::chrono::hours(1);

bool is_key(std::string_view s)
{
    return s.size() == kTreeCacheKeyLength &&
           std::all_of(s.begin(), s.end(), [](char c) { return (c >= '0' && c <= '9') || (c >= 'a' && c <= 'f'); });
}

void require_key(const std::string &key)
{
    if (!is_key(key))
        throw std::invalid_argument("\"" + key + "\" is not a tree cache key (" +
                                    std::to_string(kTreeCacheKeyLength) + " lowercase hex digits)");
}

// Entries and temporary files are named after their key.
bool is_entry_name(std::string_view name)
{
    return name.size() == kTreeCacheKeyLength + kEntrySuffix.size() && name.ends_with(kEntrySuffix) &&
           is_key(name.substr(0, kTreeCacheKeyLength));
}

bool is_partial_name(std::string_view name)
{
    return name.size() > kTreeCacheKeyLength + kPartialInfix.size() &&
           name.substr(kTreeCacheKeyLength, kPartialInfix.size()) == kPartialInfix &&
           is_key(name.substr(0, kTreeCacheKeyLength));
}

const char *environment(const char *name)
{
    const char *value = std::getenv(name);
    return value && *value ? value : nullptr;
}

class FileDescriptor {
public:
    explicit FileDescriptor(int fd) : fd_(fd) {}
    ~FileDescriptor()
    {
        if (fd_ >= 0)
            ::close(fd_);
    }
    FileDescriptor(const FileDescriptor &) = delete;
    FileDescriptor &operator=(const FileDescriptor &) = delete;
    int get() const { return fd_; }

private:
    int fd_;
};

// Deletes the unusable entry `file` that was opened as `opened`, unless a
// writer has replaced it with a new file since; says what happened.
std::string delete_entry(const fs::path &file, const struct stat &opened)
{
    struct stat now;
    if (::stat(file.c_str(), &now) != 0)
        return "already gone";
    if (now.st_dev != opened.st_dev || now.st_ino != opened.st_ino)
        return "kept: a new entry has replaced it meanwhile";
    if (::unlink(file.c_str()) != 0 && errno != ENOENT)
        return std::string("could not delete it: ") + std::strerror(errno);
    return "deleted";
}

} // namespace

std::string tree_cache_key(const Volume &volume)
{
    if (volume.empty() || volume.voxel_count() <= 0)
        throw std::invalid_argument("an empty volume has no tree cache key");
    // What the tree is a function of, besides the voxel bytes.  Fixed-size
    // fields without padding, so the same field hashes the same everywhere.
    struct Field {
        char domain[16];
        uint32_t format_version;
        uint32_t voxel_type;
        int64_t dims[3];
    } field;
    static_assert(sizeof(Field) == 48);
    std::memset(&field, 0, sizeof field);
    std::memcpy(field.domain, "arbor tree", 10);
    field.format_version = kTreeCacheFormatVersion;
    field.voxel_type = volume.type();
    for (int i = 0; i < 3; ++i)
        field.dims[i] = volume.geometry().dims[i];

    XXH3_state_t *state = XXH3_createState();
    if (!state)
        throw std::bad_alloc();
    XXH3_128bits_reset(state);
    XXH3_128bits_update(state, &field, sizeof field);
    XXH3_128bits_update(state, volume.data(), volume.byte_size());
    const XXH128_hash_t hash = XXH3_128bits_digest(state);
    XXH3_freeState(state);

    XXH128_canonical_t canonical;
    XXH128_canonicalFromHash(&canonical, hash);
    static constexpr char kHex[] = "0123456789abcdef";
    std::string key;
    key.reserve(kTreeCacheKeyLength);
    for (const unsigned char byte : canonical.digest) {
        key += kHex[byte >> 4];
        key += kHex[byte & 15];
    }
    return key;
}

TreeCache::TreeCache(fs::path folder, uint64_t max_bytes) : folder_(std::move(folder)), max_bytes_(max_bytes)
{
    if (folder_.empty())
        throw std::invalid_argument("the tree cache needs a folder");
}

fs::path TreeCache::default_folder()
{
    if (const char *dir = environment("ARBOR_CACHE_DIR"))
        return dir;
    const fs::path tail = fs::path("arbor") / "contour-trees";
    if (const char *xdg = environment("XDG_CACHE_HOME"); xdg && fs::path(xdg).is_absolute())
        return xdg / tail;
    if (const char *home = environment("HOME"))
        return fs::path(home) / ".cache" / tail;
    throw std::runtime_error("no folder for the tree cache: set ARBOR_CACHE_DIR, XDG_CACHE_HOME or HOME");
}

uint64_t TreeCache::default_max_bytes()
{
    const char *text = environment("ARBOR_CACHE_MAX_MB");
    if (!text)
        return kDefaultMaxBytes;
    const std::string_view s(text);
    uint64_t mib = 0;
    const auto [end, error] = std::from_chars(s.data(), s.data() + s.size(), mib);
    if (error != std::errc() || end != s.data() + s.size() || mib > (UINT64_MAX >> 20))
        throw std::invalid_argument("ARBOR_CACHE_MAX_MB must be a whole number of mebibytes, not \"" +
                                    std::string(s) + "\"");
    return mib << 20;
}

fs::path TreeCache::entry_path(const std::string &key) const
{
    require_key(key);
    return folder_ / (key + std::string(kEntrySuffix));
}

std::optional<topology::ContourTree> TreeCache::load(const std::string &key, uint64_t vertex_count,
                                                     std::string *why_not, std::stop_token stop) const
{
    const fs::path file = entry_path(key);
    const auto fail = [&](std::string why) -> std::optional<topology::ContourTree> {
        if (why_not)
            *why_not = std::move(why);
        return std::nullopt;
    };
    const FileDescriptor fd(::open(file.c_str(), O_RDONLY | O_CLOEXEC));
    if (fd.get() < 0) {
        if (errno == ENOENT || errno == ENOTDIR)
            return fail("not in the cache");
        return fail("cannot open the cached tree " + file.string() + ": " + std::strerror(errno));
    }
    struct stat opened;
    if (::fstat(fd.get(), &opened) != 0)
        return fail("cannot inspect the cached tree " + file.string() + ": " + std::strerror(errno));
    if (!S_ISREG(opened.st_mode))
        return fail(file.string() + " is not a regular file; left alone");

    TreeEntryRead read = read_tree_entry(fd.get(), key, vertex_count, std::move(stop));
    switch (read.status) {
    case TreeEntryRead::Status::Loaded:
        ::futimens(fd.get(), nullptr); // recently used; a failure only ages the entry
        if (why_not)
            why_not->clear();
        return std::move(read.tree);
    case TreeEntryRead::Status::Cancelled:
        return fail("cancelled");
    case TreeEntryRead::Status::Rejected:
        break;
    }
    return fail("unusable cached tree " + file.string() + ": " + read.why_not + " (" + delete_entry(file, opened) +
                ")");
}

bool TreeCache::store(const std::string &key, const topology::ContourTree &tree)
{
    const fs::path file = entry_path(key);
    if (std::string defect = find_tree_defect(tree, tree.vertex_arc.size()); !defect.empty())
        throw std::invalid_argument("refusing to cache an inconsistent contour tree: " + defect);
    std::error_code ec;
    if (tree_entry_bytes(tree) > max_bytes_) {
        // Not kept at all, and an older copy (as large) must not linger.
        fs::remove(file, ec);
        evict({});
        return false;
    }
    fs::create_directories(folder_, ec);
    if (ec)
        throw std::runtime_error("cannot create the tree cache folder " + folder_.string() + ": " + ec.message());
    write_tree_entry(file, key, tree);
    evict(file);
    return true;
}

void TreeCache::evict(const fs::path &keep) const
{
    struct Entry {
        fs::path path;
        uint64_t bytes;
        fs::file_time_type used;
    };
    std::vector<Entry> entries;
    uint64_t total = 0;
    const auto now = fs::file_time_type::clock::now();
    std::error_code ec;
    for (fs::directory_iterator it(folder_, ec), end; !ec && it != end; it.increment(ec)) {
        const std::string name = it->path().filename().string();
        const bool entry = is_entry_name(name);
        if (!entry && !is_partial_name(name))
            continue; // not ours
        std::error_code item;
        if (!it->is_regular_file(item))
            continue;
        const fs::file_time_type used = it->last_write_time(item);
        const uint64_t bytes = it->file_size(item);
        if (item)
            continue; // deleted meanwhile
        if (!entry) {
            if (now - used > kStalePartialAge)
                fs::remove(it->path(), item);
            continue;
        }
        entries.push_back({it->path(), bytes, used});
        total += bytes;
    }
    std::sort(entries.begin(), entries.end(), [](const Entry &a, const Entry &b) {
        return a.used != b.used ? a.used < b.used : a.path < b.path;
    });
    for (const Entry &e : entries) {
        if (total <= max_bytes_)
            break;
        if (e.path == keep)
            continue;
        std::error_code item;
        fs::remove(e.path, item); // already gone (another process evicting) counts as removed
        if (!item)
            total -= e.bytes;
    }
}

} // namespace arbor::pipeline
