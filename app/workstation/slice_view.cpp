#include "slice_view.hpp"

#include "branch_colors.hpp"
#include "slice_image.hpp"
#include "workstation.hpp"

#include <imgui.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace arbor::workstation {

using pipeline::Stage;

namespace {

// Most CT and MR slices are 512 pixels a side or less.
constexpr int64_t kReserved = 1024;

} // namespace

void SliceView::reserve()
{
    texture_.reserve(kReserved, kReserved, false);
    image_.rgba.assign(static_cast<std::size_t>(kReserved * kReserved * 4), 0);
}

void SliceView::draw(Workstation &ws)
{
    const ImVec2 avail = ImGui::GetContentRegionAvail();
    const auto filtered = ws.pipeline().latest<Stage::Filter>();
    if (!filtered) {
        // A black pixel drawn until there is a volume (see VolumeView: the
        // software OpenGL compiles its shader for nearest filtering now).
        if (texture_.empty())
            reserve();
        ImGui::Image(texture_.imgui_id(), ImVec2(1, 1), ImVec2(0, 0), ImVec2(texture_.u_max(), texture_.v_max()));
        ImGui::TextDisabled("%s: no volume yet", orientation_name(orientation_));
        return;
    }
    const Volume &volume = *filtered->volume;
    const SliceGeometry s = slice_geometry(volume.geometry(), orientation_);
    ViewState &v = ws.view();
    const int64_t slice = v.crosshair[s.normal];
    // The labels and colours only when they belong to this volume.
    const auto labels = ws.pipeline().latest<Stage::Labels>();
    const auto tf = ws.pipeline().latest<Stage::TransferFunctions>();
    const bool labelled = v.overlay && labels && tf && labels->labels.size() == static_cast<std::size_t>(volume.voxel_count()) &&
                          tf->functions->branch_count() == labels->names.size();
    if (labelled && overlay_of_ != tf->functions) {
        overlay_colors_ = overlay_colors(ws.colors());
        overlay_of_ = tf->functions;
    }
    const auto selected = ws.document().appearance.selected;
    Key key{filtered->revision, labelled ? labels->revision : 0, slice, v.window.width, v.window.level,
            v.overlay_opacity, labelled, selected ? std::optional<uint32_t>(static_cast<uint32_t>(*selected)) : std::nullopt,
            ws.hidden_labels(), labelled ? static_cast<const void *>(tf->functions.get()) : nullptr};
    if (!(key == shown_) || texture_.empty()) {
        LabelOverlay overlay;
        if (labelled) {
            overlay.labels = labels->labels;
            overlay.colors = &overlay_colors_;
            overlay.opacity = v.overlay_opacity;
            overlay.selected = key.selected;
            overlay.hidden = &key.hidden;
        }
        slice_image(volume, s, slice, v.window, overlay, image_);
        texture_.upload(image_.rgba.data(), image_.width, image_.height, false);
        shown_ = key;
    }
    // Fit the slice's physical extent (non-square voxels) into the space.
    const double mm_w = s.width * s.x_spacing, mm_h = s.height * s.y_spacing;
    const float scale = static_cast<float>(std::min(avail.x / mm_w, (avail.y - 18) / mm_h));
    const ImVec2 size{static_cast<float>(mm_w) * scale, static_cast<float>(mm_h) * scale};
    const ImVec2 lo = ImGui::GetCursorScreenPos();
    ImGui::Image(texture_.imgui_id(), size, ImVec2(0, 0), ImVec2(texture_.u_max(), texture_.v_max()));
    const bool hovered = ImGui::IsItemHovered();
    ImDrawList *dl = ImGui::GetWindowDrawList();
    const ImVec2 hi{lo.x + size.x, lo.y + size.y};
    // The crosshair.
    const auto sc = s.screen(v.crosshair);
    const float cx = lo.x + (static_cast<float>(sc[0]) + 0.5f) * size.x / static_cast<float>(s.width);
    const float cy = lo.y + (static_cast<float>(sc[1]) + 0.5f) * size.y / static_cast<float>(s.height);
    const ImU32 cross = IM_COL32(255, 210, 60, 160);
    dl->AddLine({lo.x, cy}, {hi.x, cy}, cross);
    dl->AddLine({cx, lo.y}, {cx, hi.y}, cross);
    const ImU32 text = IM_COL32(230, 230, 230, 255);
    char edge[2] = {s.left, 0};
    dl->AddText({lo.x + 3, (lo.y + hi.y) / 2 - 7}, text, edge);
    edge[0] = s.right;
    dl->AddText({hi.x - 11, (lo.y + hi.y) / 2 - 7}, text, edge);
    edge[0] = s.top;
    dl->AddText({(lo.x + hi.x) / 2 - 4, lo.y + 2}, text, edge);
    edge[0] = s.bottom;
    dl->AddText({(lo.x + hi.x) / 2 - 4, hi.y - 16}, text, edge);
    // Where the slice is: its position along the patient axis, in mm.
    const auto centre = volume.geometry().position(static_cast<double>(v.crosshair[0]), static_cast<double>(v.crosshair[1]),
                                                   static_cast<double>(v.crosshair[2]));
    const int patient_axis = orientation_ == SliceOrientation::Axial ? 2 : orientation_ == SliceOrientation::Coronal ? 1 : 0;
    char line[160];
    std::snprintf(line, sizeof line, "%s %lld/%lld  %c %.1f mm", orientation_name(orientation_),
                  static_cast<long long>(slice + 1), static_cast<long long>(s.count), "LPS"[patient_axis],
                  centre[patient_axis]);
    ImGui::TextUnformatted(line);
    if (!hovered)
        return;
    ImGuiIO &io = ImGui::GetIO();
    const int64_t x = std::clamp<int64_t>(static_cast<int64_t>((io.MousePos.x - lo.x) / size.x * s.width), 0, s.width - 1);
    const int64_t y = std::clamp<int64_t>(static_cast<int64_t>((io.MousePos.y - lo.y) / size.y * s.height), 0, s.height - 1);
    const auto ijk = s.voxel(x, y, slice);
    const auto &dims = volume.geometry().dims;
    const int64_t voxel = ijk[0] + dims[0] * (ijk[1] + dims[1] * ijk[2]);
    const double value = volume.mapping().physical(volume.value(voxel));
    std::optional<uint32_t> label;
    if (labelled)
        label = labels->labels[static_cast<std::size_t>(voxel)];
    v.hovered = label;
    const std::string unit = volume.mapping().unit.empty() ? "" : " " + volume.mapping().unit;
    char under[160];
    if (label)
        std::snprintf(under, sizeof under, "(%lld, %lld, %lld)  %.1f%s  branch %u", static_cast<long long>(ijk[0]),
                      static_cast<long long>(ijk[1]), static_cast<long long>(ijk[2]), value, unit.c_str(), *label);
    else
        std::snprintf(under, sizeof under, "(%lld, %lld, %lld)  %.1f%s", static_cast<long long>(ijk[0]),
                      static_cast<long long>(ijk[1]), static_cast<long long>(ijk[2]), value, unit.c_str());
    dl->AddText({lo.x + 4, hi.y - 34}, text, under);
    try {
        if (io.MouseWheel != 0) {
            auto c = v.crosshair;
            c[s.normal] += io.MouseWheel > 0 ? 1 : -1;
            ws.move_crosshair(c);
        }
        if (ImGui::IsMouseClicked(ImGuiMouseButton_Left)) {
            ws.move_crosshair(ijk);
            ws.select(label && *label > 0 ? std::optional<int32_t>(static_cast<int32_t>(*label)) : std::nullopt);
        }
        if (ImGui::IsMouseDragging(ImGuiMouseButton_Right)) {
            // Right drag: horizontal is the width, vertical the level (Slicer's habit).
            const ImVec2 d = io.MouseDelta;
            const double step = std::max(1e-3, v.window.width / 300);
            ws.window_level(std::max(1e-6, v.window.width + d.x * step), v.window.level - d.y * step);
        }
    } catch (const std::exception &e) {
        ws.say(ARBOR_LOG_ERROR, e.what());
    }
}

} // namespace arbor::workstation
