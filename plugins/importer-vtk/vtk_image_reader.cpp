// vtk_image_reader.cpp - creating VTK image readers and reading extent,
// geometry and the scalar array from their pipeline information.
#include "vtk_image_reader.hpp"

#include <arbor/sdk/error.hpp>

#include <vtkDataArray.h>
#include <vtkDataArraySelection.h>
#include <vtkDataObject.h>
#include <vtkDataSetAttributes.h>
#include <vtkImageData.h>
#include <vtkInformation.h>
#include <vtkInformationVector.h>
#include <vtkMatrix3x3.h>
#include <vtkPointData.h>
#include <vtkStreamingDemandDrivenPipeline.h>
#include <vtkStructuredPointsReader.h>
#include <vtkXMLImageDataReader.h>

namespace arbor::importer_vtk {

namespace {

void describe_array(vtkInformation &field, ImageLayout &layout)
{
    layout.known = field.Has(vtkDataObject::FIELD_ARRAY_TYPE()) != 0;
    if (!layout.known)
        return;
    layout.vtk_type = field.Get(vtkDataObject::FIELD_ARRAY_TYPE());
    if (field.Has(vtkDataObject::FIELD_NAME()))
        layout.array_name = field.Get(vtkDataObject::FIELD_NAME());
    if (field.Has(vtkDataObject::FIELD_NUMBER_OF_COMPONENTS()))
        layout.components = field.Get(vtkDataObject::FIELD_NUMBER_OF_COMPONENTS());
}

} // namespace

vtkSmartPointer<vtkAlgorithm> make_image_reader(VtkLayout layout, const std::string &path)
{
    if (layout == VtkLayout::legacy) {
        auto reader = vtkSmartPointer<vtkStructuredPointsReader>::New();
        reader->SetFileName(path.c_str());
        return reader;
    }
    auto reader = vtkSmartPointer<vtkXMLImageDataReader>::New();
    reader->SetFileName(path.c_str());
    return reader;
}

ImageLayout image_layout(vtkAlgorithm &reader, const std::string &what)
{
    vtkInformation *info = reader.GetOutputInformation(0);
    if (!info || !info->Has(vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT()))
        sdk::fail(ARBOR_ERROR_FORMAT, what + ": the file describes no image extent");
    ImageLayout layout;
    info->Get(vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT(), layout.extent.data());
    for (int a = 0; a < 3; ++a)
        if (layout.dim(a) < 1)
            sdk::fail(ARBOR_ERROR_FORMAT,
                      what + ": the image extent " + std::to_string(layout.extent[2 * a]) + ".." +
                          std::to_string(layout.extent[2 * a + 1]) + " along axis " +
                          std::to_string(a) + " holds no voxels");
    if (info->Has(vtkDataObject::SPACING()))
        info->Get(vtkDataObject::SPACING(), layout.spacing.data());
    if (info->Has(vtkDataObject::ORIGIN()))
        info->Get(vtkDataObject::ORIGIN(), layout.origin.data());
    if (info->Has(vtkDataObject::DIRECTION()))
        info->Get(vtkDataObject::DIRECTION(), layout.direction.data());

    if (vtkInformation *scalars = vtkDataObject::GetActiveFieldInformation(
            info, vtkDataObject::FIELD_ASSOCIATION_POINTS, vtkDataSetAttributes::SCALARS)) {
        describe_array(*scalars, layout);
    } else if (vtkInformationVector *arrays = info->Get(vtkDataObject::POINT_DATA_VECTOR());
               arrays && arrays->GetNumberOfInformationObjects() > 0) {
        describe_array(*arrays->GetInformationObject(0), layout);
    }
    return layout;
}

ImageLayout image_layout(vtkImageData &image)
{
    ImageLayout layout;
    image.GetExtent(layout.extent.data());
    image.GetSpacing(layout.spacing.data());
    image.GetOrigin(layout.origin.data());
    if (vtkMatrix3x3 *m = image.GetDirectionMatrix())
        for (int e = 0; e < 9; ++e)
            layout.direction[e] = m->GetData()[e];
    vtkPointData *points = image.GetPointData();
    vtkDataArray *array = points->GetScalars() ? points->GetScalars() : points->GetArray(0);
    if (array) {
        layout.known = true;
        layout.array_name = array->GetName() ? array->GetName() : "";
        layout.vtk_type = array->GetDataType();
        layout.components = array->GetNumberOfComponents();
    }
    return layout;
}

void read_only_array(vtkAlgorithm &reader, const std::string &name)
{
    auto *xml = vtkXMLImageDataReader::SafeDownCast(&reader);
    if (!xml || name.empty())
        return;
    xml->GetPointDataArraySelection()->DisableAllArrays();
    xml->GetPointDataArraySelection()->EnableArray(name.c_str());
    xml->GetCellDataArraySelection()->DisableAllArrays();
}

vtkDataArray *layout_array(vtkImageData &image, const ImageLayout &layout)
{
    vtkPointData *points = image.GetPointData();
    if (!layout.array_name.empty())
        if (vtkDataArray *named = points->GetArray(layout.array_name.c_str()))
            return named;
    return points->GetScalars() ? points->GetScalars() : points->GetArray(0);
}

} // namespace arbor::importer_vtk
