#include "volume_import.hpp"

#include "../core/volume_header.hpp"

#include <algorithm>
#include <fstream>
#include <sstream>

namespace arbor {

namespace fs = std::filesystem;

namespace {

std::vector<uint8_t> read_head(const fs::path &path)
{
    std::vector<uint8_t> head;
    std::error_code ec;
    // Only regular files: opening a FIFO or a device could block or never end.
    if (!fs::is_regular_file(path, ec))
        return head;
    std::ifstream in(path, std::ios::binary);
    if (!in)
        return head;
    head.resize(4096);
    in.read(reinterpret_cast<char *>(head.data()), static_cast<std::streamsize>(head.size()));
    head.resize(static_cast<std::size_t>(in.gcount()));
    return head;
}

bool suffix_matches(const char *suffixes, const fs::path &path)
{
    if (!suffixes)
        return false;
    std::string name = path.filename().string();
    std::transform(name.begin(), name.end(), name.begin(), [](unsigned char c) { return std::tolower(c); });
    std::stringstream ss(suffixes);
    std::string s;
    while (std::getline(ss, s, ';'))
        if (!s.empty() && name.size() >= s.size() && name.compare(name.size() - s.size(), s.size(), s) == 0)
            return true;
    return false;
}

} // namespace

std::vector<ImporterChoice> rank_importers(const PluginRegistry &registry, const fs::path &path)
{
    const std::vector<uint8_t> head = read_head(path);
    struct Ranked {
        ImporterChoice choice;
        bool suffix;
    };
    std::vector<Ranked> ranked;
    for (const PluginInfo *info : registry.plugins_of_kind(ARBOR_KIND_IMPORTER)) {
        try {
            PluginInstance importer = registry.create(info->descriptor->id);
            const auto &table = importer.interface<arbor_importer_v1>(ARBOR_INTERFACE_IMPORTER);
            int32_t confidence = 0;
            const arbor_status s = importer.call("importer.probe", table.probe, path.c_str(), head.data(),
                                                 head.size(), &confidence);
            if (s == ARBOR_OK && confidence > 0)
                ranked.push_back({{info->descriptor->id, confidence}, suffix_matches(table.suffixes, path)});
        } catch (const PluginError &e) {
            log_message(ARBOR_LOG_WARNING, "", e.what());
        }
    }
    std::stable_sort(ranked.begin(), ranked.end(), [](const Ranked &a, const Ranked &b) {
        if (a.choice.confidence != b.choice.confidence)
            return a.choice.confidence > b.choice.confidence;
        return a.suffix && !b.suffix;
    });
    std::vector<ImporterChoice> out;
    for (const Ranked &r : ranked)
        out.push_back(r.choice);
    return out;
}

std::string choose_importer(const PluginRegistry &registry, const fs::path &path)
{
    std::error_code ec;
    const fs::file_status status = fs::status(path, ec);
    if (!fs::exists(status))
        throw std::runtime_error(path.string() + ": no such file or folder");
    if (!fs::is_regular_file(status) && !fs::is_directory(status))
        throw std::runtime_error(path.string() + ": not a regular file or a folder");
    const auto ranked = rank_importers(registry, path);
    if (ranked.empty()) {
        std::string tried;
        for (const PluginInfo *info : registry.plugins_of_kind(ARBOR_KIND_IMPORTER))
            tried += (tried.empty() ? "" : ", ") + std::string(info->descriptor->id);
        throw std::runtime_error(path.string() + ": no importer recognises this file (tried: " +
                                 (tried.empty() ? "none loaded" : tried) +
                                 "); name one with --importer");
    }
    return ranked.front().id;
}

Volume import_volume(PluginInstance &importer, const fs::path &path, ProgressSink *progress,
                     uint64_t max_bytes, std::stop_token stop, const HeaderAdmission &admit)
{
    const auto &table = importer.interface<arbor_importer_v1>(ARBOR_INTERFACE_IMPORTER);
    arbor_volume header{};
    header.struct_size = sizeof(header);
    {
        Task task(progress, stop);
        importer.check(importer.call("importer.read_header", table.read_header, path.c_str(), task.get(), &header),
                       "reading the header of " + path.string());
    }
    std::string problem = check_volume_header(header, max_bytes);
    if (problem.empty() && admit)
        problem = admit(header);
    if (!problem.empty())
        throw std::runtime_error(path.string() + ": " + problem);
    Volume volume;
    try {
        volume = Volume::allocate(header, max_bytes);
    } catch (const std::bad_alloc &) {
        throw std::runtime_error(path.string() + ": the system refused " +
                                 format_bytes(static_cast<uint64_t>(header.dims[0] * header.dims[1] *
                                                                    header.dims[2]) *
                                              arbor_voxel_size(header.voxel_type)) +
                                 " for the voxels");
    }
    arbor_volume target = volume.view();
    {
        Task task(progress, stop);
        importer.check(importer.call("importer.read_voxels", table.read_voxels, path.c_str(), task.get(), &target),
                       "reading the voxels of " + path.string());
    }
    return volume;
}

} // namespace arbor
