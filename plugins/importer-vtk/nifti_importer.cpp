// nifti_importer.cpp - probing, header and voxels of NIfTI files.
//
// Voxels leave this importer in the file's storage order (i fastest, then j,
// then k), whatever the orientation: the geometry, not the voxel order,
// carries the orientation.  vtkNIFTIImageReader reverses the slice order when
// the qform's qfac is -1 (or, with no qform, the sform is left-handed), to
// keep VTK's index space right-handed; the copy puts those slices back.
#include "nifti_importer.hpp"

#include "input_file.hpp"
#include "nifti_geometry.hpp"
#include "nifti_header_check.hpp"
#include "nifti_magic.hpp"
#include "reader_watch.hpp"
#include "scalar_copy.hpp"
#include "vtk_image_reader.hpp"
#include "vtk_message_route.hpp"
#include "vtk_voxel_type.hpp"

#include <vtkDataArray.h>
#include <vtkImageData.h>
#include <vtkNIFTIImageHeader.h>
#include <vtkNIFTIImageReader.h>
#include <vtkNew.h>
#include <vtkPointData.h>

namespace arbor::importer_vtk {

const arbor_plugin_descriptor kNiftiDescriptor = {
    sizeof(arbor_plugin_descriptor),
    ARBOR_PLUGIN_FLAG_NONE,
    "org.arbor.importer.nifti",
    ARBOR_KIND_IMPORTER,
    "NIfTI",
    "1.0.0",
    "Arbor",
    "Reads NIfTI-1 and NIfTI-2 images (.nii, .nii.gz) with VTK's reader, keeping the file's "
    "voxel order and converting its sform or qform from RAS to LPS.",
    "",
};

namespace {

constexpr int32_t kSuffixConfidence = 30;

NiftiSpace space_of(vtkNIFTIImageHeader &h)
{
    NiftiSpace s;
    s.qform_code = h.GetQFormCode();
    s.sform_code = h.GetSFormCode();
    for (int i = 0; i < 8; ++i)
        s.pixdim[i] = h.GetPixDim(i);
    s.quatern = {h.GetQuaternB(), h.GetQuaternC(), h.GetQuaternD()};
    s.qoffset = {h.GetQOffsetX(), h.GetQOffsetY(), h.GetQOffsetZ()};
    h.GetSRowX(s.srow[0].data());
    h.GetSRowY(s.srow[1].data());
    h.GetSRowZ(s.srow[2].data());
    s.xyzt_units = h.GetXYZTUnits();
    return s;
}

// The header check already refused every datatype Arbor cannot hold; this
// guards against the reader disagreeing with it.
arbor_voxel_type require_single_scalar(vtkNIFTIImageReader &reader, const std::string &what)
{
    const arbor_voxel_type type = voxel_type_of(reader.GetDataScalarType());
    if (reader.GetNumberOfScalarComponents() != 1 || type == ARBOR_VOXEL_UNKNOWN)
        sdk::fail(ARBOR_ERROR_FORMAT,
                  what + ": VTK reads " + std::to_string(reader.GetNumberOfScalarComponents()) +
                      " component(s) of " + vtk_type_name(reader.GetDataScalarType()) +
                      " per voxel, which the header does not describe");
    return type;
}

} // namespace

NiftiImporter::NiftiImporter(const arbor_host *host)
    : sdk::Importer(kNiftiDescriptor, host, ".nii;.nii.gz")
{
}

int32_t NiftiImporter::probe(const std::string &path, const uint8_t *head, uint64_t head_size)
{
    if (find_nifti_magic(head, head_size) != NiftiMagic::none)
        return 100;
    if (name_ends_with(path, ".nii") || name_ends_with(path, ".nii.gz"))
        return kSuffixConfidence;
    return 0;
}

void NiftiImporter::read_header(const std::string &path, const sdk::Task &task, arbor_volume &out)
{
    const std::string name = file_name_of(path);
    const std::string what = "header of " + name;
    const uint64_t file_size = require_readable_file(path);
    const NiftiEssentials essentials = check_nifti_header(path, name, file_size);

    VtkMessageRoute route(*this);
    vtkNew<vtkNIFTIImageReader> reader;
    reader->SetFileName(path.c_str());
    ReaderWatch watch(*reader, route, task);
    reader->UpdateInformation();
    watch.throw_if_failed(ARBOR_ERROR_FORMAT, what);

    const ImageLayout layout = image_layout(*reader, what);
    out.voxel_type = require_single_scalar(*reader, what);
    for (int a = 0; a < 3; ++a)
        out.dims[a] = layout.dim(a);
    if (essentials.dim[4] > 1)
        log(ARBOR_LOG_INFO, name + ": a series of " + std::to_string(essentials.dim[4]) +
                                " volumes; only the first is imported");

    vtkNIFTIImageHeader &h = *reader->GetNIFTIHeader();
    const NiftiPlacement placement = place_nifti(space_of(h));
    placement.geometry.write_to(out);
    log(ARBOR_LOG_DEBUG, name + ": geometry from the " + placement.source);
    const NiftiValueMapping mapping = nifti_value_mapping(h.GetSclSlope(), h.GetSclInter());
    out.value_scale = mapping.scale;
    out.value_offset = mapping.offset;
    task.progress(1.0);
}

void NiftiImporter::read_voxels(const std::string &path, const sdk::Task &task,
                                arbor_volume &volume)
{
    const std::string name = file_name_of(path);
    const std::string what = "voxels of " + name;
    // The file may have changed since read_header: check again before VTK
    // relies on it.
    check_nifti_header(path, name, require_readable_file(path));
    constexpr double kReadShare = 0.9; // of the progress bar; copying is the rest

    VtkMessageRoute route(*this);
    vtkNew<vtkNIFTIImageReader> reader;
    reader->SetFileName(path.c_str());
    ReaderWatch watch(*reader, route, task, 0.0, kReadShare);
    reader->Update();
    watch.throw_if_failed(ARBOR_ERROR_FORMAT, what);

    vtkImageData *image = reader->GetOutput();
    if (!image)
        sdk::fail(ARBOR_ERROR_FORMAT, what + ": the reader produced no image");
    require_same_dims(*image, volume, what);
    vtkDataArray *scalars = image->GetPointData()->GetScalars();
    if (!scalars)
        sdk::fail(ARBOR_ERROR_FORMAT, what + ": the reader produced no voxels");
    const SliceOrder order = reader->GetQFac() < 0 ? SliceOrder::reversed : SliceOrder::same;
    copy_scalars(*scalars, volume, order, task, kReadShare, what);
}

} // namespace arbor::importer_vtk
