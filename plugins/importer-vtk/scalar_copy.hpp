// scalar_copy.hpp - moving the voxels a VTK reader produced into the buffer
// the host allocated, after checking they are what read_header promised.
#pragma once

#include <arbor/sdk/task.hpp>
#include <arbor/volume.h>

#include <string>

class vtkDataArray;
class vtkImageData;

namespace arbor::importer_vtk {

enum class SliceOrder {
    same,     // VTK slice k is file slice k
    reversed, // VTK slice k is file slice nz-1-k (vtkNIFTIImageReader, qfac -1)
};

// Throws ARBOR_ERROR_FORMAT naming `what` unless `image` has the dims of
// `volume` (the file changed between the two calls, or the reader disagrees
// with its own header).
void require_same_dims(vtkImageData &image, const arbor_volume &volume, const std::string &what);

// Copies single-component `scalars` into volume.voxels (contiguous, i
// fastest) slice by slice, reporting progress from `progress_from` to 1 and
// stopping with ARBOR_ERROR_CANCELLED when the host asks.  Throws
// ARBOR_ERROR_FORMAT when count, components or type differ from `volume`.
void copy_scalars(vtkDataArray &scalars, arbor_volume &volume, SliceOrder order,
                  const sdk::Task &task, double progress_from, const std::string &what);

} // namespace arbor::importer_vtk
