#include "job_panel.hpp"

#include "workstation.hpp"

#include <imgui.h>

namespace arbor::workstation {

void JobPanel::draw(Workstation &ws)
{
    const auto jobs = ws.jobs();
    if (ws.cancelled()) {
        if (ImGui::SmallButton("Resume"))
            ws.resume();
        ImGui::SameLine();
        ImGui::TextDisabled("cancelled");
    } else if (jobs.empty()) {
        ImGui::TextDisabled(ws.idle() ? "idle" : "rendering");
    } else if (ImGui::SmallButton("Cancel all")) {
        ws.cancel();
    }
    for (const auto &job : jobs) {
        ImGui::PushID(static_cast<int>(job->serial()));
        const std::string activity = job->activity();
        char overlay[160];
        std::snprintf(overlay, sizeof overlay, "%s%s%s", pipeline::stage_name(job->stage()), activity.empty() ? "" : ": ",
                      activity.c_str());
        ImGui::ProgressBar(static_cast<float>(job->fraction()), ImVec2(-70, 0), overlay);
        ImGui::SameLine();
        if (ImGui::SmallButton("Cancel"))
            job->cancel();
        ImGui::PopID();
    }
    const auto &messages = ws.messages();
    const std::size_t first = messages.size() > 4 ? messages.size() - 4 : 0;
    for (std::size_t i = first; i < messages.size(); ++i) {
        const Message &m = messages[i];
        const ImVec4 colour = m.level >= ARBOR_LOG_ERROR     ? ImVec4(1, 0.45f, 0.4f, 1)
                              : m.level >= ARBOR_LOG_WARNING ? ImVec4(1, 0.8f, 0.3f, 1)
                                                             : ImVec4(0.75f, 0.75f, 0.75f, 1);
        ImGui::TextColored(colour, "%s", m.text.c_str());
    }
}

} // namespace arbor::workstation
