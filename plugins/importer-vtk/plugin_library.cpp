// plugin_library.cpp - the arbor-importer-vtk library: the importers built on
// VTK's readers, as one plugin library.
#include "nifti_importer.hpp"
#include "vtk_image_importer.hpp"

#include <arbor/sdk/instance.hpp>

namespace {

const arbor::sdk::PluginClass kPlugins[] = {
    {&arbor::importer_vtk::kVtkImageDescriptor,
     &arbor::sdk::make_instance<arbor::importer_vtk::VtkImageImporter>},
    {&arbor::importer_vtk::kNiftiDescriptor,
     &arbor::sdk::make_instance<arbor::importer_vtk::NiftiImporter>},
};

} // namespace

ARBOR_SDK_DEFINE_LIBRARY(kPlugins)
