#include "input_flags.hpp"

#include "usage_error.hpp"

#include "io/phantom.hpp"

#include <algorithm>
#include <cctype>
#include <stdexcept>

namespace arbor::cli {

namespace {

// A --filter NAME[:key=value,...] as a setting (the id as given).
pipeline::PluginSetting filter_spec(const std::string &spec)
{
    try {
        return parse_plugin_spec(spec, "--filter");
    } catch (const std::invalid_argument &e) {
        throw UsageError(e.what());
    }
}

} // namespace

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
        "--importer", importer_,
        "Importer plugin, by short name or id (loaded: " + plugin_names(context.registry, ARBOR_KIND_IMPORTER) +
            "); default: chosen by probing the file")->group("Input");
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
            throw UsageError("--importer and --series read files; --phantom needs neither");
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
            throw UsageError("flags for several importers were given (" + flagged[0] + ", " + flagged[1] +
                             "); choose one with --importer");
        if (flagged.size() == 1)
            input.importer.id = flagged[0];
    }
    if (!input.importer.id.empty())
        importer_flags_.apply(input.importer);
    if (series_option_->count())
        input.importer.params["series"] = series_;
}

void FilterFlags::add_to(CLI::App &command, Context &context, const std::string &help)
{
    command
        .add_option("--filter", specs_,
                    help.empty() ? "Denoise first: NAME[:key=value,...], NAME a filter's short name or id (loaded: " +
                                       plugin_names(context.registry, ARBOR_KIND_FILTER) +
                                       "), e.g. gaussian:sigma=1.5; repeat for a chain applied in order; none for no "
                                       "filter"
                                 : help)
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
                    throw UsageError("--filter none cannot be combined with other filters");
                continue;
            }
            pipeline::PluginSetting s = filter_spec(spec);
            s.id = catalog.find(ARBOR_KIND_FILTER, s.id);
            chain.push_back(std::move(s));
        }
    }
    apply_flags(chain, !specs_.empty());
    for (const std::string &id : flags_.given_plugins())
        if (std::none_of(chain.begin(), chain.end(), [&](const auto &s) { return s.id == id; }))
            log_message(ARBOR_LOG_WARNING, "", "flags for " + id + " were given but it is not in the filter chain; "
                                                                    "ignored");
}

void FilterFlags::apply_flags(std::vector<pipeline::PluginSetting> &chain, bool given) const
{
    for (pipeline::PluginSetting &s : chain) {
        pipeline::PluginSetting flagged{s.id, "", {}};
        flags_.apply(flagged, true);
        for (const auto &[key, value] : flagged.params)
            if (!given)
                s.params[key] = value; // over a session's chain
            else
                s.params.try_emplace(key, value); // --filter NAME:key=value beats --NAME.key
    }
}

std::vector<std::pair<std::string, std::vector<pipeline::PluginSetting>>>
FilterFlags::sweep_chains(const pipeline::PluginCatalog &catalog) const
{
    std::vector<std::pair<std::string, std::vector<pipeline::PluginSetting>>> chains;
    for (const std::string &spec : specs_) {
        std::vector<pipeline::PluginSetting> chain;
        if (spec != "none")
            for (const std::string &part : split_filter_chain(spec)) {
                pipeline::PluginSetting s = filter_spec(part);
                s.id = catalog.find(ARBOR_KIND_FILTER, s.id);
                chain.push_back(std::move(s));
            }
        apply_flags(chain, true);
        for (const auto &[text, other] : chains)
            if (other == chain)
                throw UsageError("--filter " + spec + " is the same setting as --filter " + text);
        chains.emplace_back(spec, std::move(chain));
    }
    if (chains.empty())
        chains.emplace_back("none", std::vector<pipeline::PluginSetting>{});
    for (const std::string &id : flags_.given_plugins())
        if (std::none_of(chains.begin(), chains.end(), [&](const auto &entry) {
                return std::any_of(entry.second.begin(), entry.second.end(), [&](const auto &s) { return s.id == id; });
            }))
            log_message(ARBOR_LOG_WARNING, "", "flags for " + id + " were given but no --filter uses it; ignored");
    return chains;
}

std::vector<std::string> split_filter_chain(const std::string &spec)
{
    std::vector<std::string> parts;
    std::size_t start = 0;
    for (std::size_t i = 0; i < spec.size(); ++i)
        if (spec[i] == '+' && i + 1 < spec.size() && std::isalpha(static_cast<unsigned char>(spec[i + 1]))) {
            parts.push_back(spec.substr(start, i - start));
            start = i + 1;
        }
    parts.push_back(spec.substr(start));
    for (const std::string &p : parts)
        if (p.empty())
            throw UsageError("--filter " + spec + ": an empty filter in the chain");
    return parts;
}

} // namespace arbor::cli
