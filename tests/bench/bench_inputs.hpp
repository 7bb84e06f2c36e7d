// bench_inputs.hpp - what the topology benchmark runs on: the built-in head
// phantom (clean and noisy), the shared real volumes that have a TTK anchor or
// reference pairs, the shared CT head DICOM stacked to 512 x 512 x 300 (a
// chest CT's size: no TTK anchor, TTK cannot build it in 20 GB), and the
// synthetic fields of the TTK anchor.
#pragma once

#include "synthetic_cache.hpp"

#include "io/phantom.hpp"

#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

namespace arbor::bench {

struct BenchInput {
    std::string name;    // also the TIMINGS.md input name where one exists
    int64_t max_dim = 0; // largest axis, for --max-size
    std::filesystem::path file;               // a shared real volume
    std::optional<SyntheticField> synthetic;  // a generated field
    std::optional<io::PhantomOptions> phantom;    // the head phantom
    // > 0: the file's slices stacked to this many, mirrored at each end
    // (0..n-1, n-1..0, 0..), so a real scan's noise and anatomy reach the
    // size of a chest or whole-body CT without resampling smoothing them.
    int64_t stacked_slices = 0;
};

struct CatalogueOptions {
    std::filesystem::path data_dir; // ../shared/data
    std::vector<int64_t> phantom_sizes{128, 256};
    double phantom_noise = 8.0;
    int phantom_blobs = 20;
    std::vector<int64_t> synthetic_sizes{64, 128, 256, 384, 512};
};

// Every input, smallest first within each group (phantom, real, synthetic).
std::vector<BenchInput> all_inputs(const CatalogueOptions &options);

// Inputs with no axis above `max_size` whose name contains one of `only`
// (all names when `only` is empty).
std::vector<BenchInput> select_inputs(const std::vector<BenchInput> &inputs, int64_t max_size,
                                      const std::vector<std::string> &only);

} // namespace arbor::bench
