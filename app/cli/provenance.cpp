#include "provenance.hpp"

#include "io/json_writer.hpp"

namespace arbor::cli {

extern const char *const kBuildCommit; // build_commit.cpp, generated at build time

std::string arbor_version() { return ARBOR_VERSION; }
std::string arbor_commit() { return kBuildCommit; }

void write_provenance_value(io::JsonWriter &j, const Context &context, const pipeline::PluginCatalog &catalog,
                            const ProvenanceParts &parts);

namespace {

void write_setting(io::JsonWriter &j, const pipeline::PluginCatalog &catalog, const pipeline::PluginSetting &s)
{
    j.field("id", s.id);
    j.field("version", s.version);
    const PluginInfo *info = catalog.registry().find(s.id);
    if (info && info->library)
        j.field("library", info->library->path().string());
    const io::JsonWriter::Scope params = j.object("parameters");
    for (const auto &[key, value] : s.params)
        j.field(key, value);
}

} // namespace

void write_provenance(io::JsonWriter &j, const Context &context, const pipeline::PluginCatalog &catalog,
                      const ProvenanceParts &parts)
{
    j.key("provenance");
    write_provenance_value(j, context, catalog, parts);
}

std::string provenance_text(const Context &context, const pipeline::PluginCatalog &catalog,
                            const ProvenanceParts &parts)
{
    std::string text;
    io::JsonWriter j(text);
    write_provenance_value(j, context, catalog, parts);
    j.finish(); // the writer buffers: its text is complete only now
    return text;
}

ProvenanceParts provenance_of(const pipeline::Document &resolved, const pipeline::ImportResult *import,
                              const std::vector<pipeline::PluginSetting> &filters_applied)
{
    ProvenanceParts parts;
    parts.import = import;
    parts.input = resolved.input;
    parts.filters = filters_applied;
    const std::pair<const char *, const pipeline::PluginSetting *> roles[] = {
        {"simplifier", &resolved.simplifier},
        {"depictor", &resolved.appearance.depictor},
        {"generator", &resolved.appearance.generator},
        {"renderer", &resolved.view.renderer}};
    for (const auto &[role, setting] : roles)
        if (!setting->empty())
            parts.plugins.emplace_back(role, *setting);
    return parts;
}

void write_provenance_value(io::JsonWriter &j, const Context &context, const pipeline::PluginCatalog &catalog,
                            const ProvenanceParts &parts)
{
    const io::JsonWriter::Scope provenance = j.object();
    {
        const io::JsonWriter::Scope arbor = j.object("arbor");
        j.field("version", arbor_version());
        j.field("commit", arbor_commit());
    }
    j.field("command_line", context.command_line);
    {
        const io::JsonWriter::Scope input = j.object("input");
        if (parts.input.phantom) {
            const pipeline::PhantomInput &ph = *parts.input.phantom;
            const io::JsonWriter::Scope phantom = j.object("phantom");
            j.field("kind", ph.kind);
            j.field("size", ph.size);
            j.field("noise", ph.noise);
            j.field("blobs", ph.blobs);
            j.field("seed", ph.seed);
        } else {
            j.field("path", parts.input.path.string());
        }
        if (parts.import) {
            j.field("checksum", parts.import->checksum);
            if (!parts.import->importer.empty()) {
                const io::JsonWriter::Scope importer = j.object("importer");
                write_setting(j, catalog, parts.import->importer);
            }
        }
    }
    {
        const io::JsonWriter::Scope filters = j.array("filters");
        for (const pipeline::PluginSetting &s : parts.filters) {
            const io::JsonWriter::Scope o = j.object();
            write_setting(j, catalog, s);
        }
    }
    const io::JsonWriter::Scope plugins = j.array("plugins");
    for (const auto &[role, setting] : parts.plugins) {
        const io::JsonWriter::Scope o = j.object();
        j.field("role", role);
        write_setting(j, catalog, setting);
    }
}

} // namespace arbor::cli
