// The panels in an ImGui context with no back end (Dear ImGui 1.86: a
// built font atlas and io.KeyMap are all it needs), input written into
// ImGuiIO before each NewFrame as the GLFW back end would, and assertions on
// the workstation's state: a click on the tree selects the branch its hover
// names, dragging the priority line sets the threshold, the branch list
// selects and hides, and a hidden branch is gone from the 3D view.
#include "workstation/branch_list.hpp"
#include "workstation/dicom_browser.hpp"
#include "workstation/parameter_panel.hpp"
#include "workstation/priority_line_view.hpp"
#include "workstation/tree_view.hpp"
#include "workstation/workstation.hpp"
#include "workstation_fixture.hpp"

#include "dicom/folder_scan.hpp"

#include <gtest/gtest.h>
#include <imgui.h>
#include <imgui_internal.h> // GetHoveredID: where a generated control is

#include <chrono>
#include <filesystem>
#include <functional>
#include <thread>

namespace arbor::workstation {
namespace {

using pipeline::Stage;

class Gui {
public:
    Gui()
    {
        ImGui::CreateContext();
        ImGuiIO &io = ImGui::GetIO();
        io.IniFilename = nullptr;
        io.DisplaySize = {800, 600};
        io.DeltaTime = 1.0f / 60;
        unsigned char *pixels = nullptr;
        int w = 0, h = 0;
        io.Fonts->GetTexDataAsRGBA32(&pixels, &w, &h);
        for (int k = 0; k < ImGuiKey_COUNT; ++k)
            io.KeyMap[k] = k;
    }
    ~Gui() { ImGui::DestroyContext(); }

    // One frame with the mouse at `mouse` (button 0 `down`), the panel in a
    // window filling (0, 0) .. (400, 400).
    void frame(const std::function<void()> &panel, ImVec2 mouse, bool down)
    {
        ImGuiIO &io = ImGui::GetIO();
        io.MousePos = mouse;
        io.MouseDown[0] = down;
        ImGui::NewFrame();
        ImGui::SetNextWindowPos({0, 0});
        ImGui::SetNextWindowSize({400, 400});
        ImGui::Begin("panel", nullptr, ImGuiWindowFlags_NoMove | ImGuiWindowFlags_NoResize | ImGuiWindowFlags_NoTitleBar);
        panel();
        ImGui::End();
        ImGui::Render();
    }
    void click(const std::function<void()> &panel, ImVec2 at)
    {
        frame(panel, at, false);
        frame(panel, at, true);
        frame(panel, at, false);
    }
};

using test_support::wait_idle;

std::unique_ptr<Workstation> phantom()
{
    auto ws = test_support::phantom_workstation(64, 4);
    wait_idle(*ws);
    return ws;
}

TEST(Panels, ClickingTheTreeSelectsTheBranchItsHoverNames)
{
    auto ws = phantom();
    Gui gui;
    TreeView tree;
    const auto draw = [&] { tree.draw(*ws); };
    // Sweep the mouse over the tree until it hovers a non-root branch.
    std::optional<uint32_t> hovered;
    ImVec2 at{};
    for (float x = 10; x < 400 && !hovered; x += 3)
        for (float y = 10; y < 400 && !hovered; y += 6) {
            gui.frame(draw, {x, y}, false);
            if (ws->view().hovered && *ws->view().hovered > 0) {
                hovered = ws->view().hovered;
                at = {x, y};
            }
        }
    ASSERT_TRUE(hovered) << "no branch line found under the mouse";
    gui.click(draw, at);
    EXPECT_EQ(ws->document().appearance.selected, std::optional<int32_t>(static_cast<int32_t>(*hovered)));
    EXPECT_TRUE(ws->history().can_undo()) << "a selection is an undo step";
}

TEST(PriorityScale, LinearUnlessTheValuesSpanMoreThanTwoDecades)
{
    const PriorityScale linear = PriorityScale::of(2.0, 0.05); // 40x
    EXPECT_EQ(linear.bottom, 0.0);
    EXPECT_DOUBLE_EQ(linear.height(1.0), 0.5);
    EXPECT_DOUBLE_EQ(linear.value_at(0.25), 0.5);

    // ITri's usual shape: one branch at 1, the rest from 1e-4 to 1e-2.
    const PriorityScale log = PriorityScale::of(1.0, 1e-4);
    EXPECT_DOUBLE_EQ(log.bottom, 1e-4);
    EXPECT_NEAR(log.height(1e-2), 0.5, 1e-12) << "a decade is a quarter of the row";
    EXPECT_NEAR(log.height(1e-3), 0.25, 1e-12);
    EXPECT_EQ(log.height(1e-5), 0.0) << "below the smallest shown: at the base";
    EXPECT_EQ(log.height(0.0), 0.0);
    EXPECT_DOUBLE_EQ(log.height(1.0), 1.0);
    for (const double v : {1e-4, 3e-4, 0.01, 0.2, 1.0})
        EXPECT_NEAR(log.value_at(log.height(v)), v, 1e-12 * v) << v;
    // Heights grow with values, as a threshold dragged up keeps fewer.
    double last = -1;
    for (double v = 1e-4; v <= 1.0; v *= 1.7) {
        EXPECT_GT(log.height(v), last);
        last = log.height(v);
    }
    // A scale never reaches further down than six decades.
    EXPECT_DOUBLE_EQ(PriorityScale::of(1.0, 1e-9).bottom, 1e-6);
}

TEST(Panels, DraggingThePriorityLineSetsTheThresholdAsOneUndoStep)
{
    auto ws = phantom();
    Gui gui;
    PriorityLineView lines;
    const auto draw = [&] { lines.draw(*ws); };
    gui.frame(draw, {0, 0}, false);
    // The branches are ordered off the UI thread: "ordering" until then.
    for (int i = 0; i < 1000 && !lines.showed_rows(); ++i) {
        std::this_thread::sleep_for(std::chrono::milliseconds(5));
        gui.frame(draw, {0, 0}, false);
    }
    ASSERT_TRUE(lines.showed_rows()) << "the rows within 5 s";
    const std::size_t steps = ws->history().names().size();
    // Press low in the first row (the current simplifier's) and drag up.
    gui.frame(draw, {200, 60}, false);
    for (float y = 60; y >= 20; y -= 5)
        gui.frame(draw, {200, y}, true);
    ASSERT_TRUE(ws->document().cut.threshold) << "the drag set a threshold";
    EXPECT_FALSE(ws->document().cut.keep);
    gui.frame(draw, {200, 20}, false);
    EXPECT_EQ(ws->history().names().size(), steps + 1) << "the whole drag is one step";
    const double high = *ws->document().cut.threshold;
    wait_idle(*ws);
    const std::size_t kept_high = ws->pipeline().latest<Stage::Cut>()->kept();
    // Lower: more branches kept.
    gui.frame(draw, {200, 25}, false);
    for (float y = 25; y <= 70; y += 5)
        gui.frame(draw, {200, y}, true);
    gui.frame(draw, {200, 70}, false);
    EXPECT_LT(*ws->document().cut.threshold, high);
    wait_idle(*ws);
    EXPECT_GE(ws->pipeline().latest<Stage::Cut>()->kept(), kept_high);
}

TEST(Panels, TheBranchListSelectsAndHides)
{
    auto ws = phantom();
    Gui gui;
    BranchList list;
    const auto draw = [&] { list.draw(*ws); };
    gui.frame(draw, {0, 0}, false);
    // Rows are one text line each below the header; find the row of branch 2
    // by hovering down the name column.
    std::optional<float> row_y;
    for (float y = 5; y < 200 && !row_y; y += 2) {
        gui.frame(draw, {150, y}, false);
        if (ws->view().hovered == 2u)
            row_y = y;
    }
    ASSERT_TRUE(row_y);
    gui.click(draw, {150, *row_y});
    EXPECT_EQ(ws->document().appearance.selected, std::optional<int32_t>(2));
    // The check box in the second column hides it: a style the 3D view and
    // the slice overlay follow.
    EXPECT_TRUE(ws->hidden_labels().empty());
    gui.click(draw, {35, *row_y});
    ASSERT_GE(ws->hidden_labels().size(), 3u);
    EXPECT_TRUE(ws->hidden_labels()[2]);
    EXPECT_FALSE(ws->branch_style(2).visible);
    EXPECT_EQ(ws->document().view.branch_styles.size(), 1u);
}

TEST(Panels, TheGeneratedFlowRateSliderMovesTheFlowRateAsOneUndoStep)
{
    auto ws = phantom();
    Gui gui;
    ParameterPanel panel;
    // The slider's id as the panel makes it: the plugin slot, the parameter
    // id, the parameter's label (parameter_panel.cpp's ID stack).
    ImGuiID slider = 0;
    const auto draw = [&] {
        panel.draw(*ws);
        ImGui::PushID("generator");
        ImGui::PushID("flow-rate");
        slider = ImGui::GetID("Flow rate Q");
        ImGui::PopID();
        ImGui::PopID();
    };
    gui.frame(draw, {0, 0}, false);
    std::optional<ImVec2> at;
    for (float y = 5; y < 400 && !at; y += 4)
        for (float x = 20; x < 200 && !at; x += 40) {
            gui.frame(draw, {x, y}, false);
            if (ImGui::GetCurrentContext()->HoveredIdPreviousFrame == slider)
                at = ImVec2{x, y};
        }
    ASSERT_TRUE(at) << "no flow-rate slider in the panel";
    const std::string before = ws->document().appearance.generator.params.at("flow-rate");
    const std::size_t steps = ws->history().names().size();
    // A press sets the value under the mouse (ImGui's sliders); dragging
    // to the right raises it live; the release makes the whole drag one step.
    gui.frame(draw, *at, true);
    gui.frame(draw, *at, true);
    const double pressed = std::stod(ws->document().appearance.generator.params.at("flow-rate"));
    EXPECT_GT(pressed, 0);
    EXPECT_LE(pressed, 600) << "the slider spans ten times the default, not the plugin's 1e6";
    for (float dx = 10; dx <= 60; dx += 10)
        gui.frame(draw, {at->x + dx, at->y}, true);
    const std::string during = ws->document().appearance.generator.params.at("flow-rate");
    EXPECT_GT(std::stod(during), pressed) << "dragging right raises Q";
    gui.frame(draw, {at->x + 60, at->y}, false);
    gui.frame(draw, {at->x + 60, at->y}, false);
    EXPECT_EQ(ws->history().names().size(), steps + 1) << "the drag is one undo step";
    EXPECT_EQ(ws->pipeline().document().appearance.generator.params.at("flow-rate"), during)
        << "the pipeline has the value the slider shows";
    ASSERT_TRUE(ws->undo());
    EXPECT_EQ(ws->document().appearance.generator.params.at("flow-rate"), before);
}

// Draws the browser until its scan is done (at most two minutes).
void scan_to_the_end(Gui &gui, DicomBrowser &browser, Workstation &ws)
{
    const auto end = std::chrono::steady_clock::now() + std::chrono::seconds(120);
    do {
        gui.frame([&] { browser.draw(ws); }, {0, 0}, false);
        std::this_thread::sleep_for(std::chrono::milliseconds(5));
    } while (browser.scanning() && std::chrono::steady_clock::now() < end);
    gui.frame([&] { browser.draw(ws); }, {0, 0}, false);
    ASSERT_FALSE(browser.scanning());
}

TEST(Panels, ADicomFolderWithOneSeriesOpensItAtOnce)
{
    Workstation ws(test::built_plugins(), pipeline::PipelineOptions{});
    Gui gui;
    DicomBrowser browser;
    const auto folder = test::shared_data("dicom_ct_head_0051");
    browser.scan(folder, true);
    scan_to_the_end(gui, browser, ws);
    ASSERT_TRUE(ws.has_input());
    EXPECT_EQ(ws.document().input.path, folder);
    // The series the folder scan found, by its UID (the importer reads that one).
    const auto scan = dicom::scan_dicom(folder);
    ASSERT_EQ(scan.series.size(), 1u);
    EXPECT_EQ(ws.document().input.importer.params.at("series"), scan.series[0].uid);
    EXPECT_FALSE(browser.shown()) << "the browser closes once the series is open";
    ws.pipeline().cancel_all();
}

TEST(Panels, ADicomFolderWithSeveralSeriesWaitsForAChoice)
{
    Workstation ws(test::built_plugins(), pipeline::PipelineOptions{});
    Gui gui;
    DicomBrowser browser;
    browser.scan(test::shared_data("dicom_pydicom_variants"), true);
    scan_to_the_end(gui, browser, ws);
    EXPECT_FALSE(ws.has_input()) << "nothing opened before a person chooses";
    EXPECT_TRUE(browser.shown());
}

} // namespace
} // namespace arbor::workstation
