// `arbor phantom`: write a built-in synthetic volume to a NRRD file.
#include "commands.hpp"

#include "io/label_map_output.hpp"
#include "io/nrrd_writer.hpp"
#include "io/phantom.hpp"

#include <cstdio>
#include <memory>

namespace arbor::cli {

namespace {

struct PhantomArgs {
    std::string kind = "head";
    std::string output;
    io::PhantomOptions options;
    bool raw = false;
    std::string labels;
};

} // namespace

void add_phantom_command(CLI::App &app, Context &context)
{
    CLI::App *sub = app.add_subcommand(
        "phantom", "Write a deterministic synthetic volume (the built-in default data) as NRRD");
    auto a = std::make_shared<PhantomArgs>();
    sub->add_option("--kind", a->kind, "Phantom kind")->check(CLI::IsMember(io::builtin_phantom_kinds()))
        ->default_val("head");
    sub->add_option("-o,--output", a->output, "Output NRRD file")->required();
    sub->add_option("--size", a->options.size, "Voxels per axis")->check(CLI::Range(8, 1024))
        ->default_val(128);
    sub->add_option("--noise", a->options.noise_sigma, "Gaussian noise sigma in stored units")
        ->check(CLI::NonNegativeNumber)->default_val(0.0);
    sub->add_option("--blobs", a->options.blobs, "Small high-contrast blobs to add")
        ->check(CLI::Range(0, 10000))->default_val(0);
    sub->add_option("--seed", a->options.seed, "Random seed for noise and blobs")->default_val(1);
    sub->add_flag("--raw", a->raw, "Write raw (uncompressed) voxel data");
    sub->add_option("--labels", a->labels,
                    "Also write the structures as a ground-truth label map (NRRD + 3D Slicer .ctbl), e.g. for "
                    "`arbor compare --truth`");
    context.add_command(sub, [a]() {
        const io::PhantomRecipe recipe = io::builtin_phantom(a->kind);
        const Volume v = io::make_phantom(recipe, a->options);
        io::NrrdWriteOptions w;
        w.gzip = !a->raw;
        w.content = "arbor phantom " + a->kind;
        w.key_values = {{"arbor_phantom", a->kind},
                        {"arbor_phantom_noise", std::to_string(a->options.noise_sigma)},
                        {"arbor_phantom_blobs", std::to_string(a->options.blobs)},
                        {"arbor_phantom_seed", std::to_string(a->options.seed)}};
        io::write_nrrd(v, a->output, w);
        if (!a->labels.empty()) {
            std::vector<std::string> names{"background"};
            for (const io::PhantomStructure &st : recipe.structures)
                names.push_back(st.name);
            io::write_label_map(a->labels, v.geometry(), "arbor phantom " + a->kind + " structures",
                                io::phantom_structure_labels(recipe, a->options.size), names);
        }
        std::printf("wrote %s: %s phantom, %lld^3 voxels\n", a->output.c_str(), a->kind.c_str(),
                    static_cast<long long>(a->options.size));
        return 0;
    });
}

} // namespace arbor::cli
