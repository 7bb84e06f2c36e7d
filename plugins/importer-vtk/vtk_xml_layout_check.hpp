// vtk_xml_layout_check.hpp - what VTK 9.1's XML image reader trusts in a
// file, checked before it reads the file.
//
// Compressed binary arrays start with a header: the number of blocks, the
// size of a block and of the last one uncompressed, then each block's
// compressed size.  VTK trusts it: the block count sizes its block tables,
// each compressed size a read buffer, each uncompressed size a decompression
// buffer, a block size of 0 divides by zero, and a last block larger than
// the others (or one without blocks) makes it read past its tables.  So a few
// bytes could claim terabytes.  And a piece reaching outside the image's whole
// extent is read in parts, whose buffers VTK leaks when a part fails.
//
// So the headers and the piece extents are read here, independently, and
// refused unless the headers fit in the file and describe no block larger
// than its array, and every piece lies inside the image.
#pragma once

#include <cstdint>
#include <string>

namespace arbor::importer_vtk {

// Throws ARBOR_ERROR_FORMAT naming `what` and the array or piece.  Files
// VTK's XML parser cannot parse pass (its reader then says what is wrong).
void check_xml_image_layout(const std::string &path, uint64_t file_size, const std::string &what);

} // namespace arbor::importer_vtk
