// importer_classes.hpp - the plugins of this library: one descriptor and one
// factory per importer, gathered by library.cpp into the entry point.
#pragma once

#include <arbor/sdk/instance.hpp>

namespace arbor::importers {

extern const arbor_plugin_descriptor kNrrdImporterDescriptor;
extern const arbor_plugin_descriptor kMetaImageImporterDescriptor;
extern const arbor_plugin_descriptor kRawImporterDescriptor;

sdk::Instance *create_nrrd_importer(const arbor_host *host);
sdk::Instance *create_metaimage_importer(const arbor_host *host);
sdk::Instance *create_raw_importer(const arbor_host *host);

} // namespace arbor::importers
