// vtk_file_kind.hpp - what a VTK file holds, told from its first bytes: XML
// or legacy layout, and the dataset type it declares.
#pragma once

#include <string>
#include <string_view>

namespace arbor::importer_vtk {

enum class VtkLayout { unknown, xml, legacy };

struct VtkFileKind {
    VtkLayout layout = VtkLayout::unknown;
    // XML: the type attribute of <VTKFile> ("ImageData"); legacy: the word
    // after DATASET, upper-cased ("STRUCTURED_POINTS"); "" when the bytes
    // seen do not say.
    std::string dataset;
    bool binary = false; // legacy only: BINARY rather than ASCII

    bool is_image() const;
};

VtkFileKind classify_vtk_file(std::string_view head);

} // namespace arbor::importer_vtk
