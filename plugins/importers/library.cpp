// library.cpp - the entry point of arbor-importers: the NRRD, MetaImage and
// headerless raw importers.
#include "importer_classes.hpp"

namespace {

const arbor::sdk::PluginClass kImporters[] = {
    {&arbor::importers::kNrrdImporterDescriptor, &arbor::importers::create_nrrd_importer},
    {&arbor::importers::kMetaImageImporterDescriptor, &arbor::importers::create_metaimage_importer},
    {&arbor::importers::kRawImporterDescriptor, &arbor::importers::create_raw_importer},
};

} // namespace

ARBOR_SDK_DEFINE_LIBRARY(kImporters)
