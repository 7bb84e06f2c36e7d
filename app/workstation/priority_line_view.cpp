#include "priority_line_view.hpp"

#include "workstation.hpp"

#include "topology/branch_decomposition.hpp"

#include <imgui.h>

#include <algorithm>
#include <cmath>
#include <numeric>
#include <vector>

namespace arbor::workstation {

using pipeline::Stage;


void PriorityLineView::build_rows(Workstation &ws, const pipeline::CutResult &cut)
{
    const topology::BranchDecomposition &d = cut.decomposition->branches;
    const std::size_t n = d.branches.size();
    const std::string current = pipeline::short_name(cut.decomposition->simplifier.id);
    std::vector<Row> &rows = rows_;
    rows.clear();
    {
        Row r{current, std::vector<double>(n, 0), true};
        for (std::size_t b = 1; b < n; ++b)
            r.values[b] = std::isfinite(d.branches[b].importance) ? d.branches[b].importance : 0;
        r.top = *std::max_element(r.values.begin(), r.values.end());
        if (!(r.top > 0))
            r.top = 1;
        rows.push_back(std::move(r));
    }
    const std::pair<const char *, int> measures[] = {
        {"persistence", topology::kPersistence}, {"volume", topology::kVolume}, {"hypervolume", topology::kHypervolume}};
    for (const auto &[name, m] : measures) {
        if (name == current)
            continue;
        try {
            ws.catalog().find(ARBOR_KIND_SIMPLIFIER, name);
        } catch (const std::exception &) {
            continue; // not installed
        }
        Row r{name, std::vector<double>(n, 0), false};
        for (std::size_t b = 1; b < n; ++b)
            r.values[b] = d.relative(static_cast<uint32_t>(b), m);
        r.top = *std::max_element(r.values.begin(), r.values.end());
        if (!(r.top > 0))
            r.top = 1;
        rows.push_back(std::move(r));
    }
    // The current simplifier's order, most important first (the root left out).
    std::vector<uint32_t> &order = order_;
    order.assign(n > 0 ? n - 1 : 0, 0);
    std::iota(order.begin(), order.end(), 1u);
    std::stable_sort(order.begin(), order.end(),
                     [&](uint32_t a, uint32_t b) { return rows[0].values[a] > rows[0].values[b]; });
}

void PriorityLineView::draw(Workstation &ws)
{
    const auto cut = ws.pipeline().latest<Stage::Cut>();
    if (!cut) {
        ImGui::TextDisabled(ws.has_input() ? "the contour tree is being computed" : "no volume");
        return;
    }
    if (cut != rows_of_) {
        build_rows(ws, *cut);
        rows_of_ = cut;
    }
    const std::vector<Row> &rows = rows_;
    const std::vector<uint32_t> &order = order_;
    const std::size_t n = cut->decomposition->branches.branches.size();
    const auto &kept_index = cut->cut.kept_index;
    const auto &colors = ws.colors();
    const ImVec2 avail = ImGui::GetContentRegionAvail();
    const float row_h = std::max(40.0f, (avail.y - 30) / static_cast<float>(rows.size()));
    ImDrawList *dl = ImGui::GetWindowDrawList();
    // Lowest importance kept: where the current row's threshold line is.
    double lowest_kept = 0;
    for (uint32_t b : order)
        if (kept_index[b] >= 0)
            lowest_kept = rows[0].values[b];
    for (const Row &row : rows) {
        const double top = row.top;
        const ImVec2 lo = ImGui::GetCursorScreenPos();
        const ImVec2 size{avail.x, row_h - 4};
        ImGui::PushID(row.simplifier.c_str());
        ImGui::InvisibleButton("row", size);
        const bool active = ImGui::IsItemActive();
        ImGui::PopID();
        dl->AddRectFilled(lo, {lo.x + size.x, lo.y + size.y}, IM_COL32(25, 25, 30, 255));
        const float plot_h = size.y - 16;
        const float base = lo.y + size.y - 2;
        // The most important branches, at least three pixels a line: the
        // kept ones and as many again (a noisy scan's long tail of tiny
        // branches would be a flat line of pixels).
        const std::size_t shown = std::min(order.size(), std::max<std::size_t>(
                                                              {3 * cut->kept(), 64, static_cast<std::size_t>(size.x / 3)}));
        const float px_per = shown > 0 ? size.x / static_cast<float>(shown) : 1;
        int last_px = -1;
        float tallest = 0;
        for (std::size_t i = 0; i < shown; ++i) {
            const uint32_t b = order[i];
            const float h = static_cast<float>(row.values[b] / top) * plot_h;
            const int px = static_cast<int>(static_cast<float>(i) * px_per);
            if (px == last_px && h <= tallest)
                continue;
            tallest = px == last_px ? std::max(tallest, h) : h;
            last_px = px;
            const bool kept = row.current && kept_index[b] >= 0;
            ImU32 c = IM_COL32(110, 110, 110, 255);
            if (kept) {
                const uint32_t label = static_cast<uint32_t>(kept_index[b]);
                c = label < colors.size()
                        ? ImGui::ColorConvertFloat4ToU32({colors[label][0], colors[label][1], colors[label][2], 1})
                        : IM_COL32(230, 200, 80, 255);
            }
            const float x = lo.x + static_cast<float>(i) * px_per + px_per / 2;
            dl->AddLine({x, base}, {x, base - std::max(1.0f, h)}, c, std::max(1.0f, std::min(3.0f, px_per - 1)));
        }
        // The threshold line.
        float fraction = 0;
        if (row.current)
            fraction = static_cast<float>(lowest_kept / top);
        if (row.current || dragging_ == row.simplifier) {
            const float y = base - fraction * plot_h;
            dl->AddLine({lo.x, y}, {lo.x + size.x, y}, IM_COL32(255, 80, 80, 255), 2.0f);
        }
        char title[96];
        std::snprintf(title, sizeof title, "%s%s", row.simplifier.c_str(), row.current ? "  (drag the red line)" : "");
        dl->AddText({lo.x + 4, lo.y + 1}, IM_COL32(220, 220, 220, 255), title);
        if (active) {
            const float y = ImGui::GetIO().MousePos.y;
            const double f = std::clamp((base - y) / plot_h, 0.0f, 1.0f);
            try {
                if (!row.current) {
                    pipeline::Document doc = ws.document();
                    doc.simplifier = {row.simplifier, "", {}};
                    ws.change(doc, "simplifier " + row.simplifier, false);
                }
                dragging_ = row.simplifier;
                ws.drag_threshold(f, false);
            } catch (const std::exception &e) {
                ws.say(ARBOR_LOG_ERROR, e.what());
            }
        }
        if (ImGui::IsItemDeactivated() && dragging_ == row.simplifier) {
            ws.commit("threshold");
            dragging_.clear();
        }
    }
    // Keep-N instead of a threshold.
    int keep = static_cast<int>(cut->kept());
    ImGui::SetNextItemWidth(avail.x * 0.6f);
    if (ImGui::SliderInt("keep", &keep, 1, static_cast<int>(std::min<std::size_t>(n, 200)))) {
        try {
            ws.set("keep", std::to_string(keep), false);
        } catch (const std::exception &e) {
            ws.say(ARBOR_LOG_ERROR, e.what());
        }
    }
    if (ImGui::IsItemDeactivatedAfterEdit())
        ws.commit("keep " + std::to_string(keep));
    ImGui::SameLine();
    if (ImGui::Button("knee"))
        try {
            ws.set("keep", "knee");
        } catch (const std::exception &e) {
            ws.say(ARBOR_LOG_ERROR, e.what());
        }
}

} // namespace arbor::workstation
