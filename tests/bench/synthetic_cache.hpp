// synthetic_cache.hpp - the synthetic fields of the TTK anchor (blobs_N,
// blobsnoise_N, random_N), made by the reference generator
// ../shared/reference/ttk/synthetic/gen_volumes.py into a cache folder of the
// build tree, each with a detached NRRD header so that the NRRD importer (and
// `arbor info`) opens it.  Files are regenerated only when missing or of the
// wrong size (an interrupted run).
#pragma once

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

namespace arbor::bench {

enum class SyntheticKind { Blobs, BlobsNoise, Random };

struct SyntheticField {
    SyntheticKind kind;
    int64_t size; // N: N^3 float32 voxels

    std::string name() const; // "blobs_128", "blobsnoise_128", "random_128"
};

struct SyntheticSetup {
    std::filesystem::path cache_dir; // e.g. build/bench-data
    std::filesystem::path generator; // gen_volumes.py
    std::string python;              // an interpreter with numpy
    // Where the shipped generator outputs live (reference/ttk/synthetic): a
    // field found there with the right size is used as is, since those are
    // the exact files TTK ran on (regenerated floats can differ in the last
    // bit across numpy versions).
    std::filesystem::path shipped_dir;
};

// The .nhdr to import for `field`, generating it first when needed.  Throws
// std::runtime_error when the generator fails.
std::filesystem::path synthetic_header(const SyntheticSetup &setup, const SyntheticField &field);

// Generates every missing field of `fields` with as few generator runs as
// possible (blobs_N and blobsnoise_N come from one run).  Prints what it does
// on stderr; generating the 512^3 fields takes a few minutes and ~4 GB.
void prepare_synthetic(const SyntheticSetup &setup, const std::vector<SyntheticField> &fields);

} // namespace arbor::bench
