// The plugin contract (sdk/docs/contract.md), checked on the host's side:
// a fixture library with one plugin of every kind records every call the
// host makes into it (fixture_recorder.c), and a whole pipeline runs on it.
// Each rule below is a rule of the contract; the record says whether the
// host kept it.
#include "pipeline/pipeline.hpp"
#include "pipeline/transfer_function_file.hpp"

#include "host/depiction_application.hpp"
#include "host/plugin_registry.hpp"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <set>
#include <sstream>
#include <tuple>

#include <unistd.h>

namespace arbor::pipeline {
namespace {

namespace fs = std::filesystem;

struct Call {
    std::string plugin, function;
    unsigned long instance = 0, thread = 0;
    std::string task;
    bool overlap = false, serial_overlap = false;
    std::string param;
};

struct Row {
    unsigned kind = 0;
    double saddle = 0, extremum = 0;
    bool root = false;
    unsigned batch = 0;
};

struct Record {
    std::vector<Call> calls;
    std::vector<Row> rows;
    std::vector<std::string> schemas;
    std::vector<std::string> rows_without_extrema;
};

std::string field(const std::string &word, const char *key)
{
    const std::string k = std::string(key) + "=";
    return word.rfind(k, 0) == 0 ? word.substr(k.size()) : std::string();
}

Record read_record(const fs::path &path)
{
    Record r;
    std::ifstream in(path);
    std::string line;
    while (std::getline(in, line)) {
        std::istringstream s(line);
        std::vector<std::string> words;
        for (std::string w; s >> w;)
            words.push_back(w);
        if (words.empty())
            continue;
        if (words[0] == "schema") {
            r.schemas.push_back(line);
        } else if (words[0] == "row") {
            if (words.size() < 6) {
                r.rows_without_extrema.push_back(line);
                continue;
            }
            Row row;
            row.batch = static_cast<unsigned>(std::stoul(field(words[1], "batch")));
            row.kind = static_cast<unsigned>(std::stoul(field(words[2], "kind")));
            row.saddle = std::stod(field(words[3], "saddle"));
            row.extremum = std::stod(field(words[4], "extremum"));
            row.root = field(words[5], "root") == "1";
            r.rows.push_back(row);
        } else if (words.size() >= 8) {
            Call c;
            c.plugin = words[0];
            c.function = words[1];
            c.instance = std::stoul(field(words[2], "instance"));
            c.thread = std::stoul(field(words[3], "thread"));
            c.task = field(words[4], "task");
            c.overlap = field(words[5], "overlap") == "1";
            c.serial_overlap = field(words[6], "serial_overlap") == "1";
            c.param = field(words[7], "param");
            r.calls.push_back(c);
        }
    }
    return r;
}

// A scratch folder, the record file, a .rec volume and a registry holding
// the recorder library alone, loaded with the record switched on.
class PluginContract : public ::testing::Test {
protected:
    PluginContract()
    {
        dir = fs::temp_directory_path() /
              ("arbor-contract-" + std::to_string(::getpid()) + "-" +
               ::testing::UnitTest::GetInstance()->current_test_info()->name());
        fs::remove_all(dir);
        fs::create_directories(dir);
        record = dir / "calls.txt";
        volume = dir / "blobs.rec";
        std::ofstream(volume) << "12\n";
        ::setenv("ARBOR_FIXTURE_RECORD", record.c_str(), 1);
        registry = std::make_unique<PluginRegistry>();
        registry->load_directories({fs::path(ARBOR_FIXTURE_PLUGIN_DIR) / "fixture-recorder"});
    }
    ~PluginContract() override
    {
        registry.reset();
        ::unsetenv("ARBOR_FIXTURE_RECORD");
        fs::remove_all(dir);
    }

    static PluginSetting setting(const std::string &kind, std::map<std::string, std::string> params = {})
    {
        return {"org.arbor.test.recorder." + kind, "", std::move(params)};
    }

    Document document(const std::string &generator_mode = "plain") const
    {
        Document d = default_document();
        d.input = {};
        d.input.path = volume;
        d.filters = {setting("filter", {{"param", "2"}})};
        d.auto_denoise = false;
        d.simplifier = setting("simplifier", {{"param", "3"}});
        d.cut.keep = 4;
        d.appearance.depictor = setting("depictor");
        d.appearance.legend = setting("depictor");
        d.appearance.legend_size = 64;
        d.appearance.generator = setting("generator", {{"param", "5"}, {"mode", generator_mode}});
        d.appearance.balance_visibility = false;
        d.view.renderer = setting("renderer");
        d.view.width = d.view.height = 32;
        d.view.frame_content = false;
        return d;
    }

    fs::path dir, record, volume;
    std::unique_ptr<PluginRegistry> registry;
};

std::vector<Call> of(const Record &r, const std::string &function)
{
    std::vector<Call> out;
    for (const Call &c : r.calls)
        if (c.function == function)
            out.push_back(c);
    return out;
}

TEST_F(PluginContract, EveryCallKeepsTheThreadTaskAndParameterRules)
{
    std::shared_ptr<const DecompositionResult> decomposition;
    {
        Pipeline pipeline(*registry);
        pipeline.set_document(document());
        // The render and the legend at once: the depiction and the legend
        // stages run on two threads, each with an instance of the
        // serialised depictor.
        const auto render = pipeline.request(Stage::Render);
        const auto legend = pipeline.request(Stage::Legend);
        render->wait();
        legend->wait();
        decomposition = pipeline.run<Stage::Decomposition>();
        // A parameter changed between two calls: the next call sees it.
        Document d = pipeline.document();
        d.appearance.generator.params["param"] = "7";
        pipeline.set_document(d);
        pipeline.run<Stage::Render>();
    }
    registry.reset(); // deinit
    const Record r = read_record(record);
    ASSERT_FALSE(r.calls.empty()) << "nothing recorded at " << record;

    // [main-thread]: init, plugin_count, plugin_descriptor and deinit on the
    // thread that loaded the library (this one).
    std::set<unsigned long> loading;
    for (const char *f : {"init", "plugin_count", "plugin_descriptor", "deinit"})
        for (const Call &c : of(r, f))
            loading.insert(c.thread);
    EXPECT_EQ(loading.size(), 1u) << "library functions ran on several threads";
    EXPECT_EQ(of(r, "init").size(), 1u);
    EXPECT_EQ(of(r, "deinit").size(), 1u);
    EXPECT_EQ(r.calls.back().function, "deinit") << "deinit is the last call";

    std::map<unsigned long, std::vector<const Call *>> by_instance;
    std::set<unsigned long> job_threads;
    for (const Call &c : r.calls) {
        // [instance]: never two calls into one instance at once; the
        // serialised depictor: never two calls into any of its instances.
        EXPECT_FALSE(c.overlap) << c.plugin << " " << c.function << " overlapped a call into its instance";
        EXPECT_FALSE(c.serial_overlap) << c.function << " overlapped a call into another serialised instance";
        // The task: never NULL, every function set.
        if (c.task != "none") {
            EXPECT_EQ(c.task, "ok") << c.plugin << " " << c.function << " got task " << c.task;
        }
        if (c.instance != 0) {
            by_instance[c.instance].push_back(&c);
            if (c.plugin != "library" && c.function != "params.get" && c.function != "params.set" &&
                c.function != "plugin.destroy" && c.function != "importer.probe")
                job_threads.insert(c.thread);
        }
    }
    // Every instance is destroyed exactly once, and nothing calls it after.
    for (const auto &[instance, calls] : by_instance) {
        const auto destroys = std::count_if(calls.begin(), calls.end(),
                                            [](const Call *c) { return c->function == "plugin.destroy"; });
        EXPECT_EQ(destroys, 1) << "instance " << instance;
        EXPECT_EQ(calls.back()->function, "plugin.destroy") << "instance " << instance << " called after destroy";
    }
    // Pipeline work runs on job threads, not the loading thread.
    EXPECT_EQ(job_threads.count(*loading.begin()), 0u) << "a pipeline stage called a plugin on the front's thread";

    // Importing: probe on an instance of its own, then read_header and
    // read_voxels on one instance, in that order, nothing between them.
    const auto probes = of(r, "importer.probe");
    const auto headers = of(r, "importer.read_header");
    ASSERT_FALSE(probes.empty());
    ASSERT_EQ(headers.size(), 1u);
    for (const Call &p : probes)
        EXPECT_NE(p.instance, headers[0].instance) << "the probing instance also read";
    const auto &reader = by_instance.at(headers[0].instance);
    for (std::size_t i = 0; i + 1 < reader.size(); ++i) {
        if (reader[i]->function == "importer.read_header") {
            EXPECT_EQ(reader[i + 1]->function, "importer.read_voxels");
        }
    }

    // Parameters are set before the call that uses them, and a change shows
    // in the next call.
    for (const Call &c : of(r, "filter.apply"))
        EXPECT_EQ(c.param, "2");
    const auto generations = of(r, "tf-generator.generate");
    ASSERT_GE(generations.size(), 2u);
    EXPECT_EQ(generations.front().param, "5");
    EXPECT_EQ(generations.back().param, "7");
    // The simplifier: prepare first, with the value it keeps for the run (the
    // fixture fails any importance call made before prepare or after a change).
    const auto prepares = of(r, "simplifier.prepare");
    ASSERT_FALSE(prepares.empty());
    for (const Call &c : prepares)
        EXPECT_EQ(c.param, "3");
    for (const Call &c : of(r, "simplifier.importance"))
        EXPECT_EQ(c.param, "3");

    // The depiction and the legend use two instances of the depictor.
    const auto depicts = of(r, "depictor.depict"), legends = of(r, "depictor.legend");
    ASSERT_FALSE(depicts.empty());
    ASSERT_FALSE(legends.empty());
    EXPECT_NE(depicts.front().instance, legends.front().instance);

    // Simplifier rows (ABI 1.4): the value mapping of the volume, the
    // extremum of every row, and the root's row marked.
    ASSERT_FALSE(r.schemas.empty());
    for (const std::string &s : r.schemas)
        EXPECT_EQ(s, "schema rows14=1 root_row=-1 scale=2 offset=-100 unit=rec");
    EXPECT_TRUE(r.rows_without_extrema.empty());
    ASSERT_FALSE(r.rows.empty());
    double lowest = INFINITY, highest = -INFINITY;
    for (const Row &row : r.rows) {
        lowest = std::min({lowest, row.saddle, row.extremum});
        highest = std::max({highest, row.saddle, row.extremum});
        EXPECT_GE(row.batch, 2u) << "a batch of the decomposition holds the candidates at one saddle";
        if (row.kind == ARBOR_EXTREMUM_MAXIMUM && !row.root) {
            EXPECT_GE(row.extremum, row.saddle);
        } else if (row.kind == ARBOR_EXTREMUM_MINIMUM) {
            EXPECT_LE(row.extremum, row.saddle);
        } else {
            EXPECT_TRUE(row.root) << "kind " << row.kind;
        }
    }
    for (const Row &row : r.rows) {
        if (row.root) {
            EXPECT_EQ(row.saddle, lowest) << "the root's row runs from the global minimum";
            EXPECT_EQ(row.extremum, highest) << "to the global maximum";
        }
    }
    // Every branch of the decomposition was a row (its kind and values).
    std::set<std::tuple<unsigned, double, double>> seen;
    for (const Row &row : r.rows)
        seen.insert({row.kind, row.saddle, row.extremum});
    const auto &branches = decomposition->branches.branches;
    ASSERT_GT(branches.size(), 2u);
    for (std::size_t b = 1; b < branches.size(); ++b) {
        const unsigned kind =
            branches[b].kind == topology::BranchKind::Minimum ? ARBOR_EXTREMUM_MINIMUM : ARBOR_EXTREMUM_MAXIMUM;
        EXPECT_TRUE(seen.count({kind, branches[b].saddle_value, branches[b].extremum_value}))
            << "branch " << b << " was never a row";
    }
}

// The generator leaves the depiction to the host: every table entry's
// opacity is the generator's times the depictor's factor, linear in value
// from the saddle (0.5) to the extremum (1); a generator that does not
// leave it to the host gets its table untouched.
TEST_F(PluginContract, TheHostAppliesTheDepictionWhenLeftToIt)
{
    for (const std::string mode : {"by-host", "plain"}) {
        Pipeline pipeline(*registry);
        pipeline.set_document(document(mode));
        const auto tf = pipeline.run<Stage::TransferFunctions>();
        const TransferFunctions &f = *tf->functions;
        const arbor_branch_tree &tree = tf->depiction->cut->tree->record();
        ASSERT_EQ(f.branch_count(), tree.branch_count);
        for (uint32_t b = 0; b < f.branch_count(); ++b) {
            const auto [lo, hi] = f.domain(b);
            const double s = tree.saddle_value[b], e = tree.extremum_value[b];
            for (uint32_t i = 0; i < f.lut_size(); ++i) {
                const double v = lo + (hi - lo) * i / (f.lut_size() - 1.0);
                const double t = e == s ? 1.0 : std::clamp((v - s) / (e - s), 0.0, 1.0);
                const double factor = mode == "by-host" ? 0.5 + 0.5 * t : 1.0;
                const float *c = f.lut(b) + 4 * i;
                EXPECT_NEAR(c[3], 0.5 * factor, 1e-6) << mode << " branch " << b << " entry " << i;
                EXPECT_FLOAT_EQ(c[0], 0.8f);
            }
            for (uint32_t p = f.point_offsets()[b]; p < f.point_offsets()[b + 1]; ++p) {
                const double v = f.points()[p].value;
                const double t = e == s ? 1.0 : std::clamp((v - s) / (e - s), 0.0, 1.0);
                EXPECT_NEAR(f.points()[p].rgba[3], 0.5 * (mode == "by-host" ? 0.5 + 0.5 * t : 1.0), 1e-6);
            }
        }
    }
}

TEST_F(PluginContract, PointsOutOfValueOrderAreRefused)
{
    Pipeline pipeline(*registry);
    pipeline.set_document(document("disorder"));
    try {
        pipeline.run<Stage::TransferFunctions>();
        FAIL() << "points out of order were accepted";
    } catch (const PluginError &e) {
        EXPECT_NE(std::string(e.what()).find("out of value order"), std::string::npos) << e.what();
        EXPECT_NE(std::string(e.what()).find("org.arbor.test.recorder.generator"), std::string::npos) << e.what();
    }
}

// Renderers use the tables; a person edits points.  An edited point in a
// transfer-function file is never silently ignored: that branch's table is
// rebaked from its points (linear between them), the others stay as written,
// and an edited table whose points were left alone stays as edited.
TEST_F(PluginContract, EditedControlPointsRebakeTheirTable)
{
    Pipeline pipeline(*registry);
    pipeline.set_document(document());
    const auto tf = pipeline.run<Stage::TransferFunctions>();
    const fs::path file = dir / "tf.json";
    write_transfer_functions(file, *tf, "blobs.rec");
    StoredTransferFunctions as_written = read_transfer_functions(file);
    EXPECT_TRUE(as_written.rebaked.empty());
    ASSERT_GE(as_written.functions->branch_count(), 2u);

    nlohmann::json j = nlohmann::json::parse(std::ifstream(file));
    j["branches"][1]["points"][0]["rgba"][3] = 0.9; // the first point of branch 1: opacity 0.5 -> 0.9
    j["branches"][0]["lut"][0][0] = 0.25;          // a table entry of branch 0, its points untouched
    std::ofstream(file) << j.dump(1);
    const StoredTransferFunctions edited = read_transfer_functions(file);
    ASSERT_EQ(edited.rebaked, std::vector<uint32_t>{1});
    const TransferFunctions &f = *edited.functions;
    const uint32_t n = f.lut_size();
    for (uint32_t i = 0; i < n; ++i) {
        // The recorder's points sit at both ends of the domain: linear from
        // 0.9 to 0.5 across the table.
        EXPECT_NEAR(f.lut(1)[4 * i + 3], 0.9 + (0.5 - 0.9) * i / (n - 1.0), 1e-6) << i;
        EXPECT_NEAR(f.lut(1)[4 * i], 0.8, 1e-6);
    }
    EXPECT_FLOAT_EQ(f.lut(0)[0], 0.25f);
    for (uint32_t b = 2; b < f.branch_count(); ++b)
        for (uint32_t i = 0; i < 4 * n; ++i)
            EXPECT_EQ(f.lut(b)[i], as_written.functions->lut(b)[i]);

    // Through the pipeline, as `arbor render --tf` reads it.
    Document d = pipeline.document();
    d.appearance.transfer_functions_file = file;
    pipeline.set_document(d);
    const auto from_file = pipeline.run<Stage::TransferFunctions>();
    EXPECT_NEAR(from_file->functions->lut(1)[3], 0.9, 1e-6);
}

// The colour formulas of depictor.h, on colours worked out by hand.
TEST(DepictionColour, HueAndVividnessFollowTheContract)
{
    std::vector<arbor_branch_role> role(1, ARBOR_ROLE_OTHER);
    std::vector<float> at_saddle(1, 1.0f), at_extremum(1, 1.0f), hue(1, 120.0f), saturation(1, 1.0f);
    arbor_depiction d{};
    d.struct_size = sizeof d;
    d.branch_count = 1;
    d.role = role.data();
    d.opacity_at_saddle = at_saddle.data();
    d.opacity_at_extremum = at_extremum.data();
    d.hue = hue.data();
    d.saturation = saturation.data();
    // Red with hue 120 is green (HSV saturation and value kept).
    Rgb c = depiction_colour(d, 0, {1.0, 0.0, 0.0});
    EXPECT_NEAR(c[0], 0.0, 1e-9);
    EXPECT_NEAR(c[1], 1.0, 1e-9);
    EXPECT_NEAR(c[2], 0.0, 1e-9);
    c = depiction_colour(d, 0, {0.5, 0.25, 0.25}); // hue 0, s 0.5, v 0.5 -> hue 120
    EXPECT_NEAR(c[0], 0.25, 1e-9);
    EXPECT_NEAR(c[1], 0.5, 1e-9);
    EXPECT_NEAR(c[2], 0.25, 1e-9);
    // Vividness 0: the grey of the same L*.  sRGB red has L* 53.2408
    // (CIELAB, D65): Y 0.2126729, the grey of that luminance is sRGB 0.498519.
    hue[0] = std::nanf("");
    saturation[0] = 0.0f;
    c = depiction_colour(d, 0, {1.0, 0.0, 0.0});
    // (The published sRGB matrices are inverse to about 1e-7.)
    EXPECT_NEAR(c[0], 0.498519, 1e-5);
    EXPECT_NEAR(c[1], c[0], 1e-6);
    EXPECT_NEAR(c[2], c[0], 1e-6);
    EXPECT_NEAR(rgb_to_lab(c)[0], 53.2408, 1e-3);
    // Half the chroma at the same L* and hue angle.
    saturation[0] = 0.5f;
    const Lab before = rgb_to_lab({0.2, 0.6, 0.9});
    const Lab after = rgb_to_lab(depiction_colour(d, 0, {0.2, 0.6, 0.9}));
    EXPECT_NEAR(after[0], before[0], 1e-4);
    EXPECT_NEAR(after[1], 0.5 * before[1], 1e-4);
    EXPECT_NEAR(after[2], 0.5 * before[2], 1e-4);
}

} // namespace
} // namespace arbor::pipeline
