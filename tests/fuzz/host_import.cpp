// host_import.cpp - see host_import.hpp.
#include "host_import.hpp"

#include "fuzz_support.hpp"

#include "host/param_text.hpp"
#include "host/volume_import.hpp"

namespace arbor::fuzz {

namespace {

// Plugin log messages (warnings about the input) are expected, not news.
class QuietLog final : public LogSink {
public:
    void write(arbor_log_level, const std::string &, const std::string &) override {}
};

// A new instance, made as PluginLibrary makes one (init once, then create).
PluginInstance create_instance(const std::string &id)
{
    static HostIdentity library_host("fuzz harness");
    static const arbor_status init = arbor_entry.init(library_host.get(), "linked into the fuzz harness");
    if (init != ARBOR_OK)
        finding("the plugin library's init failed: " + std::string(arbor_status_name(init)));
    auto host = std::make_unique<HostIdentity>(id);
    arbor_plugin *plugin = nullptr;
    const arbor_status created = arbor_entry.create_plugin(host->get(), id.c_str(), &plugin);
    if (created != ARBOR_OK || !plugin)
        finding("cannot create " + id + ": " + arbor_status_name(created));
    return PluginInstance(plugin, std::move(host));
}

} // namespace

void import_through_host(const std::string &id, const std::filesystem::path &path, const ImportCheck &check)
{
    static QuietLog quiet;
    PluginInstance importer = create_instance(id);
    importer.route_log(&quiet);
    for (const auto &[param, text] : check.params) {
        const arbor_param_desc *desc = importer.find_param(param);
        if (!desc)
            finding(id + " has no parameter " + param + " (the harness, not the plugin)");
        importer.set_param(param, parse_param_value(*desc, text).value);
    }
    const HeaderAdmission bounded = [&](const arbor_volume &header) {
        const uint64_t bytes = static_cast<uint64_t>(header.dims[0]) * static_cast<uint64_t>(header.dims[1]) *
                               static_cast<uint64_t>(header.dims[2]) * arbor_voxel_size(header.voxel_type);
        if (check.header_bound > 0 && bytes > check.header_bound)
            finding(id + " accepted a header claiming " + std::to_string(bytes) +
                    " bytes of voxels from a file that can hold at most " + std::to_string(check.header_bound));
        return std::string();
    };
    try {
        import_volume(importer, path, nullptr, kHostMaxBytes, {}, bounded);
    } catch (const PluginError &e) {
        if (e.status() == ARBOR_ERROR_INTERNAL)
            finding("internal error instead of a message about the input: " + std::string(e.what()));
    } catch (const std::runtime_error &) {
        // The host refused the header (dims, geometry, memory).
    } catch (...) {
        unexpected_exception(std::current_exception());
    }
}

} // namespace arbor::fuzz
