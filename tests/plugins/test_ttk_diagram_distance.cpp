// Diagram distances between Arbor's persistence diagram of a shared volume
// (imported through the plugins, as the host does) and TTK's reference
// diagram of the same volume (shared/reference/ttk, read by the same reader
// `arbor diagram-distance` uses): both metrics must say 0, since the pairs
// are the same.  And against a real change of the data: the stability
// theorem (Cohen-Steiner, Edelsbrunner, Harer) bounds the bottleneck
// distance by the largest change of a value.
#include "plugin_fixture.hpp"

#include "io/persistence_diagram_files.hpp"
#include "topology/diagram_distance.hpp"
#include "topology/persistence_diagram.hpp"
#include "topology/persistence_pairs.hpp"
#include "topology/topology_pipeline.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <fstream>
#include <iostream>

namespace arbor {
namespace {

namespace fs = std::filesystem;

struct Case {
    std::string name, data;
};

class TtkDiagramDistance : public testing::TestWithParam<Case> {};

topology::PersistenceDiagram arbor_diagram(const Volume &volume, std::vector<topology::PersistencePair> *pairs_out)
{
    const topology::TopologyResult r = topology::compute_topology(volume, topology::persistence_importance());
    const topology::FieldView field{volume.type(), volume.data(), static_cast<uint32_t>(volume.voxel_count()),
                                    &volume.geometry()};
    std::vector<topology::PersistencePair> pairs = topology::persistence_pairs(r.tree, r.branches, field);
    const topology::PersistenceDiagram d = topology::diagram_of_pairs(pairs, topology::grid_dimension(volume.geometry()));
    if (pairs_out)
        *pairs_out = std::move(pairs);
    return d;
}

TEST_P(TtkDiagramDistance, ArborAndTtkDiagramsAreAtDistanceZero)
{
    const Case &c = GetParam();
    const Volume volume = test::import(test::shared_dir() / c.data);
    std::vector<topology::PersistencePair> pairs;
    const topology::PersistenceDiagram ours = arbor_diagram(volume, &pairs);
    const topology::PersistenceDiagram ttk =
        io::read_persistence_diagram(test::shared_dir() / "reference" / "ttk" / (c.name + ".pairs.txt.gz"));
    ASSERT_EQ(ours.points.size(), ttk.points.size());
    // TTK's file prints a value with 9 significant digits: exact for
    // integers, and for a float32 volume the float back but not the double
    // we compare it with, which can differ by up to half a float's unit in
    // the last place of the largest value (2^-24 of it). Integer volumes must
    // be at distance exactly 0.
    double largest = 0;
    for (const auto &p : ours.points)
        largest = std::max({largest, std::abs(p.birth), std::abs(p.death)});
    const bool floating = volume.type() == ARBOR_VOXEL_F32 || volume.type() == ARBOR_VOXEL_F64;
    const double tolerance = floating ? largest * std::ldexp(1.0, -24) : 0.0;
    for (auto metric : {topology::DiagramMetric::Bottleneck, topology::DiagramMetric::Wasserstein}) {
        const auto start = std::chrono::steady_clock::now();
        const topology::DiagramDistance d = topology::diagram_distance(ours, ttk, {metric, 2.0, {}});
        const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        EXPECT_LE(d.total, tolerance) << c.name;
        ASSERT_FALSE(d.dimensions.empty());
        EXPECT_EQ(d.dimensions[0].essential_a, 1u);
        EXPECT_EQ(d.dimensions[0].essential_b, 1u);
        std::cout << "[   INFO   ] " << c.name << ": " << ours.points.size() << " pairs, "
                  << (metric == topology::DiagramMetric::Bottleneck ? "bottleneck" : "W2") << " 0 in " << seconds
                  << " s\n";
    }
    // Through our CSV and back: still the same diagram.
    const fs::path csv = test::scratch_dir() / (c.name + ".csv");
    {
        std::ofstream out(csv);
        io::write_pairs_csv(out, pairs, volume.geometry(), volume.type());
    }
    const topology::PersistenceDiagram again = io::read_persistence_diagram(csv);
    // Both sides printed with the same 9 digits: exactly the same values.
    EXPECT_EQ(topology::diagram_distance(again, ttk, {topology::DiagramMetric::Bottleneck, 2.0, {}}).total, 0.0);
}

INSTANTIATE_TEST_SUITE_P(Shared, TtkDiagramDistance,
                         testing::Values(Case{"bucky", "data/bucky/bucky.nhdr"},
                                         Case{"nucleon", "data/nucleon/nucleon.nrrd"},
                                         Case{"neghip", "data/neghip/neghip.nhdr"},
                                         Case{"hydrogen_orbital", "data/hydrogen_orbital/hydrogen.vti"},
                                         Case{"mr_head_lowres", "data/mr_head_lowres/HeadMRVolume.mhd"},
                                         Case{"tooth", "data/tooth/tooth.nhdr"}),
                         [](const testing::TestParamInfo<Case> &info) { return info.param.name; });

// nucleon with the top voxel of its most persistent (non-global) maximum
// lowered to the saddle's value: the diagrams differ (> 0), by no more than
// the change of that voxel (stability), and W2 is never below the
// bottleneck distance.
TEST(TtkDiagramDistanceChange, StabilityBoundsTheChange)
{
    Volume volume = test::import(test::shared_data("nucleon/nucleon.nrrd"));
    std::vector<topology::PersistencePair> pairs;
    const topology::PersistenceDiagram before = arbor_diagram(volume, &pairs);
    const topology::PersistencePair *top = nullptr;
    for (const auto &p : pairs)
        if (p.type == 2 && (!top || p.persistence() > top->persistence()))
            top = &p;
    ASSERT_NE(top, nullptr);
    ASSERT_EQ(volume.type(), ARBOR_VOXEL_U8);
    static_cast<uint8_t *>(volume.data())[top->death] = static_cast<uint8_t>(top->birth_value);
    const topology::PersistenceDiagram after = arbor_diagram(volume, nullptr);
    const double bn = topology::diagram_distance(before, after, {topology::DiagramMetric::Bottleneck, 2.0, {}}).total;
    const double w2 = topology::diagram_distance(before, after, {topology::DiagramMetric::Wasserstein, 2.0, {}}).total;
    EXPECT_GT(bn, 0.0);
    EXPECT_LE(bn, top->persistence()) << "|f - g| is at most the change of that voxel";
    EXPECT_GE(w2, bn);
}

} // namespace
} // namespace arbor
