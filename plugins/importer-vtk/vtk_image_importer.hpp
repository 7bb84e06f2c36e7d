// vtk_image_importer.hpp - org.arbor.importer.vtk-image: VTK image data, XML
// .vti and legacy STRUCTURED_POINTS .vtk, read through VTK's own readers.
#pragma once

#include <arbor/sdk/importer.hpp>

namespace arbor::importer_vtk {

extern const arbor_plugin_descriptor kVtkImageDescriptor;

class VtkImageImporter final : public sdk::Importer {
public:
    explicit VtkImageImporter(const arbor_host *host);

    int32_t probe(const std::string &path, const uint8_t *head, uint64_t head_size) override;
    void read_header(const std::string &path, const sdk::Task &task, arbor_volume &out) override;
    void read_voxels(const std::string &path, const sdk::Task &task, arbor_volume &volume) override;
};

} // namespace arbor::importer_vtk
