// Reading persistence diagrams: TTK's reference files (gzip), our CSV written
// and read back, and malformed files refused with the file and line named.
#include "test_paths.hpp"

#include "io/persistence_diagram_files.hpp"

#include <gtest/gtest.h>
#include <zlib.h>

#include <fstream>
#include <sstream>

namespace arbor {
namespace {

namespace fs = std::filesystem;

TEST(DiagramFiles, ReadsTtksReferenceFile)
{
    const fs::path path = test::shared_dir() / "reference/ttk/bucky.pairs.txt.gz";
    // An independent count: the data lines, by zlib directly.
    std::size_t lines = 0, type2 = 0, essential = 0;
    gzFile f = gzopen(path.c_str(), "rb");
    ASSERT_NE(f, nullptr);
    char buf[1024];
    while (gzgets(f, buf, sizeof buf))
        if (buf[0] != '#') {
            ++lines;
            type2 += buf[0] == '2';
            essential += buf[0] == '-';
        }
    gzclose(f);
    const topology::PersistenceDiagram d = io::read_persistence_diagram(path);
    ASSERT_EQ(d.points.size(), lines);
    std::size_t dim2 = 0, ess = 0;
    for (const auto &p : d.points) {
        dim2 += p.dimension == 2;
        ess += p.essential;
        EXPECT_GE(p.death, p.birth);
    }
    EXPECT_EQ(dim2, type2);
    EXPECT_EQ(ess, essential);
    EXPECT_EQ(ess, 1u);
}

TEST(DiagramFiles, CsvRoundTripKeepsDimensionsAndTheEssentialPair)
{
    Geometry grid;
    grid.dims = {4, 5, 1}; // a single slice: saddle-maximum pairs are dimension 1
    const std::vector<topology::PersistencePair> pairs{
        {0, 1, 2, 1.5, 2.25}, {2, 3, 7, 4.0, 9.0}, {-1, 0, 19, 0.0, 10.0}};
    const fs::path path = test::scratch_dir() / "pairs.csv";
    {
        std::ofstream out(path);
        io::write_pairs_csv(out, pairs, grid, ARBOR_VOXEL_F32);
    }
    std::ifstream in(path);
    std::string header;
    std::getline(in, header);
    EXPECT_EQ(header, "dimension,birth,death,persistence,essential,birth_vertex,death_vertex,bx,by,bz,dx,dy,dz");
    std::string second;
    std::getline(in, second);
    EXPECT_EQ(second, "0,1.5,2.25,0.75,0,1,2,1,0,0,2,0,0");
    const topology::PersistenceDiagram d = io::read_persistence_diagram(path);
    ASSERT_EQ(d.points.size(), 3u);
    EXPECT_EQ(d.points[1].dimension, 1);
    EXPECT_EQ(d.points[1].birth, 4.0);
    EXPECT_EQ(d.points[1].death, 9.0);
    EXPECT_TRUE(d.points[2].essential);
    EXPECT_FALSE(d.points[0].essential);
}

std::string error_of(const std::string &name, const std::string &content)
{
    const fs::path path = test::scratch_dir() / name;
    std::ofstream(path) << content;
    try {
        io::read_persistence_diagram(path);
    } catch (const std::runtime_error &e) {
        return e.what();
    }
    return "no error";
}

TEST(DiagramFiles, MalformedFilesNameTheLine)
{
    EXPECT_NE(error_of("a.txt", "# dims=2 2 2\n0 1 2 3 4\n0 1 2 x 4\n").find("a.txt:3: birth value \"x\""),
              std::string::npos);
    EXPECT_NE(error_of("b.txt", "0 1 2 5 4\n").find("b.txt:1: death"), std::string::npos);
    EXPECT_NE(error_of("c.txt", "7 1 2 3 4\n").find("c.txt:1: pair type 7"), std::string::npos);
    EXPECT_NE(error_of("d.txt", "0 1 2\n").find("d.txt:1: expected"), std::string::npos);
    EXPECT_NE(error_of("e.csv", "dimension,birth,death\n0,1,2\n0,1\n").find("e.csv:3: 2 values"),
              std::string::npos);
    EXPECT_NE(error_of("f.csv", "dim,birth,death\n").find("needs the columns"), std::string::npos);
    EXPECT_NE(error_of("g.csv", "dimension,birth,death,essential\n0,1,2,5\n").find("g.csv:2: essential"),
              std::string::npos);
    EXPECT_NE(error_of("h.txt", "").find("h.txt: empty"), std::string::npos);
    EXPECT_NE(error_of("i.txt", "0 1 2 3 nan\n").find("i.txt:1:"), std::string::npos);
}

} // namespace
} // namespace arbor
