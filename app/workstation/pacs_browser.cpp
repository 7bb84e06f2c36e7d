#include "pacs_browser.hpp"

#include "series_cells.hpp"
#include "workstation.hpp"

#include <imgui.h>

#include <cstdio>
#include <stdexcept>

namespace arbor::workstation {

PacsBrowser::~PacsBrowser() { cancel(); }

void PacsBrowser::cancel()
{
    stop_.request_stop();
    if (pending_.valid())
        pending_.wait();
    pending_ = {};
}

void PacsBrowser::load_nodes()
{
    nodes_loaded_ = true;
    try {
        nodes_ = dicom::read_nodes(dicom::default_nodes_file());
        nodes_problem_.clear();
        if (!nodes_.empty() && node_[0] == '\0')
            std::snprintf(node_, sizeof node_, "%s", nodes_.front().name.c_str());
    } catch (const std::exception &e) {
        nodes_problem_ = e.what();
    }
}

void PacsBrowser::search(const std::string &node_text, const dicom::PacsQuery &query)
{
    cancel();
    if (!nodes_loaded_)
        load_nodes();
    std::snprintf(node_, sizeof node_, "%s", node_text.c_str());
    error_.clear();
    rows_.clear();
    const dicom::PacsNode node = dicom::find_node(node_text, nodes_); // std::invalid_argument: said at once
    stop_ = {};
    searched_node_ = node_text;
    pending_ = std::async(std::launch::async, [node, query, stop = stop_.get_token()] {
        return dicom::connect(node, {30, stop})->find_series(query);
    });
}

void PacsBrowser::poll()
{
    if (!pending_.valid() || pending_.wait_for(std::chrono::seconds(0)) != std::future_status::ready)
        return;
    try {
        rows_ = pending_.get();
    } catch (const std::exception &e) {
        error_ = e.what();
    }
    pending_ = {};
}

void PacsBrowser::open(std::size_t row, Workstation &ws)
{
    if (row >= rows_.size())
        throw std::out_of_range("the search found " + std::to_string(rows_.size()) + " series; there is no row " +
                                std::to_string(row + 1));
    const dicom::SeriesRow &r = rows_[row];
    pipeline::Document d = ws.document();
    d.input = {};
    d.input.path = "pacs://" + searched_node_ + "/" + r.series_uid;
    ws.open_document(d, "open series " + r.series_number + " (" + r.modality + ") from " + searched_node_);
    opened_ = true;
}

void PacsBrowser::draw(Workstation &ws)
{
    if (!nodes_loaded_)
        load_nodes();
    poll();
    ImGui::SetNextItemWidth(360);
    ImGui::InputText("node", node_, sizeof node_);
    if (!nodes_.empty()) {
        ImGui::SameLine();
        ImGui::SetNextItemWidth(160);
        if (ImGui::BeginCombo("##configured", "configured...")) {
            for (const dicom::PacsNode &n : nodes_)
                if (ImGui::Selectable((n.name + "  " + n.describe()).c_str()))
                    std::snprintf(node_, sizeof node_, "%s", n.name.c_str());
            ImGui::EndCombo();
        }
    }
    ImGui::SameLine();
    if (ImGui::SmallButton("Reload nodes"))
        load_nodes();
    if (!nodes_problem_.empty())
        ImGui::TextColored({1, 0.45f, 0.4f, 1}, "%s", nodes_problem_.c_str());
    else if (nodes_.empty())
        ImGui::TextDisabled("No configured nodes (arbor pacs nodes add NAME AET@host:port); type one here.");
    const auto field = [](const char *label, char *text, std::size_t size, float width) {
        ImGui::SetNextItemWidth(width);
        const bool enter = ImGui::InputText(label, text, size, ImGuiInputTextFlags_EnterReturnsTrue);
        ImGui::SameLine();
        return enter;
    };
    bool go = field("patient", patient_, sizeof patient_, 160);
    go |= field("study date", date_, sizeof date_, 150);
    go |= field("modality", modality_, sizeof modality_, 50);
    go |= field("accession", accession_, sizeof accession_, 110);
    if (ImGui::Button(searching() ? "Searching..." : "Search") || go) {
        try {
            search(node_, {patient_, date_, modality_, accession_, ""});
        } catch (const std::exception &e) {
            error_ = e.what();
        }
    }
    if (ImGui::IsItemHovered())
        ImGui::SetTooltip("Patient: name with * and ? wildcards.  Study date: YYYYMMDD or YYYYMMDD-YYYYMMDD.");
    if (searching()) {
        ImGui::SameLine();
        if (ImGui::SmallButton("Cancel"))
            stop_.request_stop();
    }
    if (!error_.empty())
        ImGui::TextColored({1, 0.45f, 0.4f, 1}, "%s", error_.c_str());
    if (!searching() && error_.empty() && !searched_node_.empty())
        ImGui::Text("%zu series on %s.  Open retrieves a series into the PACS cache (progress in Jobs).",
                    rows_.size(), searched_node_.c_str());
    const ImGuiTableFlags flags = ImGuiTableFlags_RowBg | ImGuiTableFlags_ScrollY | ImGuiTableFlags_Resizable |
                                  ImGuiTableFlags_BordersInnerV;
    if (!rows_.empty() && ImGui::BeginTable("pacs-series", 7, flags)) {
        ImGui::TableSetupColumn("", ImGuiTableColumnFlags_WidthFixed, 40);
        setup_series_columns();
        ImGui::TableSetupColumn("images", ImGuiTableColumnFlags_WidthFixed, 60);
        ImGui::TableSetupScrollFreeze(0, 1);
        ImGui::TableHeadersRow();
        for (std::size_t i = 0; i < rows_.size(); ++i) {
            const dicom::SeriesRow &r = rows_[i];
            ImGui::TableNextRow();
            ImGui::PushID(static_cast<int>(i));
            ImGui::TableNextColumn();
            if (ImGui::SmallButton("Open")) {
                try {
                    open(i, ws);
                } catch (const std::exception &e) {
                    error_ = e.what();
                }
            }
            draw_series_cells(
                {r.patient_name, r.patient_id, r.study_date, r.study_description, r.series_number, r.modality, r.description});
            if (ImGui::IsItemHovered())
                ImGui::SetTooltip("%s", r.series_uid.c_str());
            ImGui::TableNextColumn();
            if (r.image_count >= 0)
                ImGui::Text("%d", r.image_count);
            ImGui::PopID();
        }
        ImGui::EndTable();
    }
}

} // namespace arbor::workstation
