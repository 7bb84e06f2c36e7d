#include "series_cells.hpp"

#include "dicom/value_text.hpp"

#include <imgui.h>

namespace arbor::workstation {

void setup_series_columns()
{
    for (const char *h : {"patient", "study", "series", "modality", "description"})
        ImGui::TableSetupColumn(h, ImGuiTableColumnFlags_WidthStretch, 1.0f);
}

void draw_series_cells(const SeriesCells &c)
{
    ImGui::TableNextColumn();
    ImGui::Text("%s %s", c.patient_name.c_str(), c.patient_id.c_str());
    ImGui::TableNextColumn();
    ImGui::Text("%s %s", dicom::display_date(c.study_date).c_str(), c.study_description.c_str());
    ImGui::TableNextColumn();
    ImGui::TextUnformatted(c.number.c_str());
    ImGui::TableNextColumn();
    ImGui::TextUnformatted(c.modality.c_str());
    ImGui::TableNextColumn();
    ImGui::TextUnformatted(c.description.c_str());
}

} // namespace arbor::workstation
