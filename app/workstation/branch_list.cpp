#include "branch_list.hpp"

#include "workstation.hpp"

#include <imgui.h>

#include <cstdio>

namespace arbor::workstation {

using pipeline::Stage;

void BranchList::draw(Workstation &ws)
{
    const auto cut = ws.pipeline().latest<Stage::Cut>();
    const auto filtered = ws.pipeline().latest<Stage::Filter>();
    if (!cut || !filtered) {
        ImGui::TextDisabled("no branches yet");
        return;
    }
    const arbor_branch_tree &t = cut->tree->record();
    const auto &colors = ws.colors();
    const std::vector<double> shares = ws.visibility_shares();
    const auto selected = ws.document().appearance.selected;
    ViewState &v = ws.view();
    const ValueMapping &mapping = filtered->volume->mapping();
    const int volume_column = [&] {
        for (uint32_t m = 0; m < t.measure_count; ++m)
            if (std::string(t.measure_ids[m]) == ARBOR_MEASURE_VOLUME)
                return static_cast<int>(m);
        return -1;
    }();
    const bool edited = !ws.document().view.branch_styles.empty();
    if (!edited)
        ImGui::BeginDisabled();
    if (ImGui::SmallButton("Reset edits"))
        ws.reset_branch_styles();
    if (!edited)
        ImGui::EndDisabled();
    ImGui::SameLine();
    ImGui::TextDisabled("colour, show and opacity edits follow a structure until reset");
    const ImGuiTableFlags flags = ImGuiTableFlags_RowBg | ImGuiTableFlags_ScrollY | ImGuiTableFlags_BordersInnerV;
    if (!ImGui::BeginTable("branches", 7, flags))
        return;
    ImGui::TableSetupScrollFreeze(0, 1);
    ImGui::TableSetupColumn("", ImGuiTableColumnFlags_WidthFixed, 18);
    ImGui::TableSetupColumn("show", ImGuiTableColumnFlags_WidthFixed, 34);
    ImGui::TableSetupColumn("branch");
    ImGui::TableSetupColumn("opacity", ImGuiTableColumnFlags_WidthFixed, 54);
    ImGui::TableSetupColumn("visible");
    ImGui::TableSetupColumn(mapping.unit.empty() ? "values" : mapping.unit.c_str());
    ImGui::TableSetupColumn("voxels");
    ImGui::TableHeadersRow();
    for (uint32_t b = 0; b < t.branch_count; ++b) {
        ImGui::TableNextRow();
        ImGui::PushID(static_cast<int>(b));
        pipeline::BranchStyle style = ws.branch_style(b);
        bool restyled = false, live = false;
        ImGui::TableNextColumn();
        float c[3] = {0.5f, 0.5f, 0.5f};
        if (style.color)
            for (int k = 0; k < 3; ++k)
                c[k] = static_cast<float>((*style.color)[k]);
        else if (b < colors.size())
            for (int k = 0; k < 3; ++k)
                c[k] = colors[b][k];
        if (ImGui::ColorEdit3("##colour", c, ImGuiColorEditFlags_NoInputs | ImGuiColorEditFlags_NoLabel)) {
            style.color = std::array<double, 3>{c[0], c[1], c[2]};
            restyled = true;
            live = true; // the picker is being dragged
        }
        ImGui::TableNextColumn();
        if (ImGui::Checkbox("##show", &style.visible))
            restyled = true;
        ImGui::TableNextColumn();
        char name[64];
        std::snprintf(name, sizeof name, "%u %s", b,
                      b == 0 ? "root" : t.extremum_kind[b] == ARBOR_EXTREMUM_MAXIMUM ? "max" : "min");
        const bool is_selected = selected && static_cast<uint32_t>(*selected) == b;
        if (ImGui::Selectable(name, is_selected || v.hovered == b, ImGuiSelectableFlags_SpanAllColumns)) {
            try {
                ws.select(is_selected ? std::nullopt : std::optional<int32_t>(static_cast<int32_t>(b)));
            } catch (const std::exception &e) {
                ws.say(ARBOR_LOG_ERROR, e.what());
            }
        }
        if (ImGui::IsItemHovered())
            v.hovered = b;
        ImGui::TableNextColumn();
        float opacity = static_cast<float>(style.opacity);
        ImGui::SetNextItemWidth(-1);
        if (ImGui::DragFloat("##opacity", &opacity, 0.02f, 0.0f, 10.0f, "x%.2f", ImGuiSliderFlags_AlwaysClamp)) {
            style.opacity = opacity;
            restyled = true;
            live = true;
        }
        if (ImGui::IsItemHovered())
            ImGui::SetTooltip("opacity: a multiple of the structure's optical depth (x2: as if twice as dense)");
        if (ImGui::IsItemDeactivatedAfterEdit())
            ws.commit("opacity of branch " + std::to_string(b));
        if (restyled) {
            try {
                ws.set_branch_style(b, style, !live);
            } catch (const std::exception &e) {
                ws.say(ARBOR_LOG_ERROR, e.what());
            }
        }
        ImGui::TableNextColumn();
        if (b < shares.size())
            ImGui::Text("%.1f %%", 100 * shares[b]);
        else
            ImGui::TextDisabled("-");
        ImGui::TableNextColumn();
        ImGui::Text("%.0f .. %.0f", mapping.physical(t.saddle_value[b]), mapping.physical(t.extremum_value[b]));
        ImGui::TableNextColumn();
        if (volume_column >= 0)
            ImGui::Text("%.0f", t.measures[std::size_t{b} * t.measure_count + static_cast<uint32_t>(volume_column)]);
        ImGui::PopID();
    }
    ImGui::EndTable();
}

} // namespace arbor::workstation
