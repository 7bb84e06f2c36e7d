// value_text.hpp - DICOM values as people read them, in listings of folders
// and archives: dates (DA) as 2002-06-04, person names (PN) with spaces for
// the ^ separators, counts (IS) as numbers.
#pragma once

#include <string>

namespace arbor::dicom {

// "20020604" -> "2002-06-04"; anything else unchanged.
std::string display_date(const std::string &da);
// "DOE^JOHN^^^" -> "DOE JOHN".
std::string display_person_name(std::string pn);
// An IS value as a count; -1 when empty or not a non-negative integer.
int count_value(const std::string &is);

} // namespace arbor::dicom
