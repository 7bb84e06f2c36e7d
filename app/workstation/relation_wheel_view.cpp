#include "relation_wheel_view.hpp"

#include "workstation.hpp"

#include <imgui.h>

#include <algorithm>

namespace arbor::workstation {

void RelationWheelView::draw(Workstation &ws)
{
    if (texture_.empty()) {
        // Drawn once at startup: the software OpenGL compiles its shader for
        // linear filtering now, not when the first legend arrives mid-job.
        const uint8_t clear[4] = {0, 0, 0, 0};
        texture_.upload(clear, 1, 1, true);
        ImGui::Image(texture_.imgui_id(), ImVec2(1, 1), ImVec2(0, 0), ImVec2(texture_.u_max(), texture_.v_max()));
    }
    const auto legend = ws.pipeline().latest<pipeline::Stage::Legend>();
    if (ws.document().appearance.legend.empty()) {
        ImGui::TextDisabled("no legend (choose one under Legend)");
        return;
    }
    if (!legend || legend->size == 0) {
        ImGui::TextDisabled(ws.has_input() ? "the legend is being drawn" : "no volume");
        return;
    }
    if (legend.get() != shown_) {
        const float back[3] = {0.1f, 0.1f, 0.12f};
        std::vector<uint8_t> rgba;
        to_rgba8(legend->rgba, back, rgba);
        texture_.upload(rgba.data(), legend->size, legend->size, true);
        shown_ = legend.get();
    }
    const ImVec2 avail = ImGui::GetContentRegionAvail();
    const float side = std::max(32.0f, std::min(avail.x, avail.y - 20));
    ImGui::Text("around branch %u (%s)", legend->selected, pipeline::short_name(legend->depictor.id).c_str());
    ImGui::Image(texture_.imgui_id(), ImVec2(side, side), ImVec2(0, 0), ImVec2(texture_.u_max(), texture_.v_max()));
}

} // namespace arbor::workstation
