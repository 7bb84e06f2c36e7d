// tree_cache.hpp - an on-disk cache of contour trees and their segmentation,
// keyed by the content of the volume they were computed on.
//
// Building the contour tree of a large CT takes tens of seconds; reading it
// back takes a fraction of one.  The pipeline asks the cache before building:
// tree_cache_key names the field (voxel type, dims, voxel bytes and the cache
// format version), TreeCache::load returns the stored tree or says why not,
// TreeCache::store keeps a computed one.  Entries are `<key>.tree` files
// (format: tree_cache_entry.hpp) in one folder, by default the XDG cache
// folder.  The folder is kept under a size bound by deleting the least
// recently used entries (by modification time; a hit touches its entry).  An
// entry is never trusted: a damaged or inconsistent one is reported, deleted,
// and the caller computes the tree again.  Several threads and processes may
// share one folder: entries appear whole (written to a temporary file, then
// renamed) and every delete tolerates a file that is already gone.
#pragma once

#include "core/volume.hpp"
#include "topology/contour_tree.hpp"

#include <cstdint>
#include <filesystem>
#include <optional>
#include <stop_token>
#include <string>

namespace arbor::pipeline {

// XXH3-128 of the cache format version, the voxel type, the dims and the
// voxel bytes, as 32 lowercase hex digits.  The value mapping and geometry
// are not part of it: the tree depends on the stored values alone.  Throws
// std::invalid_argument for an empty volume.
std::string tree_cache_key(const Volume &volume);

class TreeCache {
public:
    // Entries live in `folder` (created by the first store) and total at
    // most `max_bytes` after every store.
    TreeCache(std::filesystem::path folder, uint64_t max_bytes);

    // $ARBOR_CACHE_DIR if set, else $XDG_CACHE_HOME/arbor/contour-trees (when
    // absolute, as the XDG base directory rules require), else
    // $HOME/.cache/arbor/contour-trees.  Throws std::runtime_error when none
    // of them is set.
    static std::filesystem::path default_folder();
    // 4 GiB, or $ARBOR_CACHE_MAX_MB mebibytes when set.  Throws
    // std::invalid_argument when that is not a whole number.
    static uint64_t default_max_bytes();

    const std::filesystem::path &folder() const { return folder_; }
    uint64_t max_bytes() const { return max_bytes_; }
    std::filesystem::path entry_path(const std::string &key) const;

    // The tree stored under `key` for a volume of `vertex_count` voxels, or
    // nullopt with the reason in *why_not (when given): not in the cache, an
    // unusable entry (deleted, so the next store replaces it), or `stop`
    // requested during the read (the entry is kept; the caller, who owns the
    // stop source, should not take this for a miss).  A hit marks the entry
    // as recently used.  Throws std::invalid_argument for a malformed key.
    std::optional<topology::ContourTree> load(const std::string &key, uint64_t vertex_count,
                                              std::string *why_not = nullptr, std::stop_token stop = {}) const;

    // Stores `tree` under `key`, replacing any entry there, then deletes the
    // least recently used other entries until the folder is within
    // max_bytes.  An entry larger than max_bytes alone is not kept: returns
    // false then, true when stored.  Throws std::invalid_argument for a
    // malformed key or an inconsistent tree, std::runtime_error when the
    // folder cannot be created or written.
    bool store(const std::string &key, const topology::ContourTree &tree);

private:
    void evict(const std::filesystem::path &keep) const;

    std::filesystem::path folder_;
    uint64_t max_bytes_;
};

} // namespace arbor::pipeline
