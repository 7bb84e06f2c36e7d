// nifti_importer.hpp - org.arbor.importer.nifti: NIfTI-1 and NIfTI-2 images
// (.nii, .nii.gz) read through vtkNIFTIImageReader, voxels in file order.
#pragma once

#include <arbor/sdk/importer.hpp>

namespace arbor::importer_vtk {

extern const arbor_plugin_descriptor kNiftiDescriptor;

class NiftiImporter final : public sdk::Importer {
public:
    explicit NiftiImporter(const arbor_host *host);

    int32_t probe(const std::string &path, const uint8_t *head, uint64_t head_size) override;
    void read_header(const std::string &path, const sdk::Task &task, arbor_volume &out) override;
    void read_voxels(const std::string &path, const sdk::Task &task, arbor_volume &volume) override;
};

} // namespace arbor::importer_vtk
