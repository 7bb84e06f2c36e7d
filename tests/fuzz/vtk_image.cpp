// vtk_image.cpp - fuzzes the VTK image importer (plugins/importer-vtk): the
// sniffing of XML and legacy files, our checks before VTK's readers allocate,
// and what the importer does with their answers, through the host's import
// flow.  The input is one VTK file, XML image data (.vti) or legacy
// STRUCTURED_POINTS (.vtk); the importer tells them apart by content.
#include "fuzz_support.hpp"
#include "host_import.hpp"

#include "vtk_file_kind.hpp"

#include <string_view>

// A legacy file stores every value, in at least one byte (binary) or two
// characters (ASCII), so its voxels take at most 8 bytes per file byte; the
// importer promises to refuse larger claims before the host allocates.  XML
// files may compress their data without a stated bound.
constexpr uint64_t kLegacyBytesPerFileByte = 8;

extern "C" int LLVMFuzzerTestOneInput(const uint8_t *data, std::size_t size)
{
    const auto path = arbor::fuzz::write_input("input.vtk", data, size);
    const auto kind = arbor::importer_vtk::classify_vtk_file({reinterpret_cast<const char *>(data), size});
    const uint64_t bound = kind.layout == arbor::importer_vtk::VtkLayout::legacy ? kLegacyBytesPerFileByte * (size + 1) : 0;
    arbor::fuzz::import_through_host("org.arbor.importer.vtk-image", path, {bound, {}});
    return 0;
}
