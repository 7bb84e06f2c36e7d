// The workstation's plain state on known answers: undo history, controls
// by name, patient orientation of the slice views, window/level, slice
// pictures, the script's parsing.
#include "workstation/controls.hpp"
#include "workstation/history.hpp"
#include "workstation/script.hpp"
#include "workstation/slice_geometry.hpp"
#include "workstation/slice_image.hpp"
#include "workstation/window_level.hpp"

#include "plugin_fixture.hpp"

#include "pipeline/plugin_catalog.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace arbor::workstation {
namespace {

using pipeline::Document;

TEST(History, UndoRedoAndADragIsOneStep)
{
    Document d = pipeline::default_document();
    History h(d);
    EXPECT_FALSE(h.can_undo());
    d.view.orbit.azimuth = 10;
    h.apply(d, "orbit 10");
    // A drag: many live values, one step when it ends.
    for (int a = 11; a <= 40; ++a) {
        d.view.orbit.azimuth = a;
        h.set(d);
    }
    h.commit("orbit 40");
    EXPECT_EQ(h.names(), (std::vector<std::string>{"open", "orbit 10", "orbit 40"}));
    EXPECT_EQ(h.undo(), "orbit 40");
    EXPECT_EQ(h.current().view.orbit.azimuth, 10);
    EXPECT_EQ(h.undo(), "orbit 10");
    EXPECT_EQ(h.current().view.orbit.azimuth, 0);
    EXPECT_EQ(h.undo(), "");
    EXPECT_EQ(h.redo(), "orbit 10");
    // A new step drops the redo steps.
    d = h.current();
    d.view.orbit.elevation = 5;
    h.apply(d, "orbit 10 5");
    EXPECT_FALSE(h.can_redo());
    EXPECT_EQ(h.current().view.orbit.elevation, 5);
    // Committing what is already recorded records nothing.
    h.commit("nothing");
    EXPECT_EQ(h.names().size(), 3u);
}

TEST(History, UndoingADragInProgressGoesBackToItsStart)
{
    Document d = pipeline::default_document();
    History h(d);
    d.view.orbit.zoom = 2;
    h.set(d);
    EXPECT_EQ(h.undo(), "the change in progress");
    EXPECT_EQ(h.current().view.orbit.zoom, 1);
    EXPECT_FALSE(h.can_undo());
}

class Controls : public ::testing::Test {
protected:
    Controls() : catalog_(test::built_plugins())
    {
        Document d = pipeline::default_document();
        d.view.renderer.id = "cpu-raycast";
        for (pipeline::PluginSetting *s : {&d.simplifier, &d.appearance.depictor, &d.appearance.generator,
                                           &d.appearance.legend, &d.view.renderer}) {
            const char *kinds[] = {ARBOR_KIND_SIMPLIFIER, ARBOR_KIND_DEPICTOR, ARBOR_KIND_TF_GENERATOR,
                                   ARBOR_KIND_DEPICTOR, ARBOR_KIND_RENDERER};
            const std::size_t i = static_cast<std::size_t>(
                s == &d.simplifier ? 0 : s == &d.appearance.depictor ? 1 : s == &d.appearance.generator ? 2
                                         : s == &d.appearance.legend ? 3 : 4);
            *s = catalog_.resolve(kinds[i], *s);
        }
        doc_ = d;
    }
    pipeline::PluginCatalog catalog_;
    Document doc_;
};

TEST_F(Controls, BuiltinsAndPluginParametersByName)
{
    Document d = doc_;
    set_control(d, "keep", "12", catalog_);
    EXPECT_EQ(d.cut.keep, std::optional<std::size_t>(12));
    set_control(d, "threshold", "0.05", catalog_);
    EXPECT_FALSE(d.cut.keep);
    EXPECT_EQ(d.cut.threshold, std::optional<double>(0.05));
    set_control(d, "keep", "knee", catalog_);
    EXPECT_TRUE(d.cut.automatic());
    set_control(d, "flow-rate", "150", catalog_);
    EXPECT_EQ(d.appearance.generator.params.at("flow-rate"), "150");
    set_control(d, "residue-flow.shape", "hat", catalog_);
    EXPECT_EQ(d.appearance.generator.params.at("shape"), "hat");
    set_control(d, "relation", "none", catalog_);
    EXPECT_TRUE(d.appearance.depictor.empty());
    set_control(d, "filter", "gaussian:sigma=1.5", catalog_);
    ASSERT_EQ(d.filters.size(), 1u);
    EXPECT_EQ(d.filters[0].params.at("sigma"), "1.5");
    EXPECT_FALSE(d.auto_denoise);
    set_control(d, "azimuth", "30", catalog_);
    EXPECT_EQ(d.view.orbit.azimuth, 30);
    EXPECT_EQ(control_value(d, "azimuth", catalog_), "30");
    EXPECT_EQ(control_value(d, "flow-rate", catalog_), "150");
    const auto names = control_names(doc_, catalog_);
    EXPECT_NE(std::find(names.begin(), names.end(), "residue-flow.flow-rate"), names.end());
}

TEST_F(Controls, BadNamesAndValuesAreRefusedWithTheName)
{
    Document d = doc_;
    try {
        set_control(d, "flowrate", "1", catalog_);
        FAIL();
    } catch (const std::invalid_argument &e) {
        EXPECT_NE(std::string(e.what()).find("flowrate"), std::string::npos);
    }
    EXPECT_THROW(set_control(d, "keep", "0", catalog_), std::invalid_argument);
    EXPECT_THROW(set_control(d, "keep", "2.5", catalog_), std::invalid_argument);
    EXPECT_THROW(set_control(d, "threshold", "2", catalog_), std::invalid_argument);
    EXPECT_THROW(set_control(d, "elevation", "95", catalog_), std::invalid_argument);
    EXPECT_THROW(set_control(d, "zoom", "abc", catalog_), std::invalid_argument);
    EXPECT_THROW(set_control(d, "filter", "gaussian:sigma", catalog_), std::invalid_argument);
    EXPECT_EQ(d, doc_) << "a refused value changes nothing";
}

Geometry grid(std::array<int64_t, 3> dims, std::array<double, 9> direction = {1, 0, 0, 0, 1, 0, 0, 0, 1})
{
    Geometry g;
    g.dims = dims;
    g.direction = direction;
    return g;
}

TEST(SliceGeometry, AxialCoronalSagittalInPatientOrientation)
{
    // LPS-aligned grid: i runs to the patient's left, j posterior, k superior.
    const Geometry g = grid({10, 20, 30});
    const SliceGeometry ax = slice_geometry(g, SliceOrientation::Axial);
    EXPECT_EQ(ax.normal, 2);
    EXPECT_EQ(ax.width, 10);
    EXPECT_EQ(ax.height, 20);
    // Screen left is the patient's right: voxel i = 0 (rightmost) at x = 0.
    EXPECT_EQ(ax.voxel(0, 0, 5), (std::array<int64_t, 3>{0, 0, 5}));
    EXPECT_EQ(ax.left, 'R');
    EXPECT_EQ(ax.top, 'A');
    const SliceGeometry co = slice_geometry(g, SliceOrientation::Coronal);
    EXPECT_EQ(co.normal, 1);
    // Superior up: the top row is the highest k.
    EXPECT_EQ(co.voxel(0, 0, 3), (std::array<int64_t, 3>{0, 3, 29}));
    const SliceGeometry sa = slice_geometry(g, SliceOrientation::Sagittal);
    EXPECT_EQ(sa.normal, 0);
    // Anterior on the left (j = 0 is the most anterior), superior up.
    EXPECT_EQ(sa.voxel(0, 0, 4), (std::array<int64_t, 3>{4, 0, 29}));
    EXPECT_EQ(sa.left, 'A');
    // screen() inverts voxel().
    for (const SliceGeometry &s : {ax, co, sa})
        EXPECT_EQ(s.screen(s.voxel(3, 7, 2)), (std::array<int64_t, 3>{3, 7, 2}));
}

TEST(SliceGeometry, FollowsTheDirectionCosines)
{
    // RAS-stored (i towards the right, j anterior) and acquired coronally
    // (the third axis is the patient's A-P): the views still show patient
    // orientation.
    const Geometry g = grid({10, 20, 30}, {-1, 0, 0, 0, 0, -1, 0, 1, 0});
    // LPS row p, voxel column c: x = -i, y(P) = -k, z(S) = j.
    const SliceGeometry ax = slice_geometry(g, SliceOrientation::Axial);
    EXPECT_EQ(ax.normal, 1); // S runs along j
    EXPECT_EQ(ax.x_axis, 0);
    EXPECT_TRUE(ax.x_flip);  // i runs to the right: screen x (to the left) counts down
    EXPECT_EQ(ax.y_axis, 2);
    EXPECT_TRUE(ax.y_flip);  // k runs anterior: screen y (posterior) counts down
    EXPECT_EQ(ax.voxel(0, 0, 7), (std::array<int64_t, 3>{9, 7, 29}));
}

TEST(WindowLevel, PresetsAndTheHistogramsWindow)
{
    const auto bone = ct_preset("bone");
    ASSERT_TRUE(bone);
    EXPECT_EQ(bone->width, 1000);
    EXPECT_EQ(bone->level, 400);
    EXPECT_FALSE(ct_preset("liver"));
    EXPECT_DOUBLE_EQ(bone->grey(400), 0.5);
    EXPECT_DOUBLE_EQ(bone->grey(-100), 0.0);
    EXPECT_DOUBLE_EQ(bone->grey(900), 1.0);
    // Values 0..99 repeated: the 1st to 99th percentile.
    Geometry g = grid({100, 10, 10});
    Volume v = Volume::allocate(ARBOR_VOXEL_U8, g, {}, 1 << 20);
    for (int64_t i = 0; i < v.voxel_count(); ++i)
        v.as<uint8_t>()[i] = static_cast<uint8_t>(i % 100);
    const WindowLevel w = auto_window(v);
    EXPECT_NEAR(w.level - w.width / 2, 1, 1.01);
    EXPECT_NEAR(w.level + w.width / 2, 98, 1.01);
    // Above a background of 50: the window covers 51..99 only.
    const WindowLevel above = auto_window(v, 50.0);
    EXPECT_GT(above.level - above.width / 2, 50);
    // Not HU: the histogram's; HU: soft tissue.
    EXPECT_EQ(default_window(v).width, w.width);
    v.mapping().unit = "HU";
    EXPECT_EQ(default_window(v).width, 400);
}

TEST(SliceImage, GreyThroughTheWindowAndTheOverlay)
{
    Geometry g = grid({4, 3, 2});
    Volume v = Volume::allocate(ARBOR_VOXEL_U8, g, {}, 1 << 20);
    for (int64_t i = 0; i < v.voxel_count(); ++i)
        v.as<uint8_t>()[i] = static_cast<uint8_t>(i * 10);
    const SliceGeometry s = slice_geometry(g, SliceOrientation::Axial);
    const WindowLevel w{230, 115}; // 0 -> black, 230 -> white
    SliceImage im = slice_image(v, s, 1, w);
    ASSERT_EQ(im.width, 4);
    ASSERT_EQ(im.height, 3);
    // Pixel (x, y) of slice 1 is voxel (x, y, 1): value 10 * (x + 4 y + 12).
    for (int64_t y = 0; y < 3; ++y)
        for (int64_t x = 0; x < 4; ++x) {
            const double value = 10.0 * static_cast<double>(x + 4 * y + 12);
            EXPECT_NEAR(im.rgba[static_cast<std::size_t>((y * 4 + x) * 4)], std::lround(value / 230 * 255), 1);
            EXPECT_EQ(im.rgba[static_cast<std::size_t>((y * 4 + x) * 4 + 3)], 255);
        }
    // Labels: voxel 13 (x 1, y 0 of slice 1) is branch 1, drawn red at opacity 1; the root is not coloured.
    std::vector<uint32_t> labels(static_cast<std::size_t>(v.voxel_count()), 0);
    labels[13] = 1;
    const std::vector<std::array<float, 3>> colors{{0, 0, 0}, {1, 0, 0}};
    LabelOverlay overlay{labels, &colors, 1.0, std::nullopt, nullptr};
    im = slice_image(v, s, 1, w, overlay);
    EXPECT_EQ(im.rgba[4 * 1 + 0], 255);
    EXPECT_EQ(im.rgba[4 * 1 + 1], 0);
    EXPECT_NEAR(im.rgba[0], std::lround(120.0 / 230 * 255), 1) << "label 0 is left grey";
    // Hidden: grey again.
    const std::vector<bool> hidden{false, true};
    overlay.hidden = &hidden;
    im = slice_image(v, s, 1, w, overlay);
    EXPECT_EQ(im.rgba[4 * 1 + 0], im.rgba[4 * 1 + 1]);
}

TEST(Script, ParsesCommandsAndNamesTheLineOfAMistake)
{
    const auto lines = parse_script("# a comment\n\nopen /data/my scan.nrrd\nwait idle 30\nset flow-rate 150\n"
                                    "orbit 30 -10\nscreenshot out.png\nquit\n",
                                    "steps.txt");
    ASSERT_EQ(lines.size(), 6u);
    EXPECT_EQ(lines[0].number, 3u);
    EXPECT_EQ(lines[0].args, (std::vector<std::string>{"/data/my scan.nrrd"}));
    EXPECT_EQ(lines[1].args, (std::vector<std::string>{"idle", "30"}));
    EXPECT_EQ(lines[2].args, (std::vector<std::string>{"flow-rate", "150"}));
    EXPECT_EQ(lines[3].args, (std::vector<std::string>{"30", "-10"}));
    try {
        parse_script("open a\nfly away\n", "steps.txt");
        FAIL();
    } catch (const ScriptError &e) {
        EXPECT_STREQ(e.what(), "steps.txt:2: unknown command 'fly'");
    }
    EXPECT_THROW(parse_script("orbit 30\n", "s"), ScriptError);
    EXPECT_THROW(parse_script("quit now\n", "s"), ScriptError);
    EXPECT_THROW(parse_script("wait busy\n", "s"), ScriptError);
}

} // namespace
} // namespace arbor::workstation
