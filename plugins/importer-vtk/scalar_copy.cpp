// scalar_copy.cpp - checked slice-by-slice copy from a vtkDataArray into the
// host's voxel buffer.
#include "scalar_copy.hpp"

#include "vtk_voxel_type.hpp"

#include <arbor/sdk/error.hpp>

#include <vtkDataArray.h>
#include <vtkImageData.h>

#include <cstring>

namespace arbor::importer_vtk {

namespace {

std::string dims_text(const int64_t d[3])
{
    return std::to_string(d[0]) + " x " + std::to_string(d[1]) + " x " + std::to_string(d[2]);
}

} // namespace

void require_same_dims(vtkImageData &image, const arbor_volume &volume, const std::string &what)
{
    int d[3] = {0, 0, 0};
    image.GetDimensions(d);
    const int64_t got[3] = {d[0], d[1], d[2]};
    for (int a = 0; a < 3; ++a)
        if (got[a] != volume.dims[a])
            sdk::fail(ARBOR_ERROR_FORMAT, what + ": the reader produced " + dims_text(got) +
                                              " voxels where the header said " +
                                              dims_text(volume.dims) +
                                              " (did the file change in between?)");
}

void copy_scalars(vtkDataArray &scalars, arbor_volume &volume, SliceOrder order,
                  const sdk::Task &task, double progress_from, const std::string &what)
{
    if (scalars.GetNumberOfComponents() != 1)
        sdk::fail(ARBOR_ERROR_FORMAT, what + ": the reader produced " +
                                          std::to_string(scalars.GetNumberOfComponents()) +
                                          " components per voxel where the header said 1");
    const arbor_voxel_type type = voxel_type_of(scalars.GetDataType());
    if (type != volume.voxel_type)
        sdk::fail(ARBOR_ERROR_FORMAT,
                  what + ": the reader produced " + vtk_type_name(scalars.GetDataType()) +
                      " voxels where the header said " + arbor_voxel_type_name(volume.voxel_type));
    const int64_t slice_voxels = volume.dims[0] * volume.dims[1];
    const int64_t slices = volume.dims[2];
    if (static_cast<int64_t>(scalars.GetNumberOfTuples()) != slice_voxels * slices)
        sdk::fail(ARBOR_ERROR_FORMAT,
                  what + ": the reader produced " + std::to_string(scalars.GetNumberOfTuples()) +
                      " voxels where the header said " + std::to_string(slice_voxels * slices));

    const std::size_t slice_bytes =
        static_cast<std::size_t>(slice_voxels) * arbor_voxel_size(volume.voxel_type);
    const auto *source = static_cast<const unsigned char *>(scalars.GetVoidPointer(0));
    auto *target = static_cast<unsigned char *>(volume.voxels);
    for (int64_t k = 0; k < slices; ++k) {
        const int64_t from = order == SliceOrder::reversed ? slices - 1 - k : k;
        std::memcpy(target + static_cast<std::size_t>(k) * slice_bytes,
                    source + static_cast<std::size_t>(from) * slice_bytes, slice_bytes);
        task.progress(progress_from + (1.0 - progress_from) * double(k + 1) / double(slices));
    }
}

} // namespace arbor::importer_vtk
