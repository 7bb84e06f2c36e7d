#include "input_flags.hpp"

#include "io/phantom.hpp"

#include <algorithm>
#include <stdexcept>

namespace arbor::cli {

std::vector<std::string> split_list(const std::string &list)
{
    std::vector<std::string> out;
    std::size_t start = 0;
    while (start <= list.size()) {
        std::size_t end = list.find(',', start);
        if (end == std::string::npos)
            end = list.size();
        std::string item = list.substr(start, end - start);
        item.erase(0, item.find_first_not_of(" \t"));
        item.erase(item.find_last_not_of(" \t") + 1);
        if (!item.empty())
            out.push_back(item);
        start = end + 1;
    }
    return out;
}

void InputFlags::add_to(CLI::App &command, Context &context)
{
    registry_ = &context.registry;
    path_option_ = command.add_option(
        "volume", path_, "Volume file or folder (DICOM folder or file, NRRD, MetaImage, VTK, NIfTI, raw...)");
    phantom_option_ =
        command.add_option("--phantom", phantom_, "Use a built-in synthetic volume instead of a file (head)");
    phantom_option_->check(CLI::IsMember(io::builtin_phantom_kinds()));
    path_option_->excludes(phantom_option_);
    size_option_ = command.add_option("--phantom-size", phantom_size_, "Phantom voxels per axis")
                       ->default_val(128)->check(CLI::Range(8, 1024))->group("Phantom");
    noise_option_ = command.add_option("--phantom-noise", phantom_noise_, "Phantom Gaussian noise sigma (stored units)")
                        ->default_val(0.0)->check(CLI::NonNegativeNumber)->group("Phantom");
    blobs_option_ = command.add_option("--phantom-blobs", phantom_blobs_, "Phantom small high-contrast blobs")
                        ->default_val(0)->check(CLI::Range(0, 10000))->group("Phantom");
    seed_option_ = command.add_option("--phantom-seed", phantom_seed_, "Phantom random seed")
                       ->default_val(1)->group("Phantom");
    phantom_option_->group("Input");
    path_option_->group("Input");
    importer_option_ = command.add_option(
        "--importer", importer_, "Importer plugin id (default: chosen by probing the file)")->group("Input");
    series_option_ = command.add_option("--series", series_,
                                        "DICOM folders: the series to read, by Series Instance UID or its number in "
                                        "`arbor dicom ls` (needed when the folder holds several)")
                         ->group("Input");
    command.add_flag("--no-cache", no_cache_,
                     "Neither read nor write the on-disk contour-tree cache (see README: the cache)")
        ->group("Input");
    importer_flags_.add(command, context.registry, ARBOR_KIND_IMPORTER, "Importer options");
    context.flag_names.add(importer_flags_);
    context.flag_names.add("series", "--series");
}

bool InputFlags::given() const
{
    return path_option_->count() > 0 || phantom_option_->count() > 0;
}

void InputFlags::apply(pipeline::InputChoice &input, const pipeline::PluginCatalog &catalog) const
{
    if (phantom_option_->count()) {
        input = {};
        input.phantom = pipeline::PhantomInput{phantom_, phantom_size_, phantom_noise_, phantom_blobs_, phantom_seed_};
    } else if (path_option_->count()) {
        input = {};
        input.path = path_;
    } else if (input.phantom) { // a session's phantom, with some of its recipe changed
        if (size_option_->count())
            input.phantom->size = phantom_size_;
        if (noise_option_->count())
            input.phantom->noise = phantom_noise_;
        if (blobs_option_->count())
            input.phantom->blobs = phantom_blobs_;
        if (seed_option_->count())
            input.phantom->seed = phantom_seed_;
    }
    if (input.phantom) {
        if (importer_option_->count() || series_option_->count())
            throw std::invalid_argument("--importer and --series read files; --phantom needs neither");
        return;
    }
    if (importer_option_->count()) {
        input.importer = {catalog.find(ARBOR_KIND_IMPORTER, importer_), "", {}};
    } else if (input.importer.empty()) {
        // Flags given for one importer choose it; otherwise the file is probed.
        std::vector<std::string> flagged;
        for (const PluginInfo *p : registry_->plugins_of_kind(ARBOR_KIND_IMPORTER))
            if (importer_flags_.given_for(p->descriptor->id))
                flagged.push_back(p->descriptor->id);
        if (flagged.size() > 1)
            throw std::invalid_argument("flags for several importers were given (" + flagged[0] + ", " + flagged[1] +
                                        "); choose one with --importer");
        if (flagged.size() == 1)
            input.importer.id = flagged[0];
    }
    if (!input.importer.id.empty())
        importer_flags_.apply(input.importer);
    if (series_option_->count())
        input.importer.params["series"] = series_;
}

void FilterFlags::add_to(CLI::App &command, Context &context)
{
    command
        .add_option("--filter", specs_,
                    "Denoise first: NAME[:key=value,...], e.g. gaussian:sigma=1.5, median:size=3, bilateral, "
                    "nlmeans:h=0.05; repeat for a chain applied in order; none for no filter")
        ->group("Input");
    flags_.add(command, context.registry, ARBOR_KIND_FILTER, "Filter options");
    context.flag_names.add(flags_);
}

void FilterFlags::apply(std::vector<pipeline::PluginSetting> &chain, bool &auto_denoise,
                        const pipeline::PluginCatalog &catalog) const
{
    if (!specs_.empty()) {
        chain.clear();
        auto_denoise = false; // the user chose: exactly these filters, or none
        for (const std::string &spec : specs_) {
            if (spec == "none") {
                if (specs_.size() > 1)
                    throw std::invalid_argument("--filter none cannot be combined with other filters");
                continue;
            }
            pipeline::PluginSetting s = parse_plugin_spec(spec, "--filter");
            s.id = catalog.find(ARBOR_KIND_FILTER, s.id);
            chain.push_back(std::move(s));
        }
    }
    for (pipeline::PluginSetting &s : chain) {
        pipeline::PluginSetting flagged{s.id, "", {}};
        flags_.apply(flagged, true);
        for (const auto &[key, value] : flagged.params)
            if (specs_.empty())
                s.params[key] = value; // over a session's chain
            else
                s.params.try_emplace(key, value); // --filter NAME:key=value beats --NAME.key
    }
    for (const std::string &id : flags_.given_plugins())
        if (std::none_of(chain.begin(), chain.end(), [&](const auto &s) { return s.id == id; }))
            log_message(ARBOR_LOG_WARNING, "", "flags for " + id + " were given but it is not in the filter chain; "
                                                                    "ignored");
}

} // namespace arbor::cli
