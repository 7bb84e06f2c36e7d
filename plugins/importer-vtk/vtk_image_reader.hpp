// vtk_image_reader.hpp - the VTK reader for a .vti or legacy
// STRUCTURED_POINTS file, and what its pipeline information tells about the
// image before any voxel is read.
#pragma once

#include "vtk_file_kind.hpp"

#include <vtkSmartPointer.h>

#include <array>
#include <cstdint>
#include <string>

class vtkAlgorithm;
class vtkDataArray;
class vtkImageData;

namespace arbor::importer_vtk {

// vtkXMLImageDataReader for VtkLayout::xml, vtkStructuredPointsReader for
// VtkLayout::legacy, with its file name set.
vtkSmartPointer<vtkAlgorithm> make_image_reader(VtkLayout layout, const std::string &path);

// The image as UpdateInformation describes it.
struct ImageLayout {
    std::array<int, 6> extent{};                      // i0 i1 j0 j1 k0 k1
    std::array<double, 3> spacing{1.0, 1.0, 1.0};
    std::array<double, 3> origin{0.0, 0.0, 0.0};      // of index (0, 0, 0), not of extent start
    std::array<double, 9> direction{1, 0, 0, 0, 1, 0, 0, 0, 1};
    // The point-data array that becomes the voxels: the flagged scalars, or
    // the first array when none is flagged.  known is false when the
    // information does not describe any (legacy files whose point data is a
    // FIELD): then only reading the data tells.
    bool known = false;
    std::string array_name; // "" for an unnamed array
    int vtk_type = 0;
    int components = 1;

    int64_t dim(int axis) const
    {
        return int64_t{extent[2 * axis + 1]} - int64_t{extent[2 * axis]} + 1;
    }
};

// Reads the layout from the information of a reader after UpdateInformation.
// Throws ARBOR_ERROR_FORMAT naming `what` when there is no usable extent.
ImageLayout image_layout(vtkAlgorithm &reader, const std::string &what);

// The layout of an image already read (whole-data fallback for legacy files).
ImageLayout image_layout(vtkImageData &image);

// Lets an XML reader skip every array but `name` (call after
// UpdateInformation, which lists the arrays).  Other readers are left as
// they are.
void read_only_array(vtkAlgorithm &reader, const std::string &name);

// The array `layout` describes in an image the reader produced, or nullptr.
vtkDataArray *layout_array(vtkImageData &image, const ImageLayout &layout);

} // namespace arbor::importer_vtk
