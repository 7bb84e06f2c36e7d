// vtk_image_importer.cpp - probing, header and voxels of VTK image files.
//
// VTK image data has no anatomical frame: its world axes are whatever the
// writer meant.  They are taken as the SDK's LPS axes unchanged, so the
// volume lands where VTK itself would draw it.
#include "vtk_image_importer.hpp"

#include "grid_geometry.hpp"
#include "input_file.hpp"
#include "reader_watch.hpp"
#include "scalar_copy.hpp"
#include "vtk_file_kind.hpp"
#include "vtk_image_reader.hpp"
#include "vtk_message_route.hpp"
#include "vtk_voxel_type.hpp"
#include "vtk_xml_layout_check.hpp"

#include <vtkAlgorithm.h>
#include <vtkDataArray.h>
#include <vtkImageData.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace arbor::importer_vtk {

const arbor_plugin_descriptor kVtkImageDescriptor = {
    sizeof(arbor_plugin_descriptor),
    ARBOR_PLUGIN_FLAG_NONE,
    "org.arbor.importer.vtk-image",
    ARBOR_KIND_IMPORTER,
    "VTK image data",
    "1.0.0",
    "Arbor",
    "Reads VTK image data (XML .vti and legacy STRUCTURED_POINTS .vtk) with VTK's readers, "
    "taking VTK's unoriented axes as LPS.",
    "",
};

namespace {

// Enough of the start of a file for the XML root element or the legacy
// header lines.
constexpr std::size_t kSniffBytes = 4096;

// Confidence for a VTK file of another dataset type: low, but above zero so
// that this importer is picked and explains why it cannot read the file.
constexpr int32_t kOtherVtkConfidence = 10;
constexpr int32_t kSuffixConfidence = 30;

// VTK 9.1's legacy structured-points reader dereferences a null pointer
// when a data-set FIELD block before POINT_DATA cannot be read (it sets the
// field data it failed to read and deletes it: a fuzzed file crashed it).
// Its keywords are whitespace-separated words matched by their first five
// letters, lower-cased, and may follow a number without a space ("0FIELD"
// after ORIGIN's last value), so every word of the header after the title
// is looked at, its leading number characters skipped, up to POINT_DATA or
// CELL_DATA. Such blocks are refused before VTK reads them.
constexpr std::size_t kLegacyHeaderBytes = 64 * 1024;

// The next whitespace-separated word of `head` from `at`, lower-cased, and
// where it ends; an empty word and npos when none is left.
std::pair<std::string, std::size_t> next_word(const std::string &head, std::size_t at)
{
    const std::size_t start = head.find_first_not_of(" \t\r\n", at);
    if (start == std::string::npos)
        return {std::string(), std::string::npos};
    const std::size_t end = std::min(head.find_first_of(" \t\r\n", start), head.size());
    std::string word = head.substr(start, end - start);
    for (char &c : word)
        c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    return {word, end};
}

// The words of `head` from `at`, at most `count`.
std::vector<std::string> words_from(const std::string &head, std::size_t at, std::size_t count)
{
    std::vector<std::string> words;
    while (words.size() < count) {
        auto [word, end] = next_word(head, at);
        if (end == std::string::npos)
            break;
        words.push_back(std::move(word));
        at = end;
    }
    return words;
}

// Point data given as a FIELD: VTK 9.1 reads every array of it, strings
// too, and a fuzzed binary string array with a garbage length kept it
// copying for minutes.  Arbor reads one numeric array, so a point-data FIELD
// must hold exactly one, of a numeric type named exactly.
void refuse_odd_point_field(const std::string &head, std::size_t after_point_data, const std::string &name)
{
    // POINT_DATA n, then FIELD name count, then: array components tuples type
    const std::vector<std::string> w = words_from(head, after_point_data, 8);
    if (w.size() < 2 || w[1].compare(0, 5, "field") != 0)
        return;
    static const std::vector<std::string> numeric = {"bit",   "unsigned_char", "char",  "unsigned_short",
                                                     "short", "unsigned_int",  "int",   "unsigned_long",
                                                     "long",  "float",         "double", "vtkidtype"};
    if (w.size() < 8 || w[3] != "1" || std::find(numeric.begin(), numeric.end(), w[7]) == numeric.end())
        sdk::fail(ARBOR_ERROR_UNSUPPORTED,
                  name + ": point data given as a FIELD must hold one array of a numeric type (unsigned_char, "
                         "short, float...); this one does not");
}

void refuse_legacy_dataset_field(const std::string &path, const std::string &name)
{
    const std::string head = read_file_start(path, kLegacyHeaderBytes);
    std::size_t at = 0;
    for (int line = 0; line < 2 && at != std::string::npos; ++line) // "# vtk DataFile ...", the title
        at = head.find('\n', at) == std::string::npos ? std::string::npos : head.find('\n', at) + 1;
    while (at != std::string::npos && at < head.size()) {
        const auto [word, end] = next_word(head, at);
        if (end == std::string::npos)
            break;
        if (word.rfind("point_data", 0) == 0 || word.rfind("cell_data", 0) == 0) {
            refuse_odd_point_field(head, end, name);
            return;
        }
        const std::size_t letters = word.find_first_not_of("0123456789+-.e");
        if (letters != std::string::npos && word.compare(letters, 5, "field") == 0)
            sdk::fail(ARBOR_ERROR_UNSUPPORTED,
                      name + ": a FIELD block before POINT_DATA (field data of the whole data set) is not "
                             "read: VTK 9.1's legacy reader crashes on one it cannot read; write the "
                             "image without it");
        at = end;
    }
}

VtkFileKind identify(const std::string &path, const std::string &name)
{
    const VtkFileKind kind = classify_vtk_file(read_file_start(path, kSniffBytes));
    if (kind.layout == VtkLayout::legacy)
        refuse_legacy_dataset_field(path, name);
    switch (kind.layout) {
    case VtkLayout::unknown:
        sdk::fail(ARBOR_ERROR_FORMAT, name + ": not a VTK image file (it starts neither with an "
                                             "XML <VTKFile> element nor with '# vtk DataFile')");
    case VtkLayout::xml:
        if (kind.dataset.empty())
            sdk::fail(ARBOR_ERROR_FORMAT,
                      name + ": the <VTKFile> element does not say its type (type=\"ImageData\")");
        if (!kind.is_image())
            sdk::fail(ARBOR_ERROR_UNSUPPORTED, name + ": a VTK XML file of type " + kind.dataset +
                                                   "; this importer reads ImageData (.vti) only");
        break;
    case VtkLayout::legacy:
        if (kind.dataset.empty())
            sdk::fail(ARBOR_ERROR_FORMAT,
                      name + ": the legacy VTK header has no DATASET line after its title and "
                             "ASCII/BINARY lines");
        if (!kind.is_image())
            sdk::fail(ARBOR_ERROR_UNSUPPORTED,
                      name + ": legacy VTK dataset type " + kind.dataset +
                          " is not image data; this importer reads STRUCTURED_POINTS only");
        break;
    }
    return kind;
}

// A legacy file stores every voxel explicitly (binary: at least one byte per
// value, ASCII: a digit and a separator), so a header claiming more voxels
// than the file can hold is refused before the reader allocates for them.
void require_room_for_voxels(const ImageLayout &layout, const VtkFileKind &kind,
                             uint64_t file_size, const std::string &what)
{
    if (kind.layout != VtkLayout::legacy)
        return;
    const arbor_voxel_type type = layout.known ? voxel_type_of(layout.vtk_type) : 0;
    const double value_bytes = kind.binary ? (type ? arbor_voxel_size(type) : 1.0) : 2.0;
    const double voxels = double(layout.dim(0)) * double(layout.dim(1)) * double(layout.dim(2));
    const double least = voxels * value_bytes - (kind.binary ? 0.0 : 1.0);
    if (least > double(file_size))
        sdk::fail(ARBOR_ERROR_FORMAT,
                  what + ": the header claims " + std::to_string(layout.dim(0)) + " x " +
                      std::to_string(layout.dim(1)) + " x " + std::to_string(layout.dim(2)) +
                      " voxels, which need at least " + std::to_string(uint64_t(least)) +
                      " bytes, but the file holds " + std::to_string(file_size) +
                      " (truncated or a wrong DIMENSIONS line)");
}

std::string array_label(const ImageLayout &layout)
{
    return layout.array_name.empty() ? std::string("the unnamed point-data array")
                                     : "point-data array '" + layout.array_name + "'";
}

arbor_voxel_type require_single_scalar(const ImageLayout &layout, const std::string &what)
{
    if (!layout.known)
        sdk::fail(ARBOR_ERROR_FORMAT, what + ": the image has no point-data array to import");
    if (layout.components != 1)
        sdk::fail(ARBOR_ERROR_UNSUPPORTED,
                  what + ": " + array_label(layout) + " has " + std::to_string(layout.components) +
                      " components per voxel; only single-component scalars can be imported");
    const arbor_voxel_type type = voxel_type_of(layout.vtk_type);
    if (type == ARBOR_VOXEL_UNKNOWN)
        sdk::fail(ARBOR_ERROR_UNSUPPORTED,
                  what + ": " + array_label(layout) + " holds " + vtk_type_name(layout.vtk_type) +
                      " values, which have no Arbor voxel type (8-, 16- and 32-bit integers, "
                      "float and double are supported)");
    return type;
}

// VTK places point (i, j, k) of the extent at origin + D * (spacing * (i, j,
// k)); the volume's voxel (0, 0, 0) is the extent's first point.
GridGeometry image_geometry(const ImageLayout &layout, const std::string &what)
{
    for (double v : layout.direction)
        if (!std::isfinite(v))
            sdk::fail(ARBOR_ERROR_FORMAT, what + ": the direction matrix is not finite");
    std::array<double, 9> steps{};
    for (int r = 0; r < 3; ++r)
        for (int c = 0; c < 3; ++c)
            steps[3 * r + c] = layout.direction[3 * r + c] * layout.spacing[c];
    std::array<double, 3> first = layout.origin;
    for (int r = 0; r < 3; ++r)
        for (int c = 0; c < 3; ++c)
            first[r] += steps[3 * r + c] * layout.extent[2 * c];
    return geometry_from_affine(steps, first);
}

} // namespace

VtkImageImporter::VtkImageImporter(const arbor_host *host)
    : sdk::Importer(kVtkImageDescriptor, host, ".vti;.vtk")
{
}

int32_t VtkImageImporter::probe(const std::string &path, const uint8_t *head,
                                uint64_t head_size)
{
    const VtkFileKind kind = classify_vtk_file(
        std::string_view(reinterpret_cast<const char *>(head), head ? head_size : 0));
    if (kind.is_image())
        return 100;
    if (kind.layout != VtkLayout::unknown)
        return kOtherVtkConfidence;
    if (name_ends_with(path, ".vti") || name_ends_with(path, ".vtk"))
        return kSuffixConfidence;
    return 0;
}

void VtkImageImporter::read_header(const std::string &path, const sdk::Task &task,
                                   arbor_volume &out)
{
    const std::string name = file_name_of(path);
    const std::string what = "header of " + name;
    const uint64_t file_size = require_readable_file(path);
    const VtkFileKind kind = identify(path, name);
    // VTK's legacy reader reports short or unparsable data only as warnings.
    const bool warnings_fail = kind.layout == VtkLayout::legacy;

    VtkMessageRoute route(*this);
    if (kind.layout == VtkLayout::xml)
        check_xml_image_layout(path, file_size, what);
    vtkSmartPointer<vtkAlgorithm> reader = make_image_reader(kind.layout, path);
    ReaderWatch watch(*reader, route, task);
    reader->UpdateInformation();
    watch.throw_if_failed(ARBOR_ERROR_FORMAT, what, warnings_fail);
    ImageLayout layout = image_layout(*reader, what);
    require_room_for_voxels(layout, kind, file_size, what);
    if (!layout.known && kind.layout == VtkLayout::legacy) {
        // Point data given as a FIELD names its type only next to the values;
        // the check above bounds what reading them allocates.
        reader->Update();
        watch.throw_if_failed(ARBOR_ERROR_FORMAT, what, warnings_fail);
        if (auto *image = vtkImageData::SafeDownCast(reader->GetOutputDataObject(0))) {
            const ImageLayout read = image_layout(*image);
            layout.known = read.known;
            layout.array_name = read.array_name;
            layout.vtk_type = read.vtk_type;
            layout.components = read.components;
        }
    }
    out.voxel_type = require_single_scalar(layout, what);
    for (int a = 0; a < 3; ++a)
        out.dims[a] = layout.dim(a);
    image_geometry(layout, what).write_to(out);
    task.progress(1.0);
}

void VtkImageImporter::read_voxels(const std::string &path, const sdk::Task &task,
                                   arbor_volume &volume)
{
    const std::string name = file_name_of(path);
    const std::string what = "voxels of " + name;
    const uint64_t file_size = require_readable_file(path);
    const VtkFileKind kind = identify(path, name);
    const bool warnings_fail = kind.layout == VtkLayout::legacy;
    constexpr double kReadShare = 0.9; // of the progress bar; copying is the rest

    VtkMessageRoute route(*this);
    if (kind.layout == VtkLayout::xml)
        check_xml_image_layout(path, file_size, what);
    vtkSmartPointer<vtkAlgorithm> reader = make_image_reader(kind.layout, path);
    ReaderWatch watch(*reader, route, task, 0.0, kReadShare);
    reader->UpdateInformation();
    watch.throw_if_failed(ARBOR_ERROR_FORMAT, what, warnings_fail);
    const ImageLayout layout = image_layout(*reader, what);
    read_only_array(*reader, layout.array_name);
    reader->Update();
    watch.throw_if_failed(ARBOR_ERROR_FORMAT, what, warnings_fail);

    auto *image = vtkImageData::SafeDownCast(reader->GetOutputDataObject(0));
    if (!image)
        sdk::fail(ARBOR_ERROR_FORMAT, what + ": the reader produced no image");
    require_same_dims(*image, volume, what);
    vtkDataArray *scalars = layout_array(*image, layout);
    if (!scalars)
        sdk::fail(ARBOR_ERROR_FORMAT, what + ": the reader produced no point-data array");
    copy_scalars(*scalars, volume, SliceOrder::same, task, kReadShare, what);
}

} // namespace arbor::importer_vtk
