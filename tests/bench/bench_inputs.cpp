#include "bench_inputs.hpp"

#include <algorithm>
#include <utility>

namespace arbor::bench {

namespace {

struct RealVolume {
    const char *name; // the name in reference/ttk (README.md, TIMINGS.md)
    const char *file; // under shared/data
    int64_t max_dim;
};

// The shared volumes with TTK reference pairs (reference/ttk/README.md),
// small ones first; the larger ones also have a time in TIMINGS.md.
constexpr RealVolume kRealVolumes[] = {
    {"bucky", "bucky/bucky.nhdr", 32},
    {"nucleon", "nucleon/nucleon.nrrd", 41},
    {"mr_head_lowres", "mr_head_lowres/HeadMRVolume.mhd", 62},
    {"neghip", "neghip/neghip.nhdr", 64},
    {"hydrogen_orbital", "hydrogen_orbital/hydrogen.vti", 64},
    {"ironprot", "ironprot/ironProt.vtk", 68},
    {"tooth", "tooth/tooth.nhdr", 161},
    {"tooth16", "tooth16_bigendian/tooth.nhdr", 161},
    {"walnut", "walnut/walnut.nhdr", 128},
    {"mr_brain_tumor1", "mr_brain_tumor_pyradiomics/brain1_image.nrrd", 256},
    {"mr_brain_colin27", "mr_brain_colin27/ch2.nii.gz", 217},
    {"engine", "engine/engine.vti", 256},
    {"ct_chest_lidc2", "ct_chest_lidc2/LIDC2.mha", 256},
    {"ct_angio_avm", "ct_angio_avm/CT_AVM.nii.gz", 256},
    {"aneurism", "aneurism/aneurism.vti", 256},
    {"bonsai", "bonsai/bonsai.vti", 256},
};

std::string format_noise(double sigma)
{
    std::string s = std::to_string(sigma);
    s.erase(s.find_last_not_of('0') + 1);
    if (!s.empty() && s.back() == '.')
        s.pop_back();
    return s;
}

BenchInput named(std::string name, int64_t max_dim)
{
    BenchInput in;
    in.name = std::move(name);
    in.max_dim = max_dim;
    return in;
}

} // namespace

std::vector<BenchInput> all_inputs(const CatalogueOptions &options)
{
    std::vector<BenchInput> inputs;
    for (int64_t n : options.phantom_sizes) {
        BenchInput clean = named("phantom_head_" + std::to_string(n), n);
        clean.phantom = io::PhantomOptions{.size = n};
        inputs.push_back(clean);
        if (options.phantom_noise > 0 || options.phantom_blobs > 0) {
            BenchInput noisy = named(clean.name + "_noise" + format_noise(options.phantom_noise) + "_blobs" +
                                         std::to_string(options.phantom_blobs),
                                     n);
            noisy.phantom = io::PhantomOptions{.size = n, .noise_sigma = options.phantom_noise,
                                               .blobs = options.phantom_blobs};
            inputs.push_back(noisy);
        }
    }
    for (const RealVolume &v : kRealVolumes) {
        BenchInput in = named(v.name, v.max_dim);
        in.file = options.data_dir / v.file;
        inputs.push_back(in);
    }
    BenchInput stacked = named("ct_head_stacked300", 512);
    stacked.file = options.data_dir / "dicom_ct_head_0051";
    stacked.stacked_slices = 300;
    inputs.push_back(stacked);
    for (int64_t n : options.synthetic_sizes)
        for (SyntheticKind kind : {SyntheticKind::Blobs, SyntheticKind::BlobsNoise, SyntheticKind::Random}) {
            const SyntheticField field{kind, n};
            BenchInput in = named(field.name(), n);
            in.synthetic = field;
            inputs.push_back(in);
        }
    return inputs;
}

std::vector<BenchInput> select_inputs(const std::vector<BenchInput> &inputs, int64_t max_size,
                                      const std::vector<std::string> &only)
{
    std::vector<BenchInput> out;
    for (const BenchInput &in : inputs) {
        if (in.max_dim > max_size)
            continue;
        const bool named = only.empty() || std::any_of(only.begin(), only.end(), [&](const std::string &s) {
                               return in.name.find(s) != std::string::npos;
                           });
        if (named)
            out.push_back(in);
    }
    return out;
}

} // namespace arbor::bench
