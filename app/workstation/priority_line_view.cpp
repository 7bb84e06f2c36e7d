#include "priority_line_view.hpp"

#include "workstation.hpp"

#include "topology/branch_decomposition.hpp"

#include <imgui.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <numeric>
#include <vector>

namespace arbor::workstation {

using pipeline::Stage;


double PriorityLineView::value(const topology::BranchDecomposition &d, const Row &row, uint32_t branch)
{
    if (row.measure >= 0)
        return d.relative(branch, row.measure);
    const double importance = d.branches[branch].importance;
    return std::isfinite(importance) ? importance : 0.0;
}

PriorityScale PriorityScale::of(double top, double least)
{
    PriorityScale s;
    s.top = top > 0 ? top : 1;
    s.bottom = least > 0 && s.top / least > 100 ? std::max(least, s.top * 1e-6) : 0.0;
    return s;
}

double PriorityScale::height(double value) const
{
    if (!(value > 0))
        return 0;
    if (bottom > 0)
        return std::clamp(std::log(value / bottom) / std::log(top / bottom), 0.0, 1.0);
    return std::clamp(value / top, 0.0, 1.0);
}

double PriorityScale::value_at(double h) const
{
    h = std::clamp(h, 0.0, 1.0);
    return bottom > 0 ? bottom * std::pow(top / bottom, h) : h * top;
}

PriorityLineView::Ordering
PriorityLineView::order_branches(std::shared_ptr<const pipeline::DecompositionResult> decomposition,
                                 std::vector<Row> rows, std::size_t count)
{
    const topology::BranchDecomposition &d = decomposition->branches;
    const std::size_t n = d.branches.size();
    for (Row &row : rows) {
        row.top = 0;
        for (uint32_t b = 1; b < n; ++b)
            row.top = std::max(row.top, value(d, row, b));
        if (!(row.top > 0))
            row.top = 1;
    }
    // The current simplifier's order, most important first (the root left
    // out; equal importances by branch index), as far as `count`.
    const Row &current = rows[0];
    const auto before = [&](uint32_t a, uint32_t b) {
        const double va = value(d, current, a), vb = value(d, current, b);
        return va > vb || (va == vb && a < b);
    };
    std::vector<uint32_t> order(n > 0 ? n - 1 : 0);
    std::iota(order.begin(), order.end(), 1u);
    count = std::min(count, order.size());
    std::nth_element(order.begin(), order.begin() + static_cast<std::ptrdiff_t>(count), order.end(), before);
    order.resize(count);
    std::sort(order.begin(), order.end(), before);
    return {std::move(decomposition), std::move(rows), std::move(order)};
}

void PriorityLineView::start_ordering(Workstation &ws,
                                      const std::shared_ptr<const pipeline::DecompositionResult> &decomposition,
                                      std::size_t count)
{
    if (ordering_.valid())
        return;
    // The rows (which simplifiers are installed) here: the catalog is the UI thread's.
    const std::string current = pipeline::short_name(decomposition->simplifier.id);
    std::vector<Row> rows{Row{current, -1, true}};
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
        rows.push_back(Row{name, m, false});
    }
    try {
        ordering_ = std::async(std::launch::async, order_branches, decomposition, std::move(rows), count);
    } catch (const std::exception &e) { // no thread to be had
        ws.say(ARBOR_LOG_ERROR, std::string("priority lines: ") + e.what());
        failed_ = decomposition;
    }
}

void PriorityLineView::draw(Workstation &ws)
{
    showed_rows_ = false;
    const auto cut = ws.pipeline().latest<Stage::Cut>();
    if (!cut) {
        ImGui::TextDisabled(ws.has_input() ? "the contour tree is being computed" : "no volume");
        return;
    }
    const std::size_t n = cut->decomposition->branches.branches.size();
    const ImVec2 avail = ImGui::GetContentRegionAvail();
    // The most important branches, at least three pixels a line: the kept
    // ones and as many again (a noisy scan's long tail of tiny branches
    // would be a flat line of pixels).
    const std::size_t wanted = std::min(n > 0 ? n - 1 : 0, std::max<std::size_t>({3 * cut->kept(), 64,
                                                                                  static_cast<std::size_t>(avail.x / 3)}));
    if (ordering_.valid() && ordering_.wait_for(std::chrono::seconds(0)) == std::future_status::ready) {
        try {
            Ordering done = ordering_.get();
            rows_of_ = std::move(done.of);
            rows_ = std::move(done.rows);
            order_ = std::move(done.order);
        } catch (const std::exception &e) { // out of memory: the view says so, the window goes on
            ws.say(ARBOR_LOG_ERROR, std::string("priority lines: ") + e.what());
            failed_ = cut->decomposition;
        }
    }
    if (failed_ == cut->decomposition) {
        ImGui::TextDisabled("the branches could not be ordered");
        return;
    }
    if (cut->decomposition != rows_of_ || order_.size() < wanted)
        start_ordering(ws, cut->decomposition, std::max<std::size_t>(2 * wanted, 4096));
    if (cut->decomposition != rows_of_) {
        ImGui::TextDisabled("ordering %zu branches", n);
        return;
    }
    const topology::BranchDecomposition &d = rows_of_->branches;
    showed_rows_ = true;
    const std::vector<Row> &rows = rows_;
    const std::vector<uint32_t> &order = order_;
    const auto &kept_index = cut->cut.kept_index;
    const auto &colors = ws.colors();
    const float row_h = std::max(40.0f, (avail.y - 30) / static_cast<float>(rows.size()));
    ImDrawList *dl = ImGui::GetWindowDrawList();
    // Lowest importance kept: where the current row's threshold line is.
    double lowest_kept = 0;
    bool any_kept = false;
    for (const uint32_t b : cut->cut.kept)
        if (b != 0) {
            lowest_kept = any_kept ? std::min(lowest_kept, value(d, rows[0], b)) : value(d, rows[0], b);
            any_kept = true;
        }
    const std::size_t shown = std::min(order.size(), wanted);
    for (const Row &row : rows) {
        // The scale of what is shown (the rest of the order is in reserve).
        double least = row.top;
        for (std::size_t i = 0; i < shown; ++i)
            if (const double v = value(d, row, order[i]); v > 0)
                least = std::min(least, v);
        const PriorityScale scale = PriorityScale::of(row.top, least);
        const ImVec2 lo = ImGui::GetCursorScreenPos();
        const ImVec2 size{avail.x, row_h - 4};
        ImGui::PushID(row.simplifier.c_str());
        ImGui::InvisibleButton("row", size);
        const bool active = ImGui::IsItemActive();
        ImGui::PopID();
        dl->AddRectFilled(lo, {lo.x + size.x, lo.y + size.y}, IM_COL32(25, 25, 30, 255));
        const float plot_h = size.y - 16;
        const float base = lo.y + size.y - 2;
        const float px_per = shown > 0 ? size.x / static_cast<float>(shown) : 1;
        int last_px = -1;
        float tallest = 0;
        for (std::size_t i = 0; i < shown; ++i) {
            const uint32_t b = order[i];
            const float h = static_cast<float>(scale.height(value(d, row, b))) * plot_h;
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
            fraction = static_cast<float>(scale.height(lowest_kept));
        if (row.current || dragging_ == row.simplifier) {
            const float y = base - fraction * plot_h;
            dl->AddLine({lo.x, y}, {lo.x + size.x, y}, IM_COL32(255, 80, 80, 255), 2.0f);
        }
        char title[96];
        std::snprintf(title, sizeof title, "%s%s%s", row.simplifier.c_str(), scale.bottom > 0 ? " (log)" : "",
                      row.current ? "  (drag the red line)" : "");
        dl->AddText({lo.x + 4, lo.y + 1}, IM_COL32(220, 220, 220, 255), title);
        if (active) {
            const float y = ImGui::GetIO().MousePos.y;
            // The height dragged to, as a fraction of the row's top value.
            const double f = scale.value_at((base - y) / plot_h) / scale.top;
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
