// The VTU of a persistence diagram read back by VTK's own XML reader:
// counts, array names and types (those TTK's diagram filters look up), and
// every value against the pairs it was written from.
#include "test_paths.hpp"

#include "io/persistence_diagram_vtu.hpp"

#include <gtest/gtest.h>
#include <vtkCellData.h>
#include <vtkDataArray.h>
#include <vtkFloatArray.h>
#include <vtkIdList.h>
#include <vtkIntArray.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkUnstructuredGrid.h>
#include <vtkXMLUnstructuredGridReader.h>

namespace arbor {
namespace {

using topology::PersistencePair;

TEST(DiagramVtu, VtkReadsBackEveryPairInTtksLayout)
{
    Geometry grid;
    grid.dims = {10, 20, 30};
    grid.spacing = {0.5, 1.0, 2.0};
    grid.origin = {-10.0, 5.0, 100.0};
    // As persistence_pairs() sorts them: by persistence, the essential one last.
    const std::vector<PersistencePair> pairs{
        {0, 11, 12, 3.0, 4.0},       // (minimum, join saddle)
        {2, 1234, 1300, 50.0, 90.5}, // (split saddle, maximum)
        {0, 7, 4321, 1.0, 60.0},
        {-1, 5, 5999, 0.0, 200.0},   // (global minimum, global maximum)
    };
    const std::filesystem::path path = test::scratch_dir() / "diagram.vtu";
    io::write_persistence_diagram_vtu(path, pairs, grid);

    vtkNew<vtkXMLUnstructuredGridReader> reader;
    reader->SetFileName(path.c_str());
    reader->Update();
    vtkUnstructuredGrid *vtu = reader->GetOutput();
    ASSERT_NE(vtu, nullptr);
    ASSERT_EQ(vtu->GetNumberOfPoints(), 8);
    ASSERT_EQ(vtu->GetNumberOfCells(), 5); // a line per pair and the diagonal

    auto *vertex = vtkIntArray::SafeDownCast(vtu->GetPointData()->GetArray("ttkVertexScalarField"));
    auto *critical = vtkIntArray::SafeDownCast(vtu->GetPointData()->GetArray("CriticalType"));
    auto *coords = vtkFloatArray::SafeDownCast(vtu->GetPointData()->GetArray("Coordinates"));
    auto *pair_id = vtkIntArray::SafeDownCast(vtu->GetCellData()->GetArray("PairIdentifier"));
    auto *pair_type = vtkIntArray::SafeDownCast(vtu->GetCellData()->GetArray("PairType"));
    vtkDataArray *persistence = vtu->GetCellData()->GetArray("Persistence");
    vtkDataArray *birth = vtu->GetCellData()->GetArray("Birth");
    vtkDataArray *finite = vtu->GetCellData()->GetArray("IsFinite");
    ASSERT_TRUE(vertex && critical && coords && pair_id && pair_type && persistence && birth && finite)
        << "an array is missing or not of the type TTK's readers cast to";
    EXPECT_EQ(coords->GetNumberOfComponents(), 3);

    // The essential pair first, then the others in their order.
    const std::vector<PersistencePair> order{pairs[3], pairs[0], pairs[1], pairs[2]};
    const int critical_birth[] = {0, 0, 2, 0}, critical_death[] = {3, 1, 3, 1}, dimension[] = {0, 0, 2, 0};
    for (vtkIdType i = 0; i < 4; ++i) {
        const PersistencePair &p = order[static_cast<std::size_t>(i)];
        vtkNew<vtkIdList> ids;
        vtu->GetCellPoints(i, ids);
        ASSERT_EQ(ids->GetNumberOfIds(), 2);
        EXPECT_EQ(ids->GetId(0), 2 * i);
        EXPECT_EQ(ids->GetId(1), 2 * i + 1);
        double b[3], d[3];
        vtu->GetPoint(2 * i, b);
        vtu->GetPoint(2 * i + 1, d);
        EXPECT_EQ(b[0], p.birth_value);
        EXPECT_EQ(b[1], p.birth_value);
        EXPECT_EQ(d[0], p.birth_value);
        EXPECT_EQ(d[1], p.death_value);
        EXPECT_EQ(b[2], 0.0);
        EXPECT_EQ(vertex->GetValue(2 * i), static_cast<int>(p.birth));
        EXPECT_EQ(vertex->GetValue(2 * i + 1), static_cast<int>(p.death));
        EXPECT_EQ(critical->GetValue(2 * i), critical_birth[i]);
        EXPECT_EQ(critical->GetValue(2 * i + 1), critical_death[i]);
        EXPECT_EQ(pair_id->GetValue(i), i);
        EXPECT_EQ(pair_type->GetValue(i), dimension[i]);
        EXPECT_EQ(persistence->GetTuple1(i), p.death_value - p.birth_value);
        EXPECT_EQ(birth->GetTuple1(i), p.birth_value);
        EXPECT_EQ(finite->GetTuple1(i), p.type == -1 ? 0.0 : 1.0);
        // Coordinates: the vertex's position in mm.
        const auto mm = grid.position_of(p.death);
        double c[3];
        coords->GetTuple(2 * i + 1, c);
        for (int k = 0; k < 3; ++k)
            EXPECT_FLOAT_EQ(static_cast<float>(c[k]), static_cast<float>(mm[k]));
    }
    // The diagonal: from point 0 to the point of the largest birth (50).
    vtkNew<vtkIdList> diagonal;
    vtu->GetCellPoints(4, diagonal);
    EXPECT_EQ(diagonal->GetId(0), 0);
    EXPECT_EQ(diagonal->GetId(1), 4);
    EXPECT_EQ(pair_id->GetValue(4), -1);
    EXPECT_EQ(pair_type->GetValue(4), -1);
    EXPECT_EQ(persistence->GetTuple1(4), 400.0);
    EXPECT_EQ(finite->GetTuple1(4), 0.0);
}

TEST(DiagramVtu, AnUnwritableFolderIsNamed)
{
    const std::vector<PersistencePair> pairs{{-1, 0, 1, 0.0, 1.0}};
    Geometry grid;
    grid.dims = {2, 1, 1};
    try {
        io::write_persistence_diagram_vtu("/nonexistent-folder/diagram.vtu", pairs, grid);
        FAIL() << "no error";
    } catch (const std::runtime_error &e) {
        EXPECT_NE(std::string(e.what()).find("/nonexistent-folder/diagram.vtu"), std::string::npos) << e.what();
    }
}

} // namespace
} // namespace arbor
