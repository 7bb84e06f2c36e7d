#include "tree_view.hpp"

#include "workstation.hpp"

#include <imgui.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <vector>

namespace arbor::workstation {

using pipeline::Stage;

namespace {

ImU32 colour_of(const std::vector<std::array<float, 3>> &colors, uint32_t b, float alpha = 1)
{
    if (b >= colors.size())
        return IM_COL32(200, 200, 200, 255);
    return ImGui::ColorConvertFloat4ToU32({colors[b][0], colors[b][1], colors[b][2], alpha});
}

} // namespace

void TreeView::draw(Workstation &ws)
{
    const auto cut = ws.pipeline().latest<Stage::Cut>();
    if (!cut) {
        ImGui::TextDisabled(ws.has_input() ? "the contour tree is being computed" : "no volume");
        return;
    }
    const arbor_branch_tree &t = cut->tree->record();
    const uint32_t n = t.branch_count;
    const ImVec2 avail = ImGui::GetContentRegionAvail();
    const ImVec2 lo = ImGui::GetCursorScreenPos();
    const ImVec2 size{std::max(avail.x, 50.0f), std::max(avail.y, 50.0f)};
    ImGui::InvisibleButton("tree-view", size);
    const bool hovered = ImGui::IsItemHovered();
    ImDrawList *dl = ImGui::GetWindowDrawList();
    dl->AddRectFilled(lo, {lo.x + size.x, lo.y + size.y}, IM_COL32(25, 25, 30, 255));
    // x: branches in depth-first order, leaves spread evenly; y: value.
    double vmin = INFINITY, vmax = -INFINITY;
    for (uint32_t b = 0; b < n; ++b) {
        vmin = std::min({vmin, t.saddle_value[b], t.extremum_value[b]});
        vmax = std::max({vmax, t.saddle_value[b], t.extremum_value[b]});
    }
    if (!(vmax > vmin))
        vmax = vmin + 1;
    std::vector<float> x(n, 0);
    int column = 0;
    std::function<void(uint32_t)> place = [&](uint32_t b) {
        const uint32_t first = t.child_offsets[b], last = t.child_offsets[b + 1];
        // A branch sits left of its children, so the root is the leftmost line.
        x[b] = static_cast<float>(column++);
        for (uint32_t c = first; c < last; ++c)
            place(t.children[c]);
    };
    place(0);
    const float margin = 14;
    const auto sx = [&](uint32_t b) { return lo.x + margin + x[b] / std::max(1, column - 1) * (size.x - 2 * margin); };
    const auto sy = [&](double v) {
        return lo.y + size.y - margin - static_cast<float>((v - vmin) / (vmax - vmin)) * (size.y - 2 * margin);
    };
    const auto &colors = ws.colors();
    const auto selected = ws.document().appearance.selected;
    std::optional<uint32_t> under;
    float best = 6;
    const ImVec2 mouse = ImGui::GetIO().MousePos;
    for (uint32_t b = 0; b < n; ++b) {
        const float bx = sx(b), y0 = sy(t.saddle_value[b]), y1 = sy(t.extremum_value[b]);
        const bool chosen = selected && static_cast<uint32_t>(*selected) == b;
        const bool hover = ws.view().hovered == b;
        const float width = chosen ? 4.0f : hover ? 3.0f : 2.0f;
        if (t.parent[b] >= 0)
            dl->AddLine({sx(static_cast<uint32_t>(t.parent[b])), y0}, {bx, y0}, IM_COL32(120, 120, 120, 255), 1.0f);
        dl->AddLine({bx, y0}, {bx, y1}, colour_of(colors, b), width);
        dl->AddCircleFilled({bx, y1}, chosen ? 5.0f : 3.0f, colour_of(colors, b));
        if (hovered && mouse.y >= std::min(y0, y1) - 4 && mouse.y <= std::max(y0, y1) + 4 && std::fabs(mouse.x - bx) < best) {
            best = std::fabs(mouse.x - bx);
            under = b;
        }
    }
    if (hovered) {
        ws.view().hovered = under;
        if (under) {
            const uint32_t b = *under;
            ImGui::BeginTooltip();
            ImGui::Text("branch %u (%s)", b, b == 0 ? "root" : t.extremum_kind[b] == ARBOR_EXTREMUM_MAXIMUM ? "maximum" : "minimum");
            ImGui::Text("values %.1f .. %.1f", t.saddle_value[b], t.extremum_value[b]);
            if (t.importance)
                ImGui::Text("importance %.4g", t.importance[b]);
            for (uint32_t m = 0; m < t.measure_count; ++m)
                ImGui::Text("%s %.4g", t.measure_ids[m], t.measures[std::size_t{b} * t.measure_count + m]);
            ImGui::EndTooltip();
            if (ImGui::IsMouseClicked(ImGuiMouseButton_Left)) {
                try {
                    ws.select(static_cast<int32_t>(b));
                } catch (const std::exception &e) {
                    ws.say(ARBOR_LOG_ERROR, e.what());
                }
            }
        }
    }
}

} // namespace arbor::workstation
