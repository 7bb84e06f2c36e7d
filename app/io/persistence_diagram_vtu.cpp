#include "persistence_diagram_vtu.hpp"

#include "topology/persistence_diagram.hpp"

#include <vtkCellArray.h>
#include <vtkCellData.h>
#include <vtkDoubleArray.h>
#include <vtkFloatArray.h>
#include <vtkIdTypeArray.h>
#include <vtkIntArray.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkUnsignedCharArray.h>
#include <vtkUnstructuredGrid.h>
#include <vtkXMLUnstructuredGridWriter.h>

#include <algorithm>
#include <limits>
#include <stdexcept>
#include <system_error>
#include <unistd.h>

namespace arbor::io {

namespace {

enum CriticalType { kMinimum = 0, kSaddle1 = 1, kSaddle2 = 2, kMaximum = 3 };

} // namespace

void write_persistence_diagram_vtu(const std::filesystem::path &path,
                                   const std::vector<topology::PersistencePair> &pairs_in, const Geometry &grid)
{
    // The essential pair first, the others in their order.
    std::vector<topology::PersistencePair> pairs;
    pairs.reserve(pairs_in.size());
    for (const auto &p : pairs_in)
        if (p.type == -1)
            pairs.push_back(p);
    for (const auto &p : pairs_in)
        if (p.type != -1)
            pairs.push_back(p);
    const int grid_dim = topology::grid_dimension(grid);
    const vtkIdType n = static_cast<vtkIdType>(pairs.size());

    vtkNew<vtkUnstructuredGrid> vtu;
    vtkNew<vtkPoints> points;
    points->SetDataTypeToDouble();
    points->SetNumberOfPoints(2 * n);
    vtkNew<vtkIntArray> vertex, critical, pair_id, pair_type;
    vtkNew<vtkFloatArray> coordinates;
    vtkNew<vtkDoubleArray> persistence, birth;
    vtkNew<vtkUnsignedCharArray> finite;
    vertex->SetName("ttkVertexScalarField");
    critical->SetName("CriticalType");
    coordinates->SetName("Coordinates");
    coordinates->SetNumberOfComponents(3);
    pair_id->SetName("PairIdentifier");
    pair_type->SetName("PairType");
    persistence->SetName("Persistence");
    birth->SetName("Birth");
    finite->SetName("IsFinite");
    vertex->SetNumberOfTuples(2 * n);
    critical->SetNumberOfTuples(2 * n);
    coordinates->SetNumberOfTuples(2 * n);

    vtkNew<vtkCellArray> cells;
    const int saddle_of_maxima = grid_dim == 3 ? kSaddle2 : kSaddle1;
    vtkIdType highest_birth = 0;
    for (vtkIdType i = 0; i < n; ++i) {
        const topology::PersistencePair &p = pairs[static_cast<std::size_t>(i)];
        if (p.birth > static_cast<uint32_t>(std::numeric_limits<int>::max()) ||
            p.death > static_cast<uint32_t>(std::numeric_limits<int>::max()))
            throw std::runtime_error(path.string() + ": vertex ids beyond 2^31 do not fit TTK's integer arrays");
        points->SetPoint(2 * i, p.birth_value, p.birth_value, 0.0);
        points->SetPoint(2 * i + 1, p.birth_value, p.death_value, 0.0);
        const vtkIdType line[2] = {2 * i, 2 * i + 1};
        cells->InsertNextCell(2, line);
        vertex->SetValue(2 * i, static_cast<int>(p.birth));
        vertex->SetValue(2 * i + 1, static_cast<int>(p.death));
        const int birth_type = p.type == 2 ? saddle_of_maxima : kMinimum;
        const int death_type = p.type == 0 ? kSaddle1 : kMaximum;
        critical->SetValue(2 * i, birth_type);
        critical->SetValue(2 * i + 1, death_type);
        for (int end = 0; end < 2; ++end) {
            const auto mm = grid.position_of(end == 0 ? p.birth : p.death);
            coordinates->SetTuple3(2 * i + end, mm[0], mm[1], mm[2]);
        }
        pair_id->InsertNextValue(static_cast<int>(i));
        pair_type->InsertNextValue(topology::pair_dimension(p.type, grid_dim));
        persistence->InsertNextValue(p.persistence());
        birth->InsertNextValue(p.birth_value);
        finite->InsertNextValue(p.type == -1 ? 0 : 1);
        if (p.birth_value > pairs[static_cast<std::size_t>(highest_birth)].birth_value)
            highest_birth = i;
    }
    if (n > 0) {
        // The diagonal, as TTK draws it.
        const vtkIdType line[2] = {0, 2 * highest_birth};
        cells->InsertNextCell(2, line);
        pair_id->InsertNextValue(-1);
        pair_type->InsertNextValue(-1);
        const bool has_essential = pairs.front().type == -1;
        persistence->InsertNextValue(has_essential ? 2.0 * pairs.front().persistence() : 0.0);
        birth->InsertNextValue(0.0);
        finite->InsertNextValue(0);
    }
    vtu->SetPoints(points);
    vtu->SetCells(VTK_LINE, cells);
    for (vtkDataArray *a : {static_cast<vtkDataArray *>(vertex), static_cast<vtkDataArray *>(critical),
                            static_cast<vtkDataArray *>(coordinates)})
        vtu->GetPointData()->AddArray(a);
    for (vtkDataArray *a : {static_cast<vtkDataArray *>(pair_id), static_cast<vtkDataArray *>(pair_type),
                            static_cast<vtkDataArray *>(persistence), static_cast<vtkDataArray *>(birth),
                            static_cast<vtkDataArray *>(finite)})
        vtu->GetCellData()->AddArray(a);

    // A temporary file beside the target, renamed over it once whole.
    std::filesystem::path temporary = path;
    temporary += ".tmp-" + std::to_string(::getpid()) + ".vtu";
    vtkNew<vtkXMLUnstructuredGridWriter> writer;
    writer->SetFileName(temporary.c_str());
    writer->SetInputData(vtu);
    writer->SetDataModeToBinary();
    writer->SetCompressorTypeToZLib();
    const bool written = writer->Write() == 1 && writer->GetErrorCode() == 0;
    std::error_code ec;
    if (!written) {
        std::filesystem::remove(temporary, ec);
        throw std::runtime_error(path.string() + ": cannot write the diagram (is the folder writable?)");
    }
    std::filesystem::rename(temporary, path, ec);
    if (ec) {
        const std::string why = ec.message();
        std::filesystem::remove(temporary, ec);
        throw std::runtime_error(path.string() + ": cannot replace the file: " + why);
    }
}

} // namespace arbor::io
