// series_cells.hpp - the columns a series has in the DICOM browser, the same
// on its Folder and PACS tabs: patient, study, series number, modality,
// description.
#pragma once

#include <string>

namespace arbor::workstation {

struct SeriesCells {
    const std::string &patient_name, &patient_id, &study_date, &study_description;
    const std::string &number, &modality, &description;
};

// Inside BeginTable: the five columns' headers (before TableHeadersRow).
void setup_series_columns();
// The five cells of one row (TableNextColumn for each).
void draw_series_cells(const SeriesCells &cells);

} // namespace arbor::workstation
