// table_text.hpp - cells of the CLI's text tables (`arbor dicom ls`,
// `arbor pacs find`, `arbor pacs nodes`).
#pragma once

#include <string>

namespace arbor::cli {

// At most `width` bytes, never cutting a UTF-8 character in half; "~" marks a cut.
std::string clip(const std::string &s, std::size_t width);

} // namespace arbor::cli
