// arbor-session/1: write -> read -> write gives the same document and text;
// paths are relative where they can be; a third party's parameters survive;
// every refusal names the file and the problem.
#include "pipeline/pipeline.hpp"
#include "pipeline/session.hpp"

#include "plugin_fixture.hpp"
#include "test_paths.hpp"

#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include <fstream>

namespace arbor::pipeline {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

// The built plugins and the plain-C third-party simplifier of the fixtures.
const PluginRegistry &plugins()
{
    static const std::unique_ptr<PluginRegistry> registry = [] {
        auto r = std::make_unique<PluginRegistry>();
        r->load_directories({test::plugin_dir(), fs::path(ARBOR_FIXTURE_PLUGIN_DIR) / "fixture-simplifier"});
        return r;
    }();
    return *registry;
}

// A document with something in every group, resolved as a pipeline keeps it.
Document full_document(const fs::path &input)
{
    Document d = default_document();
    d.input.path = input;
    d.input.importer = {"nrrd", "", {}};
    d.filters = {{"gaussian", "", {{"sigma", "1.25"}}}, {"median", "", {{"size", "5"}}}};
    d.simplifier = {"org.arbor.test.simplifier.volume-squared", "", {{"exponent", "3"}}};
    d.cut.threshold = 0.015625;
    d.appearance.selected = 3;
    d.appearance.generator.params = {{"flow-rate", "120"}, {"shape", "hat"}, {"hues", "X:30"}};
    d.appearance.depictor = {"neighbour", "", {{"rotation", "45"}}};
    d.view.orbit = {30.5, -12.0, 1.75, false, 25.0};
    d.view.width = 320;
    d.view.height = 200;
    d.view.background = {0.2, 0.25, 0.3, 1.0};
    d.view.renderer.params = {{"shading", "false"}, {"sample-distance", "0.25"}};
    Pipeline p(plugins());
    p.set_document(d);
    return p.document();
}

fs::path write_text(const fs::path &path, const std::string &text)
{
    std::ofstream(path) << text;
    return path;
}

class Session : public ::testing::Test {
protected:
    Session() : catalog(plugins())
    {
        dir = test::scratch_dir();
        fs::create_directories(dir / "data");
        fs::create_directories(dir / "study");
        input = dir / "data" / "scan.nrrd";
        fs::copy_file(test::shared_data("nucleon/nucleon.nrrd"), input);
    }

    json saved(const Document &d, const fs::path &path)
    {
        write_session(path, d, catalog);
        std::ifstream in(path);
        return json::parse(in);
    }

    // Edits the saved session of full_document and reads it back; returns
    // the refusal's message ("" when it was accepted).
    std::string refusal(const std::function<void(json &)> &edit, bool require_input = true)
    {
        const fs::path path = dir / "study" / "edited.json";
        json j = saved(full_document(input), path);
        edit(j);
        write_text(path, j.dump(2));
        try {
            read_session(path, catalog, require_input);
        } catch (const SessionError &e) {
            return e.what();
        }
        return "";
    }

    PluginCatalog catalog;
    fs::path dir, input;
};

TEST_F(Session, WriteReadWriteGivesTheSameDocumentAndTheSameText)
{
    const Document d = full_document(input);
    const fs::path a = dir / "study" / "a.json", b = dir / "study" / "b.json";
    write_session(a, d, catalog);
    const SessionRead r = read_session(a, catalog);
    EXPECT_TRUE(r.warnings.empty());
    EXPECT_EQ(r.document, d);
    write_session(b, r.document, catalog);
    std::ifstream fa(a), fb(b);
    EXPECT_EQ(std::string(std::istreambuf_iterator<char>(fa), {}), std::string(std::istreambuf_iterator<char>(fb), {}));
}

TEST_F(Session, ThePhantomAndTheDefaultsRoundTrip)
{
    Document d = default_document();
    d.input.phantom = PhantomInput{"head", 96, 6.5, 12, 7};
    Pipeline p(plugins());
    p.set_document(d);
    const fs::path path = dir / "phantom.json";
    write_session(path, p.document(), catalog);
    EXPECT_EQ(read_session(path, catalog).document, p.document());
    EXPECT_TRUE(p.document().cut.automatic());
}

TEST_F(Session, TheFileSaysWhatAnImageDependsOnInPlainTypes)
{
    const json j = saved(full_document(input), dir / "study" / "s.json");
    EXPECT_EQ(j["format"], "arbor-session/1");
    EXPECT_EQ(j["input"]["path"], "../data/scan.nrrd"); // relative to the session's folder
    EXPECT_EQ(j["input"]["importer"]["id"], "org.arbor.importer.nrrd");
    EXPECT_EQ(j["filters"][0]["id"], "org.arbor.filter.gaussian");
    EXPECT_EQ(j["filters"][0]["parameters"]["sigma"], 1.25);
    EXPECT_EQ(j["filters"][1]["parameters"]["size"], 5);
    EXPECT_EQ(j["simplifier"]["id"], "org.arbor.test.simplifier.volume-squared");
    EXPECT_EQ(j["simplifier"]["version"], "1.0.0");
    EXPECT_EQ(j["simplifier"]["parameters"]["exponent"], 3); // a third party's parameter, by its description
    EXPECT_EQ(j["cut"]["threshold"], 0.015625);
    EXPECT_EQ(j["appearance"]["relation"]["id"], "org.arbor.depictor.neighbour");
    EXPECT_EQ(j["appearance"]["selected_branch"], 3);
    EXPECT_EQ(j["appearance"]["generator"]["parameters"]["shape"], "hat");
    EXPECT_EQ(j["appearance"]["generator"]["parameters"]["flow-rate"], 120);
    EXPECT_EQ(j["view"]["camera"]["projection"], "orthographic");
    EXPECT_EQ(j["view"]["camera"]["azimuth"], 30.5);
    EXPECT_EQ(j["view"]["image"]["width"], 320);
    EXPECT_EQ(j["view"]["background"][1], 0.25);
    EXPECT_EQ(j["view"]["renderer"]["parameters"]["shading"], false);
    // Every parameter of every plugin, not only those the user set.
    EXPECT_GE(j["appearance"]["generator"]["parameters"].size(), 10u);
}

TEST_F(Session, ASessionMovedWithItsDataStillFindsIt)
{
    const fs::path path = dir / "study" / "s.json";
    write_session(path, full_document(input), catalog);
    const fs::path moved = dir.parent_path() / "Session.moved";
    fs::remove_all(moved);
    fs::rename(dir, moved);
    const SessionRead r = read_session(moved / "study" / "s.json", catalog);
    EXPECT_EQ(fs::canonical(r.document.input.path), fs::canonical(moved / "data" / "scan.nrrd"));
    fs::rename(moved, dir);
}

TEST_F(Session, RefusalsNameTheFileAndTheProblem)
{
    const auto has = [](const std::string &message, const std::string &words) {
        return message.find(words) != std::string::npos;
    };
    std::string m;
    m = refusal([](json &j) { j["format"] = "arbor-session/2"; });
    EXPECT_TRUE(has(m, "edited.json") && has(m, "arbor-session/2") && has(m, "newer")) << m;
    m = refusal([](json &j) { j.erase("format"); });
    EXPECT_TRUE(has(m, "not an Arbor session")) << m;
    m = refusal([](json &j) { j["simplifier"]["id"] = "org.example.simplifier.magic"; });
    EXPECT_TRUE(has(m, "org.example.simplifier.magic") && has(m, "not installed")) << m;
    m = refusal([](json &j) { j["simplifier"]["parameters"]["exponent"] = 9; });
    EXPECT_TRUE(has(m, "exponent") && has(m, "9")) << m;
    m = refusal([](json &j) { j["appearance"]["generator"]["parameters"]["flow-rate"] = -3; });
    EXPECT_TRUE(has(m, "appearance.generator") && has(m, "flow-rate")) << m;
    m = refusal([](json &j) { j["appearance"]["generator"]["parameters"]["shape"] = "spiral"; });
    EXPECT_TRUE(has(m, "spiral")) << m;
    m = refusal([](json &j) { j["filters"][0]["parameters"]["sigma"] = "wide"; });
    EXPECT_TRUE(has(m, "filters[0]") && has(m, "sigma") && has(m, "wide")) << m;
    m = refusal([](json &j) { j["input"]["path"] = "../data/gone.nrrd"; });
    EXPECT_TRUE(has(m, "gone.nrrd") && has(m, "does not exist")) << m;
    EXPECT_EQ(refusal([](json &j) { j["input"]["path"] = "../data/gone.nrrd"; }, false), ""); // the front overrides it
    m = refusal([](json &j) { j["cut"] = {{"keep", 0}}; });
    EXPECT_TRUE(has(m, "cut.keep")) << m;
    m = refusal([](json &j) { j["view"]["image"]["width"] = -4; });
    EXPECT_TRUE(has(m, "view.image.width")) << m;
    m = refusal([](json &j) { j["view"]["camera"]["projection"] = "fisheye"; });
    EXPECT_TRUE(has(m, "fisheye")) << m;
    m = refusal([](json &j) { j["appearance"]["selected_branch"] = -1; });
    EXPECT_TRUE(has(m, "selected_branch")) << m;

    write_text(dir / "garbage.json", "{ this is not json");
    try {
        read_session(dir / "garbage.json", catalog);
        ADD_FAILURE();
    } catch (const SessionError &e) {
        EXPECT_TRUE(has(e.what(), "garbage.json: not JSON")) << e.what();
    }
    EXPECT_THROW(read_session(dir / "absent.json", catalog), SessionError);
}

TEST_F(Session, OtherPluginVersionsAndDroppedParametersAreWarnings)
{
    const fs::path path = dir / "study" / "old.json";
    json j = saved(full_document(input), path);
    j["appearance"]["generator"]["version"] = "0.9.0";
    j["appearance"]["generator"]["parameters"]["sparkle"] = 3;
    write_text(path, j.dump(2));
    const SessionRead r = read_session(path, catalog);
    ASSERT_EQ(r.warnings.size(), 2u);
    EXPECT_NE(r.warnings[0].find("sparkle"), std::string::npos) << r.warnings[0];
    EXPECT_NE(r.warnings[1].find("0.9.0"), std::string::npos) << r.warnings[1];
    EXPECT_EQ(r.document, full_document(input));
}

} // namespace
} // namespace arbor::pipeline
