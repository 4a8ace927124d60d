// The .pvtu a run across ranks wrote against the .vtu of the serial run:
// its pieces together hold every cell of the serial file exactly once, each
// rank wrote a piece (the cell field `rank` takes every value 0..ranks-1), and
// the displacement at each cell's points is the serial cell's to `tolerance`
// times the largest. Read with VTK's own readers, as ParaView reads them.
// usage: pieces_match_serial SERIAL.vtu PARALLEL.pvtu RANKS TOLERANCE
#include <vtkCell.h>
#include <vtkCellData.h>
#include <vtkDataArray.h>
#include <vtkIdList.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkUnstructuredGrid.h>
#include <vtkXMLPUnstructuredGridReader.h>
#include <vtkXMLUnstructuredGridReader.h>

#include <array>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <map>
#include <set>
#include <string>

namespace {

using Key = std::array<long long, 4>;  // cell type and centroid, or 0 and a point, on a fine grid

[[noreturn]] void fail(const std::string& message) {
  std::fprintf(stderr, "FAILED: %s\n", message.c_str());
  std::exit(1);
}

struct Grid {
  double origin[3], step;
  Key key(long long type, const double x[3]) const {
    Key k{type, 0, 0, 0};
    for (int i = 0; i < 3; ++i) k[i + 1] = std::llround((x[i] - origin[i]) / step);
    return k;
  }
};

Key cell_key(vtkUnstructuredGrid* mesh, vtkIdType c, const Grid& grid) {
  vtkCell* cell = mesh->GetCell(c);
  double centroid[3] = {0, 0, 0}, x[3];
  const vtkIdType n = cell->GetNumberOfPoints();
  for (vtkIdType a = 0; a < n; ++a) {
    mesh->GetPoint(cell->GetPointId(a), x);
    for (int i = 0; i < 3; ++i) centroid[i] += x[i] / n;
  }
  return grid.key(cell->GetCellType(), centroid);
}

void check_cells(vtkUnstructuredGrid* serial, vtkUnstructuredGrid* parallel, const Grid& grid) {
  std::map<Key, int> unmatched;
  for (vtkIdType c = 0; c < serial->GetNumberOfCells(); ++c) ++unmatched[cell_key(serial, c, grid)];
  for (vtkIdType c = 0; c < parallel->GetNumberOfCells(); ++c) {
    auto it = unmatched.find(cell_key(parallel, c, grid));
    if (it == unmatched.end() || it->second == 0)
      fail("the pieces' cell " + std::to_string(c) + " is not a serial cell, or is there twice");
    --it->second;
  }
  if (parallel->GetNumberOfCells() != serial->GetNumberOfCells())
    fail("the pieces hold " + std::to_string(parallel->GetNumberOfCells()) + " cells, the serial file " +
         std::to_string(serial->GetNumberOfCells()));
}

void check_ranks(vtkUnstructuredGrid* parallel, int ranks) {
  vtkDataArray* rank = parallel->GetCellData()->GetArray("rank");
  if (!rank) fail("the pieces have no cell field 'rank'");
  std::set<int> seen;
  for (vtkIdType c = 0; c < rank->GetNumberOfTuples(); ++c) seen.insert(static_cast<int>(rank->GetTuple1(c)));
  if (static_cast<int>(seen.size()) != ranks || *seen.begin() != 0 || *seen.rbegin() != ranks - 1)
    fail("the cell field 'rank' takes " + std::to_string(seen.size()) + " values; expected 0.." +
         std::to_string(ranks - 1));
}

/// Cell by cell (points on a cut's two faces share positions, so points are
/// matched through the cell they belong to): each piece cell's points are its
/// serial cell's, in the same order, with the same displacement.
void check_displacements(vtkUnstructuredGrid* serial, vtkUnstructuredGrid* parallel, const Grid& grid,
                         double tolerance) {
  vtkDataArray* u_serial = serial->GetPointData()->GetArray("displacement");
  vtkDataArray* u_parallel = parallel->GetPointData()->GetArray("displacement");
  if (!u_serial || !u_parallel) fail("a file has no point field 'displacement'");
  std::map<Key, vtkIdType> serial_cell;
  for (vtkIdType c = 0; c < serial->GetNumberOfCells(); ++c) serial_cell[cell_key(serial, c, grid)] = c;
  double largest = 0.0;
  for (vtkIdType p = 0; p < serial->GetNumberOfPoints(); ++p)
    for (int i = 0; i < 3; ++i) largest = std::max(largest, std::abs(u_serial->GetComponent(p, i)));
  double worst = 0.0;
  vtkNew<vtkIdList> mine, theirs;
  for (vtkIdType c = 0; c < parallel->GetNumberOfCells(); ++c) {
    parallel->GetCellPoints(c, mine);
    serial->GetCellPoints(serial_cell.at(cell_key(parallel, c, grid)), theirs);
    for (vtkIdType a = 0; a < mine->GetNumberOfIds(); ++a) {
      const vtkIdType p = mine->GetId(a), q = theirs->GetId(a);
      if (grid.key(0, parallel->GetPoint(p)) != grid.key(0, serial->GetPoint(q)))
        fail("the pieces' cell " + std::to_string(c) + " lists its points in another order than the serial cell");
      for (int i = 0; i < 3; ++i)
        worst = std::max(worst, std::abs(u_parallel->GetComponent(p, i) - u_serial->GetComponent(q, i)));
    }
  }
  std::printf("pieces: displacement differs from serial by %.3g of the largest %.6g\n", worst / largest, largest);
  if (worst > tolerance * largest) {
    char message[128];
    std::snprintf(message, sizeof message, "the displacements differ by more than %g of the largest", tolerance);
    fail(message);
  }
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 5) fail("usage: pieces_match_serial SERIAL.vtu PARALLEL.pvtu RANKS TOLERANCE");
  vtkNew<vtkXMLUnstructuredGridReader> serial_reader;
  serial_reader->SetFileName(argv[1]);
  serial_reader->Update();
  vtkNew<vtkXMLPUnstructuredGridReader> parallel_reader;
  parallel_reader->SetFileName(argv[2]);
  parallel_reader->Update();
  vtkUnstructuredGrid* serial = serial_reader->GetOutput();
  vtkUnstructuredGrid* parallel = parallel_reader->GetOutput();
  if (serial->GetNumberOfCells() == 0) fail(std::string("no cells in ") + argv[1]);
  double bounds[6];
  serial->GetBounds(bounds);
  const double diagonal =
      std::hypot(bounds[1] - bounds[0], bounds[3] - bounds[2], bounds[5] - bounds[4]);
  const Grid grid{{bounds[0], bounds[2], bounds[4]}, 1e-9 * diagonal};
  check_cells(serial, parallel, grid);
  check_ranks(parallel, std::atoi(argv[3]));
  check_displacements(serial, parallel, grid, std::atof(argv[4]));
  std::printf("pieces: %lld cells in %s ranks, each once\n", static_cast<long long>(parallel->GetNumberOfCells()),
              argv[3]);
  return 0;
}
