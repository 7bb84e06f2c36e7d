#include "dicom_browser.hpp"

#include "series_cells.hpp"
#include "workstation.hpp"

#include <imgui.h>

#include <cstdio>

namespace arbor::workstation {

namespace fs = std::filesystem;

namespace {

struct ScanCancelled {};

// How the importer's "series" parameter names the series at `row` of the
// scan: its UID, or its 1-based row when it has none (an anonymised export).
std::string selector(const dicom::Series &series, std::size_t row)
{
    return series.uid.empty() ? std::to_string(row + 1) : series.uid;
}

} // namespace

DicomBrowser::~DicomBrowser() { cancel(); }

void DicomBrowser::cancel()
{
    if (cancelled_)
        cancelled_->store(true);
    if (pending_.valid())
        pending_.wait();
    pending_ = {};
}

void DicomBrowser::scan(const fs::path &folder, bool open_single)
{
    cancel();
    std::snprintf(path_, sizeof path_, "%s", folder.c_str());
    shown_ = true;
    select_pacs_ = 0;
    open_single_ = open_single;
    result_.reset();
    error_.clear();
    progress_ = std::make_shared<std::atomic<double>>(0.0);
    cancelled_ = std::make_shared<std::atomic<bool>>(false);
    pending_ = std::async(std::launch::async, [folder, progress = progress_, cancelled = cancelled_] {
        auto s = std::make_shared<Scan>();
        s->folder = dicom::scan_dicom(folder, [&](double f) {
            if (cancelled->load())
                throw ScanCancelled{};
            progress->store(0.8 * f);
        });
        for (std::size_t i = 0; i < s->folder.series.size(); ++i) {
            if (cancelled->load())
                throw ScanCancelled{};
            s->series.push_back(dicom::summarise_series(s->folder.series[i]));
            progress->store(0.8 + 0.2 * static_cast<double>(i + 1) / static_cast<double>(s->folder.series.size()));
        }
        return s;
    });
}

void DicomBrowser::draw(Workstation &ws)
{
    if (!shown_)
        return;
    if (pending_.valid() && pending_.wait_for(std::chrono::seconds(0)) == std::future_status::ready) {
        try {
            result_ = pending_.get();
        } catch (const ScanCancelled &) {
            error_ = "scan cancelled";
        } catch (const std::exception &e) {
            error_ = e.what();
        }
        pending_ = {};
        if (result_ && open_single_) {
            const dicom::SeriesSummary *only = nullptr;
            std::size_t only_row = 0;
            int readable = 0;
            for (std::size_t i = 0; i < result_->series.size(); ++i)
                if (result_->series[i].layout) {
                    only = &result_->series[i];
                    only_row = i;
                    ++readable;
                }
            if (readable == 1) {
                try {
                    pipeline::Document d = ws.document();
                    d.input = {};
                    d.input.path = path_;
                    d.input.importer.params["series"] = selector(*only->series, only_row);
                    ws.open_document(d, "open " + fs::path(path_).filename().string());
                    shown_ = false;
                } catch (const std::exception &e) {
                    error_ = e.what();
                }
            }
        }
    }
    pacs_.poll();
    ImGui::SetNextWindowSize({980, 420}, ImGuiCond_FirstUseEver);
    if (!ImGui::Begin("DICOM browser", &shown_)) {
        ImGui::End();
        return;
    }
    if (ImGui::BeginTabBar("sources")) {
        if (ImGui::BeginTabItem("Folder", nullptr, select_pacs_ == 0 ? ImGuiTabItemFlags_SetSelected : 0)) {
            draw_folder(ws);
            ImGui::EndTabItem();
        }
        if (ImGui::BeginTabItem("PACS", nullptr, select_pacs_ == 1 ? ImGuiTabItemFlags_SetSelected : 0)) {
            pacs_.draw(ws);
            ImGui::EndTabItem();
        }
        select_pacs_ = -1;
        ImGui::EndTabBar();
    }
    ImGui::End();
    if (pacs_.take_opened())
        shown_ = false;
}

void DicomBrowser::show_pacs()
{
    shown_ = true;
    select_pacs_ = 1;
}

void DicomBrowser::draw_folder(Workstation &ws)
{
    ImGui::SetNextItemWidth(600);
    const bool enter = ImGui::InputText("folder", path_, sizeof path_, ImGuiInputTextFlags_EnterReturnsTrue);
    ImGui::SameLine();
    if (ImGui::Button("Scan") || enter)
        scan(path_, false);
    if (pending_.valid()) {
        ImGui::ProgressBar(static_cast<float>(progress_->load()), ImVec2(-80, 0), "scanning the folder");
        ImGui::SameLine();
        if (ImGui::Button("Cancel"))
            cancelled_->store(true);
    }
    if (!error_.empty())
        ImGui::TextColored({1, 0.45f, 0.4f, 1}, "%s", error_.c_str());
    if (result_) {
        const auto &f = result_->folder;
        ImGui::Text("%zu series; %zu files unreadable, %zu not DICOM", result_->series.size(), f.unreadable.size(),
                    f.not_dicom.size());
        const ImGuiTableFlags flags = ImGuiTableFlags_RowBg | ImGuiTableFlags_ScrollY | ImGuiTableFlags_Resizable |
                                      ImGuiTableFlags_BordersInnerV;
        if (ImGui::BeginTable("series", 8, flags)) {
            ImGui::TableSetupColumn("", ImGuiTableColumnFlags_WidthFixed, 40);
            setup_series_columns();
            ImGui::TableSetupColumn("volume", ImGuiTableColumnFlags_WidthFixed, 210);
            ImGui::TableSetupColumn("reading", ImGuiTableColumnFlags_WidthStretch, 3.0f);
            ImGui::TableSetupScrollFreeze(0, 1);
            ImGui::TableHeadersRow();
            for (std::size_t i = 0; i < result_->series.size(); ++i) {
                const dicom::SeriesSummary &s = result_->series[i];
                const dicom::ImageRecord &r = s.series->first();
                ImGui::TableNextRow();
                ImGui::PushID(static_cast<int>(i));
                ImGui::TableNextColumn();
                if (!s.layout)
                    ImGui::BeginDisabled();
                if (ImGui::SmallButton("Open")) {
                    try {
                        pipeline::Document d = ws.document();
                        d.input = {};
                        d.input.path = path_;
                        d.input.importer.params["series"] = selector(*s.series, i);
                        ws.open_document(d, "open series " + r.series_number + " of " + fs::path(path_).filename().string());
                        shown_ = false;
                    } catch (const std::exception &e) {
                        error_ = e.what();
                    }
                }
                if (!s.layout)
                    ImGui::EndDisabled();
                draw_series_cells({r.patient_name, r.patient_id, r.study_date, r.study_description, r.series_number,
                                   r.modality, r.series_description});
                ImGui::TableNextColumn();
                if (s.layout)
                    ImGui::Text("%lldx%lldx%lld, %.2fx%.2fx%.2f mm", static_cast<long long>(s.layout->dims[0]),
                                static_cast<long long>(s.layout->dims[1]), static_cast<long long>(s.layout->dims[2]),
                                s.layout->spacing[0], s.layout->spacing[1], s.layout->spacing[2]);
                ImGui::TableNextColumn();
                if (!s.refusal.empty())
                    ImGui::TextColored({1, 0.6f, 0.4f, 1}, "cannot: %s", s.refusal.c_str());
                else if (s.notes.empty())
                    ImGui::TextDisabled("as stored");
                for (const std::string &n : s.notes)
                    ImGui::TextWrapped("%s", n.c_str());
                ImGui::PopID();
            }
            ImGui::EndTable();
        }
    }
}

} // namespace arbor::workstation
