#include "parameter_panel.hpp"

#include "workstation.hpp"

#include "host/param_text.hpp"

#include <imgui.h>

#include <algorithm>
#include <cmath>
#include <cstring>

namespace arbor::workstation {

namespace {

// One parameter's widget; true when the value changed (`live` while it is
// being dragged).
bool param_widget(const arbor_param_desc &desc, std::string &text, bool &live)
{
    ParamText parsed;
    try {
        parsed = parse_param_value(desc, text);
    } catch (const std::exception &) {
        parsed = parse_param_value(desc, format_param_default(desc));
    }
    arbor_param_value v = parsed.value;
    bool changed = false;
    const char *label = desc.name && *desc.name ? desc.name : desc.id;
    ImGui::PushID(desc.id);
    switch (desc.type) {
    case ARBOR_PARAM_FLOAT:
    case ARBOR_PARAM_INT: {
        const bool integer = desc.type == ARBOR_PARAM_INT;
        double lo = desc.min_value, hi = desc.max_value;
        if (desc.components == 1 && std::isfinite(lo) && std::isfinite(hi) && hi - lo < 1e9) {
            // A range far wider than the values in use ([0, 1e6] for a flow
            // rate of 60) gets a slider over ten times the default (or the
            // value); Ctrl+click types any value within the real bounds.
            // (Of the default only, so the scale does not move under a drag; a
            // typed value beyond it stretches it.)
            const double typical = std::max(std::fabs(desc.default_value[0]), 1.0);
            const bool soft = hi - lo > 1000 * typical;
            if (soft)
                hi = std::min(hi, std::max(lo + 10 * typical, v.number[0]));
            const bool logarithmic = (desc.flags & ARBOR_PARAM_FLAG_LOG_SCALE) != 0;
            const ImGuiSliderFlags flags = (soft ? 0 : ImGuiSliderFlags_AlwaysClamp) |
                                           (logarithmic ? ImGuiSliderFlags_Logarithmic : 0);
            changed = ImGui::SliderScalar(label, ImGuiDataType_Double, &v.number[0], &lo, &hi, integer ? "%.0f" : "%.4g", flags);
        } else {
            changed = ImGui::InputScalarN(label, ImGuiDataType_Double, v.number, static_cast<int>(desc.components), nullptr,
                                          nullptr, integer ? "%.0f" : "%.4g");
        }
        if (integer)
            for (uint32_t c = 0; c < desc.components; ++c)
                v.number[c] = std::round(v.number[c]);
        for (uint32_t c = 0; c < desc.components; ++c)
            v.number[c] = std::clamp(v.number[c], desc.min_value, desc.max_value);
        live = ImGui::IsItemActive();
        break;
    }
    case ARBOR_PARAM_BOOL: {
        bool b = v.number[0] != 0;
        changed = ImGui::Checkbox(label, &b);
        v.number[0] = b ? 1 : 0;
        break;
    }
    case ARBOR_PARAM_CHOICE: {
        int index = static_cast<int>(v.number[0]);
        const auto name_of = [&](uint32_t i) {
            return desc.choice_names && desc.choice_names[i] ? desc.choice_names[i] : desc.choices[i];
        };
        if (ImGui::BeginCombo(label, index >= 0 && static_cast<uint32_t>(index) < desc.choice_count ? name_of(index) : "?")) {
            for (uint32_t i = 0; i < desc.choice_count; ++i)
                if (ImGui::Selectable(name_of(i), static_cast<uint32_t>(index) == i)) {
                    index = static_cast<int>(i);
                    changed = true;
                }
            ImGui::EndCombo();
        }
        v.number[0] = index;
        break;
    }
    default: { // STRING, PATH: applied on Enter or when the field is left
        char buf[1024];
        std::snprintf(buf, sizeof buf, "%s", parsed.storage.c_str());
        ImGui::InputText(label, buf, sizeof buf);
        if (ImGui::IsItemDeactivatedAfterEdit()) {
            parsed.storage = buf;
            changed = true;
        }
        v.text = parsed.storage.c_str();
        break;
    }
    }
    if (desc.hint && *desc.hint && ImGui::IsItemHovered())
        ImGui::SetTooltip("%s%s%s", desc.hint, desc.unit && *desc.unit ? "\nunit: " : "", desc.unit ? desc.unit : "");
    ImGui::PopID();
    if (changed) {
        std::string next = format_param_value(desc, v);
        if (next == text)
            return false;
        text = std::move(next);
    }
    return changed;
}

} // namespace

bool ParameterPanel::plugin_controls(Workstation &ws, const char *kind, const char *label, pipeline::PluginSetting &setting,
                                     bool optional, bool &live, std::string &what)
{
    bool changed = false;
    const auto plugins = ws.catalog().registry().plugins_of_kind(kind);
    const std::string current = setting.empty() ? "none" : pipeline::short_name(setting.id);
    ImGui::PushID(label);
    if (ImGui::BeginCombo(label, current.c_str())) {
        if (optional && ImGui::Selectable("none", setting.empty())) {
            setting = {};
            changed = true;
            what = std::string(label) + " none";
        }
        for (const PluginInfo *p : plugins) {
            const bool chosen = setting.id == p->descriptor->id;
            if (ImGui::Selectable(p->descriptor->name && *p->descriptor->name ? p->descriptor->name : p->descriptor->id, chosen) &&
                !chosen) {
                setting = {p->descriptor->id, "", {}};
                changed = true;
                what = std::string(label) + " " + pipeline::short_name(setting.id);
            }
            if (ImGui::IsItemHovered() && p->descriptor->description)
                ImGui::SetTooltip("%s%s", p->descriptor->description,
                                  p->library->isolated()
                                      ? "\n\nRuns isolated in a process of its own: if it crashes or hangs, the "
                                        "call fails, the session carries on, and the plugin restarts at its next call."
                                      : "");
        }
        ImGui::EndCombo();
    }
    if (!changed && !setting.empty()) {
        std::vector<const arbor_param_desc *> descriptions;
        try {
            descriptions = ws.catalog().descriptions(setting.id);
        } catch (const std::exception &) {
        }
        bool advanced_open = false, advanced_seen = false;
        for (const arbor_param_desc *d : descriptions) {
            if (d->flags & ARBOR_PARAM_FLAG_ADVANCED) {
                if (!advanced_seen) {
                    advanced_seen = true;
                    advanced_open = ImGui::TreeNode("advanced");
                }
                if (!advanced_open)
                    continue;
            }
            std::string &text = setting.params[d->id];
            bool dragging = false;
            if (param_widget(*d, text, dragging)) {
                changed = true;
                what = std::string(d->id) + " " + text;
            }
            live = live || dragging;
        }
        if (advanced_open)
            ImGui::TreePop();
    }
    ImGui::PopID();
    return changed;
}

void ParameterPanel::draw(Workstation &ws)
{
    pipeline::Document d = ws.document();
    bool changed = false, live = false;
    std::string what;
    // The input filter: automatic denoising, none, or one filter.
    if (ImGui::CollapsingHeader("Input filter", ImGuiTreeNodeFlags_DefaultOpen)) {
        const char *modes[] = {"auto (denoise when noisy)", "none", "filter"};
        int mode = !d.filters.empty() ? 2 : d.auto_denoise ? 0 : 1;
        if (ImGui::Combo("mode", &mode, modes, 3)) {
            changed = true;
            what = std::string("filter ") + modes[mode];
            d.auto_denoise = mode == 0;
            d.filters.clear();
            if (mode == 2) {
                const auto filters = ws.catalog().registry().plugins_of_kind(ARBOR_KIND_FILTER);
                if (!filters.empty())
                    d.filters.push_back({filters.front()->descriptor->id, "", {}});
            }
        }
        if (!changed && !d.filters.empty())
            changed = plugin_controls(ws, ARBOR_KIND_FILTER, "filter", d.filters.front(), false, live, what);
    }
    if (!changed && ImGui::CollapsingHeader("Simplifier", ImGuiTreeNodeFlags_DefaultOpen))
        changed = plugin_controls(ws, ARBOR_KIND_SIMPLIFIER, "simplifier", d.simplifier, false, live, what);
    if (!changed && ImGui::CollapsingHeader("Relation", ImGuiTreeNodeFlags_DefaultOpen))
        changed = plugin_controls(ws, ARBOR_KIND_DEPICTOR, "relation", d.appearance.depictor, true, live, what);
    if (!changed && ImGui::CollapsingHeader("Transfer functions", ImGuiTreeNodeFlags_DefaultOpen)) {
        changed = plugin_controls(ws, ARBOR_KIND_TF_GENERATOR, "generator", d.appearance.generator, false, live, what);
        if (!changed && ImGui::Checkbox("balance visibility", &d.appearance.balance_visibility)) {
            changed = true;
            what = "balance-visibility";
        }
    }
    if (!changed && ImGui::CollapsingHeader("Legend"))
        changed = plugin_controls(ws, ARBOR_KIND_DEPICTOR, "legend", d.appearance.legend, true, live, what);
    if (!changed && ImGui::CollapsingHeader("Renderer")) {
        changed = plugin_controls(ws, ARBOR_KIND_RENDERER, "renderer", d.view.renderer, false, live, what);
        bool ortho = !d.view.orbit.perspective;
        if (!changed && ImGui::Checkbox("orthographic", &ortho)) {
            d.view.orbit.perspective = !ortho;
            changed = true;
            what = "projection";
        }
        if (!changed && ImGui::Checkbox("frame the visible content", &d.view.frame_content)) {
            changed = true;
            what = "frame-content";
        }
    }
    if (changed) {
        try {
            ws.change(d, what, !live);
        } catch (const std::exception &e) {
            ws.say(ARBOR_LOG_ERROR, e.what());
        }
    } else if (!live && ImGui::IsMouseReleased(ImGuiMouseButton_Left)) {
        ws.commit("change a parameter"); // a drag that ended
    }
}

} // namespace arbor::workstation
