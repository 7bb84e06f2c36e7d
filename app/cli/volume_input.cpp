#include "volume_input.hpp"

#include "host/param_text.hpp"
#include "host/volume_import.hpp"
#include "io/phantom.hpp"

#include <stdexcept>

namespace arbor::cli {

void VolumeInput::add_to(CLI::App &command, Context &context)
{
    context_ = &context;
    auto *file = command.add_option("volume", path_,
                                    "Volume file or folder (DICOM folder or file, NRRD, MetaImage, VTK, NIfTI, raw...)");
    auto *phantom = command.add_option("--phantom", phantom_,
                                       "Use a built-in synthetic volume instead of a file (head)");
    phantom->check(CLI::IsMember(io::builtin_phantom_kinds()));
    file->excludes(phantom);
    command.add_option("--phantom-size", phantom_size_, "Phantom voxels per axis")
        ->default_val(128)->check(CLI::Range(8, 1024))->group("Phantom");
    command.add_option("--phantom-noise", phantom_noise_, "Phantom Gaussian noise sigma (stored units)")
        ->default_val(0.0)->check(CLI::NonNegativeNumber)->group("Phantom");
    command.add_option("--phantom-blobs", phantom_blobs_, "Phantom small high-contrast blobs")
        ->default_val(0)->check(CLI::Range(0, 10000))->group("Phantom");
    command.add_option("--phantom-seed", phantom_seed_, "Phantom random seed")->default_val(1)->group("Phantom");
    phantom->group("Input");
    file->group("Input");
    command.add_option("--importer", importer_, "Importer plugin id (default: chosen by probing the file)")
        ->group("Input");
    command.add_option("--series", series_,
                       "DICOM folders: the series to read, by Series Instance UID or its number in "
                       "`arbor dicom ls` (needed when the folder holds several)")
        ->group("Input");

    for (const PluginInfo *info : context.registry.plugins_of_kind(ARBOR_KIND_IMPORTER)) {
        try {
            importers_.push_back(context.registry.create(info->descriptor->id));
        } catch (const PluginError &e) {
            log_message(ARBOR_LOG_WARNING, "", e.what());
        }
    }
    std::vector<PluginInstance *> ptrs;
    for (PluginInstance &p : importers_)
        ptrs.push_back(&p);
    options_.add(command, "Importer options", ptrs);
}

LoadedVolume VolumeInput::load()
{
    LoadedVolume out;
    if (!phantom_.empty()) {
        io::PhantomOptions o;
        o.size = phantom_size_;
        o.noise_sigma = phantom_noise_;
        o.blobs = phantom_blobs_;
        o.seed = phantom_seed_;
        out.volume = io::make_phantom(io::builtin_phantom(phantom_), o);
        out.source = "phantom:" + phantom_;
        return out;
    }
    if (path_.empty())
        throw std::invalid_argument("no input: give a volume file or --phantom head");
    const std::string id = importer_.empty() ? choose_importer(context_->registry, path_) : importer_;
    PluginInstance *importer = nullptr;
    for (PluginInstance &p : importers_)
        if (p.id() == id)
            importer = &p;
    if (!importer)
        throw std::invalid_argument("no importer plugin with id '" + id + "' (see `arbor plugins`)");
    if (!series_.empty()) {
        const arbor_param_desc *d = importer->find_param("series");
        if (!d)
            throw std::invalid_argument("--series applies to DICOM input; " + id + " reads " + path_);
        importer->set_param("series", parse_param_value(*d, series_).value);
    }
    options_.apply(*importer);
    out.volume = import_volume(*importer, path_, &context_->progress, context_->max_volume_bytes, context_->stop.get_token());
    out.source = path_;
    out.importer_id = id;
    out.importer_version = importer->descriptor().version;
    return out;
}

} // namespace arbor::cli
