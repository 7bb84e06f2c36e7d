// Arbor's persistence pairs equal TTK's, exactly, on every reference volume
// (shared/reference/ttk, README.md there): each volume is imported through the
// plugins as the host does, its topology computed with persistence
// importance, and the set of (type, birth vertex, death vertex) compared with
// the reference file's.  The reference values are checked against the
// imported voxels, so a reader that reorders or rescales voxels cannot pass.
// On the small volumes the test suite's own elder-rule oracle
// (topology_oracles.hpp) is checked against TTK as well, which validates the
// oracle the unit property tests rely on.
#include "plugin_fixture.hpp"
#include "topology_oracles.hpp"

#include "topology/persistence_pairs.hpp"
#include "topology/topology_pipeline.hpp"

#include <gtest/gtest.h>
#include <zlib.h>

#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <iostream>
#include <map>
#include <set>
#include <sstream>
#include <string>
#include <vector>

namespace arbor {
namespace {

namespace fs = std::filesystem;
using test::PairKey;

struct ReferenceCase {
    std::string name;     // <name>.pairs.txt.gz
    std::string data;     // the volume, relative to the shared folder
    std::string type;     // voxel type as the reference header writes it
};

// The table of shared/reference/ttk/README.md.  Raw files are opened through
// their detached NRRD headers.
const std::vector<ReferenceCase> &reference_cases()
{
    static const std::vector<ReferenceCase> cases{
        {"bucky", "data/bucky/bucky.nhdr", "uint8"},
        {"nucleon", "data/nucleon/nucleon.nrrd", "uint8"},
        {"neghip", "data/neghip/neghip.nhdr", "uint8"},
        {"hydrogen_orbital", "data/hydrogen_orbital/hydrogen.vti", "float32"},
        {"ironprot", "data/ironprot/ironProt.vtk", "uint8"},
        {"mr_head_lowres", "data/mr_head_lowres/HeadMRVolume.mhd", "uint8"},
        {"tooth", "data/tooth/tooth.nhdr", "uint8"},
        {"tooth16", "data/tooth16_bigendian/tooth.nhdr", "uint16"},
        {"walnut", "data/walnut/walnut.nhdr", "uint16"},
        {"mr_brain_tumor1", "data/mr_brain_tumor_pyradiomics/brain1_image.nrrd", "int16"},
        {"ct_chest_lidc2", "data/ct_chest_lidc2/LIDC2.mha", "uint8"},
        {"engine", "data/engine/engine.vti", "uint8"},
        {"mr_brain_colin27", "data/mr_brain_colin27/ch2.nii.gz", "uint8"},
        {"ct_angio_avm", "data/ct_angio_avm/CT_AVM.nii.gz", "uint8"},
        {"bonsai", "data/bonsai/bonsai.vti", "uint8"},
        {"aneurism", "data/aneurism/aneurism.vti", "uint8"},
        {"blobs_64", "reference/ttk/synthetic/blobs_64.nhdr", "float32"},
        {"blobsnoise_64", "reference/ttk/synthetic/blobsnoise_64.nhdr", "float32"},
        {"random_64", "reference/ttk/synthetic/random_64.nhdr", "float32"},
    };
    return cases;
}

fs::path reference_dir()
{
    return test::shared_dir() / "reference" / "ttk";
}

struct ReferencePair {
    PairKey key;
    double birth_value, death_value;
};

struct ReferenceFile {
    std::map<std::string, std::string> header; // data=, dims=, type= from the comment lines
    std::vector<ReferencePair> pairs;
};

// Reads a gzip'd pair file with zlib; '#' lines are comments (the second one
// carries "data=... dims=nx ny nz type=...").
ReferenceFile read_reference(const fs::path &path)
{
    ReferenceFile out;
    gzFile in = gzopen(path.c_str(), "rb");
    if (!in)
        throw std::runtime_error("cannot open " + path.string());
    char line[1024];
    while (gzgets(in, line, sizeof line)) {
        std::string text(line);
        if (text.empty() || text == "\n")
            continue;
        if (text[0] == '#') {
            for (const char *key : {"dims=", "type="}) {
                const std::size_t at = text.find(key);
                if (at == std::string::npos)
                    continue;
                std::size_t end = text.find(key == std::string("dims=") ? " type=" : "\n", at);
                out.header[key] = text.substr(at + 5, end == std::string::npos ? end : end - at - 5);
            }
            continue;
        }
        std::istringstream fields(text);
        ReferencePair p{};
        std::string birth_value, death_value;
        if (!(fields >> p.key.type >> p.key.birth >> p.key.death >> birth_value >> death_value)) {
            gzclose(in);
            throw std::runtime_error("malformed line in " + path.string() + ": " + text);
        }
        p.birth_value = std::strtod(birth_value.c_str(), nullptr);
        p.death_value = std::strtod(death_value.c_str(), nullptr);
        out.pairs.push_back(p);
    }
    gzclose(in);
    return out;
}

// Up to `limit` elements of a - b, for the failure message.
std::string first_missing(const std::set<PairKey> &a, const std::set<PairKey> &b, std::size_t limit = 8)
{
    std::ostringstream out;
    std::size_t shown = 0, total = 0;
    for (const PairKey &p : a)
        if (!b.count(p)) {
            if (shown++ < limit)
                out << " " << p;
            ++total;
        }
    if (total > limit)
        out << " ... (" << total << " in all)";
    return out.str();
}

// Stored values compared in the precision they were written with: float32
// data round-trips through "%.9g".
bool same_value(const Volume &volume, double reference, uint32_t vertex)
{
    const double stored = volume.value(vertex);
    if (volume.type() == ARBOR_VOXEL_F32)
        return static_cast<float>(reference) == static_cast<float>(stored);
    return reference == stored;
}

class TtkReferencePairs : public testing::TestWithParam<ReferenceCase> {};

TEST_P(TtkReferencePairs, PairsEqualTtk)
{
    const ReferenceCase &c = GetParam();
    const fs::path ref_path = reference_dir() / (c.name + ".pairs.txt.gz");
    const fs::path data_path = test::shared_dir() / c.data;
    ASSERT_TRUE(fs::exists(ref_path)) << ref_path;
    ASSERT_TRUE(fs::exists(data_path)) << data_path;

    const ReferenceFile ref = read_reference(ref_path);
    ASSERT_FALSE(ref.pairs.empty()) << ref_path;
    const Volume volume = test::import(data_path);
    const Geometry &g = volume.geometry();
    std::ostringstream dims;
    dims << g.dims[0] << " " << g.dims[1] << " " << g.dims[2];
    EXPECT_EQ(ref.header.at("dims="), dims.str()) << "the reference was computed on another grid";
    EXPECT_EQ(ref.header.at("type="), c.type);

    // The reference values are the stored voxel values at those vertices.
    const uint32_t n = static_cast<uint32_t>(volume.voxel_count());
    std::set<PairKey> want;
    std::size_t value_mismatches = 0;
    for (const ReferencePair &p : ref.pairs) {
        want.insert(p.key);
        ASSERT_LT(p.key.birth, n);
        ASSERT_LT(p.key.death, n);
        if (!same_value(volume, p.birth_value, p.key.birth) || !same_value(volume, p.death_value, p.key.death)) {
            if (value_mismatches++ < 5)
                ADD_FAILURE() << "reference pair " << p.key << " has values " << p.birth_value << ", "
                              << p.death_value << "; the volume holds " << volume.value(p.key.birth) << ", "
                              << volume.value(p.key.death);
        }
    }
    EXPECT_EQ(value_mismatches, 0u);
    EXPECT_EQ(want.size(), ref.pairs.size()) << "the reference lists a pair twice";

    const auto start = std::chrono::steady_clock::now();
    const topology::TopologyResult r = topology::compute_topology(volume, topology::persistence_importance());
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    const topology::FieldView field{volume.type(), volume.data(), n, &g};
    const std::vector<topology::PersistencePair> pairs = topology::persistence_pairs(r.tree, r.branches, field);
    std::set<PairKey> got;
    for (const topology::PersistencePair &p : pairs) {
        got.insert({p.type, p.birth, p.death});
        EXPECT_EQ(p.birth_value, volume.value(p.birth));
        EXPECT_EQ(p.death_value, volume.value(p.death));
    }
    EXPECT_EQ(got.size(), pairs.size()) << "Arbor lists a pair twice";
    EXPECT_EQ(got.size(), want.size());
    EXPECT_TRUE(got == want) << c.name << ": " << got.size() << " pairs, TTK " << want.size()
                             << "\n  only in Arbor:" << first_missing(got, want)
                             << "\n  only in TTK:" << first_missing(want, got);
    std::cout << "[   INFO   ] " << c.name << ": " << want.size() << " pairs, topology in " << seconds << " s\n";

    // The independent elder-rule oracle agrees with TTK too (small volumes only:
    // it is written for clarity, not speed).
    if (n <= 320000) {
        const std::vector<PairKey> oracle = test::elder_rule_pairs(test::field_of(volume));
        const std::set<PairKey> oracle_set(oracle.begin(), oracle.end());
        EXPECT_TRUE(oracle_set == want) << c.name << ": the elder-rule oracle disagrees with TTK"
                                        << "\n  only in the oracle:" << first_missing(oracle_set, want)
                                        << "\n  only in TTK:" << first_missing(want, oracle_set);
    }
}

INSTANTIATE_TEST_SUITE_P(Shared, TtkReferencePairs, testing::ValuesIn(reference_cases()),
                         [](const testing::TestParamInfo<ReferenceCase> &info) { return info.param.name; });

// Every reference file has a case above, so a new one cannot be skipped.
TEST(TtkReferenceFiles, EveryFileHasATestCase)
{
    std::set<std::string> listed;
    for (const ReferenceCase &c : reference_cases())
        listed.insert(c.name + ".pairs.txt.gz");
    std::set<std::string> present;
    for (const auto &entry : fs::directory_iterator(reference_dir())) {
        const std::string file = entry.path().filename().string();
        if (file.size() > 13 && file.ends_with(".pairs.txt.gz"))
            present.insert(file);
    }
    EXPECT_EQ(present, listed);
    EXPECT_EQ(present.size(), 19u);
}

} // namespace
} // namespace arbor
