#include "volume_view.hpp"

#include "workstation.hpp"

#include <GLFW/glfw3.h>
#include <glm/glm.hpp>
#include <imgui.h>

#include <cmath>
#include <cstdio>
#include <cstring>

namespace arbor::workstation {

namespace {

// The patient direction (R/L, A/P, I/S) a camera axis points to most.
char direction_letter(const glm::dvec3 &v)
{
    const glm::dvec3 a = glm::abs(v);
    if (a.x >= a.y && a.x >= a.z)
        return v.x > 0 ? 'L' : 'R';
    if (a.y >= a.z)
        return v.y > 0 ? 'P' : 'A';
    return v.z > 0 ? 'S' : 'I';
}

void draw_orientation(ImDrawList *dl, ImVec2 lo, ImVec2 hi, const arbor_camera &c)
{
    const glm::dvec3 pos(c.position[0], c.position[1], c.position[2]);
    const glm::dvec3 f = glm::normalize(glm::dvec3(c.focal_point[0], c.focal_point[1], c.focal_point[2]) - pos);
    glm::dvec3 r = glm::cross(f, glm::dvec3(c.view_up[0], c.view_up[1], c.view_up[2]));
    if (glm::length(r) < 1e-9)
        return;
    r = glm::normalize(r);
    const glm::dvec3 u = glm::cross(r, f);
    const ImU32 text = IM_COL32(230, 230, 230, 255);
    const float mx = (lo.x + hi.x) / 2, my = (lo.y + hi.y) / 2;
    char s[2] = {0, 0};
    s[0] = direction_letter(-r);
    dl->AddText({lo.x + 6, my - 7}, text, s);
    s[0] = direction_letter(r);
    dl->AddText({hi.x - 14, my - 7}, text, s);
    s[0] = direction_letter(u);
    dl->AddText({mx - 4, lo.y + 4}, text, s);
    s[0] = direction_letter(-u);
    dl->AddText({mx - 4, hi.y - 20}, text, s);
    // The marker: the patient's L (red), P (green) and S (blue) axes as the
    // camera sees them, in the lower left corner.
    const ImVec2 o{lo.x + 40, hi.y - 40};
    const glm::dvec3 axes[3] = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
    const ImU32 colours[3] = {IM_COL32(230, 80, 80, 255), IM_COL32(80, 200, 80, 255), IM_COL32(90, 130, 255, 255)};
    const char *names[3] = {"L", "P", "S"};
    for (int a = 0; a < 3; ++a) {
        const float x = static_cast<float>(glm::dot(axes[a], r)) * 28, y = -static_cast<float>(glm::dot(axes[a], u)) * 28;
        dl->AddLine(o, {o.x + x, o.y + y}, colours[a], 2.5f);
        dl->AddText({o.x + x * 1.15f - 3, o.y + y * 1.15f - 6}, colours[a], names[a]);
    }
}

} // namespace

void VolumeView::reserve(uint32_t width, uint32_t height)
{
    texture_.reserve(width, height, false);
    rgba_.assign(static_cast<std::size_t>(width) * height * 4, 0);
}

void VolumeView::draw(Workstation &ws)
{
    const ImVec2 avail = ImGui::GetContentRegionAvail();
    const uint32_t w = static_cast<uint32_t>(std::max(16.0f, avail.x)), h = static_cast<uint32_t>(std::max(16.0f, avail.y));
    ws.set_viewport(w, h);
    const auto frame = ws.volume_view().latest();
    if (frame && frame->gpu) {
        drawn_ = frame;
        shown_ = frame.get();
    } else if (frame && frame.get() != shown_ && frame->image.width > 0) {
        drawn_.reset();
        const auto &bg = ws.document().view.background;
        const float back[3] = {static_cast<float>(bg[0]), static_cast<float>(bg[1]), static_cast<float>(bg[2])};
        to_rgba8(frame->image.rgba, back, rgba_);
        // Shown pixel for pixel: nearest sampling is exact, and a software
        // OpenGL's bilinear filter costs a good part of a frame.
        texture_.upload(rgba_.data(), frame->image.width, frame->image.height, false);
        shown_ = frame.get();
    }
    if (texture_.empty()) {
        // A black pixel until the first frame: drawing a texture the first
        // time makes a software OpenGL compile its shader (hundreds of ms on
        // llvmpipe), better at startup than while the first jobs run.
        // (The relation wheel's scaled, linearly filtered texture draws from
        // the start too, with its one-pixel stand-in.)
        reserve(w, h);
    }
    const ImVec2 lo = ImGui::GetCursorScreenPos();
    const ImVec2 hi{lo.x + w, lo.y + h};
    ImDrawList *dl = ImGui::GetWindowDrawList();
    // The frame keeps its own size while a new one for the new viewport renders.
    if (drawn_) {
        const GlFrame &g = *drawn_->gpu;
        ImGui::Image(reinterpret_cast<void *>(static_cast<intptr_t>(g.texture)),
                     ImVec2(static_cast<float>(g.width), static_cast<float>(g.height)));
    } else {
        ImGui::Image(texture_.imgui_id(),
                     ImVec2(static_cast<float>(texture_.width()), static_cast<float>(texture_.height())), ImVec2(0, 0),
                     ImVec2(texture_.u_max(), texture_.v_max()));
    }
    ImGui::SetCursorScreenPos(lo);
    ImGui::InvisibleButton("volume-view", ImVec2(static_cast<float>(w), static_cast<float>(h)),
                           ImGuiButtonFlags_MouseButtonLeft | ImGuiButtonFlags_MouseButtonMiddle |
                               ImGuiButtonFlags_MouseButtonRight);
    const bool hovered = ImGui::IsItemHovered();
    ImGuiIO &io = ImGui::GetIO();
    try {
        if (ImGui::IsItemActive()) {
            const ImVec2 d = io.MouseDelta;
            if (d.x != 0 || d.y != 0) {
                dragging_ = true;
                const bool pan = ImGui::IsMouseDown(ImGuiMouseButton_Middle) ||
                                 (ImGui::IsMouseDown(ImGuiMouseButton_Left) && io.KeyShift);
                if (pan) {
                    // A pixel is the view's height in mm over its height in pixels.
                    const arbor_camera c = ws.pipeline().camera();
                    const double dist = std::hypot(c.position[0] - c.focal_point[0], c.position[1] - c.focal_point[1],
                                                   c.position[2] - c.focal_point[2]);
                    const double mm = (c.projection == ARBOR_PROJECTION_PERSPECTIVE
                                           ? 2 * dist * std::tan(c.view_angle * M_PI / 360.0)
                                           : 2 * c.parallel_scale) / h;
                    ws.pan_by(-d.x * mm, d.y * mm);
                } else if (ImGui::IsMouseDown(ImGuiMouseButton_Left)) {
                    ws.rotate(-0.4 * d.x, 0.4 * d.y);
                } else if (ImGui::IsMouseDown(ImGuiMouseButton_Right)) {
                    ws.zoom_by(std::exp(-0.01 * d.y));
                }
            }
        }
        if (ImGui::IsItemDeactivated()) {
            if (dragging_)
                ws.commit("move the camera");
            else if (ImGui::IsMouseReleased(ImGuiMouseButton_Left))
                ws.pick(io.MousePos.x - lo.x, io.MousePos.y - lo.y); // a click: pick
            dragging_ = false;
        }
        if (hovered && io.MouseWheel != 0) {
            ws.zoom_by(std::pow(1.1, io.MouseWheel), true);
        }
        if (hovered && !io.WantTextInput) {
            static const std::pair<int, const char *> keys[] = {
                {GLFW_KEY_A, "anterior"}, {GLFW_KEY_P, "posterior"}, {GLFW_KEY_L, "left"},
                {GLFW_KEY_R, "right"},    {GLFW_KEY_S, "superior"},  {GLFW_KEY_I, "inferior"},
                {GLFW_KEY_HOME, "reset"}};
            for (const auto &[key, name] : keys)
                if (ImGui::IsKeyPressed(key, false) && !io.KeyCtrl)
                    ws.standard_view(name);
        }
    } catch (const std::exception &e) {
        ws.say(ARBOR_LOG_ERROR, e.what());
    }
    if (ws.has_input()) {
        try {
            draw_orientation(dl, lo, hi, ws.pipeline().camera());
        } catch (const std::exception &) {
        }
    }
    char caption[128] = "";
    if (frame) {
        if (frame->preview)
            std::snprintf(caption, sizeof caption, "preview from the values: the contour tree is being computed");
        else if (frame->pass == ARBOR_RENDER_PASS_COARSE)
            std::snprintf(caption, sizeof caption, "coarse  %.0f ms", frame->seconds * 1000);
        else if (frame->pass == ARBOR_RENDER_PASS_FULL)
            std::snprintf(caption, sizeof caption, "full  %.0f ms", frame->seconds * 1000);
        else
            std::snprintf(caption, sizeof caption, "refined x%u", frame->samples + 1);
    } else if (ws.has_input()) {
        std::snprintf(caption, sizeof caption, "computing...");
    } else {
        std::snprintf(caption, sizeof caption, "Open a volume: File > Open, drop a file or folder here");
    }
    if (frame && frame->gpu) // drawn in the window's OpenGL context, no read back
        std::strncat(caption, ", on the GPU", sizeof caption - std::strlen(caption) - 1);
    dl->AddText({hi.x - ImGui::CalcTextSize(caption).x - 8, lo.y + 4}, IM_COL32(200, 200, 200, 255), caption);
}

} // namespace arbor::workstation
