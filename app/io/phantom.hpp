// phantom.hpp - deterministic synthetic volumes built from a recipe.
//
// A recipe (JSON, see resources/phantoms/) lists ellipsoidal structures that
// are painted in order (later ones replace earlier ones with a smooth edge) or
// added as smooth bumps, plus optional small high-contrast blobs and Gaussian
// noise.  The same recipe, size, noise and seed give bit-identical volumes on
// every machine: the random numbers come from our own generator, not from the
// standard library's distributions, whose output is implementation-defined.
#pragma once

#include "core/volume.hpp"

#include <array>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

namespace arbor::io {

struct PhantomStructure {
    enum class Mode { Paint, Add };
    std::string name;
    Mode mode = Mode::Paint;
    std::array<double, 3> center{};
    std::array<double, 3> radii{};
    double edge = 0.0; // value at the boundary
    double peak = 0.0; // value at the centre (a dome in between)
};

struct PhantomRecipe {
    std::string name;
    std::string description;
    double field_of_view_mm = 200.0;
    arbor_voxel_type voxel_type = ARBOR_VOXEL_U16;
    std::string value_unit;
    double background = 0.0;
    double edge_voxels = 1.0;
    std::vector<PhantomStructure> structures;
    // Blobs: placed inside any of `blob_inside`, outside all of `blob_avoid`.
    std::vector<std::string> blob_inside, blob_avoid;
    double blob_radius_voxels = 1.0;
    double blob_value = 0.0;
};

struct PhantomOptions {
    int64_t size = 128;        // voxels along each axis
    double noise_sigma = 0.0;  // standard deviation of Gaussian noise, stored units
    int blobs = 0;             // number of small high-contrast blobs
    uint64_t seed = 1;
};

// Parses a recipe; throws std::invalid_argument naming the problem.
PhantomRecipe parse_phantom_recipe(std::string_view json);

// Names of the built-in phantoms ("head") and their recipes.
std::vector<std::string> builtin_phantom_kinds();
PhantomRecipe builtin_phantom(std::string_view kind); // throws for unknown kinds

// Throws std::invalid_argument for unusable options (size < 8 or > 1024...).
Volume make_phantom(const PhantomRecipe &recipe, const PhantomOptions &options);

// Ground truth for comparison studies: per voxel of a phantom of `size`^3,
// 1 + the index of the last structure whose ellipsoid holds the voxel's
// centre (later structures are painted over earlier ones), 0 for none.
// Blobs and noise are not structures: they keep the label around them.
std::vector<uint32_t> phantom_structure_labels(const PhantomRecipe &recipe, int64_t size);

} // namespace arbor::io
