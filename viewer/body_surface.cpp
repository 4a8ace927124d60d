#include "viewer/body_surface.h"

#include <algorithm>

#include <vtkCellArray.h>
#include <vtkCellType.h>
#include <vtkDoubleArray.h>
#include <vtkIdTypeArray.h>
#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkUnsignedCharArray.h>

#include "core/check.h"
#include "geometry/delaunay_mesh.h"

namespace kerf {
namespace {

const OutputField* field(const BodySnapshot& body, const std::string& name) {
  for (const OutputField& f : body.point_fields)
    if (f.name == name) return &f;
  return nullptr;
}

vtkNew<vtkDoubleArray> named_array(const char* name, int components, Index tuples) {
  vtkNew<vtkDoubleArray> a;
  a->SetName(name);
  a->SetNumberOfComponents(components);
  a->SetNumberOfTuples(tuples);
  return a;
}

}  // namespace

BodySurface::BodySurface(const BodySnapshot& body) {
  meshless_ = std::all_of(body.cell_types.begin(), body.cell_types.end(), [](std::uint8_t t) { return t == VTK_VERTEX; });
  if (meshless_) {
    const Mesh delaunay = delaunay_mesh(body.points, 3);
    tetrahedra_ = delaunay.cells;
    dropped_.assign(delaunay.cell_count(), 0);
  }
  take_cells(body);
  update(body);
}

void BodySurface::take_cells(const BodySnapshot& body) {
  reference_ = body.points;
  const Index n = static_cast<Index>(reference_.size());
  auto reference = named_array(reference_array, 3, n);
  for (Index i = 0; i < n; ++i) reference->SetTuple(i, reference_[i].data());
  grid_->GetPointData()->AddArray(reference);
  if (meshless_) return rebuild_meshless_cells();
  vtkNew<vtkCellArray> cells;
  vtkNew<vtkUnsignedCharArray> types;
  Index begin = 0;
  for (std::size_t c = 0; c < body.cell_types.size(); ++c) {
    const Index end = body.offsets[c];
    std::vector<vtkIdType> ids(body.connectivity.begin() + begin, body.connectivity.begin() + end);
    cells->InsertNextCell(static_cast<vtkIdType>(ids.size()), ids.data());
    types->InsertNextValue(body.cell_types[c]);
    begin = end;
  }
  grid_->SetCells(types, cells);
  snapshot_cells_ = static_cast<Index>(body.cell_types.size());
}

void BodySurface::rebuild_meshless_cells() {
  vtkNew<vtkCellArray> cells;
  for (std::size_t c = 0; c < dropped_.size(); ++c) {
    if (dropped_[c]) continue;
    const vtkIdType ids[4] = {tetrahedra_[4 * c], tetrahedra_[4 * c + 1], tetrahedra_[4 * c + 2],
                              tetrahedra_[4 * c + 3]};
    cells->InsertNextCell(4, ids);
  }
  grid_->SetCells(VTK_TETRA, cells);
}

void BodySurface::update(const BodySnapshot& body) {
  if (!meshless_ && (static_cast<Index>(body.cell_types.size()) != snapshot_cells_ ||
                     body.points.size() != reference_.size()))
    take_cells(body);
  const OutputField* displacement = field(body, "displacement");
  const OutputField* mises = field(body, "von_mises");
  KERF_CHECK(displacement && mises, "internal: the body's snapshot has no displacement or von_mises field");
  const Index n = static_cast<Index>(reference_.size());
  vtkNew<vtkPoints> points;
  points->SetNumberOfPoints(n);
  auto stress = named_array("von_mises", 1, n);
  for (Index i = 0; i < n; ++i) {
    const Vec3 x = reference_[i] + Vec3(displacement->values[3 * i], displacement->values[3 * i + 1],
                                        displacement->values[3 * i + 2]);
    points->SetPoint(i, x.data());
    stress->SetValue(i, mises->values[i]);
  }
  grid_->SetPoints(points);
  grid_->GetPointData()->AddArray(stress);
  grid_->GetPointData()->SetActiveScalars("von_mises");
}

void BodySurface::cut_by(const CutSurface& cut, Index first) {
  if (!meshless_ || first >= cut.piece_count()) return;
  Vec3 low = Vec3::Constant(1e300), high = -low;
  for (Index k = first; k < cut.piece_count(); ++k)
    for (const Vec3& c : cut.pieces[k].corner) low = low.cwiseMin(c), high = high.cwiseMax(c);
  bool changed = false;
  constexpr int edges[6][2] = {{0, 1}, {0, 2}, {0, 3}, {1, 2}, {1, 3}, {2, 3}};
  for (std::size_t c = 0; c < dropped_.size(); ++c) {
    if (dropped_[c]) continue;
    const Index* v = &tetrahedra_[4 * c];
    Vec3 cell_low = reference_[v[0]], cell_high = cell_low;
    for (int k = 1; k < 4; ++k) cell_low = cell_low.cwiseMin(reference_[v[k]]), cell_high = cell_high.cwiseMax(reference_[v[k]]);
    if ((cell_high.array() < low.array()).any() || (cell_low.array() > high.array()).any()) continue;
    for (const auto& e : edges)
      if (segment_crosses_cut(cut, first, cut.piece_count(), reference_[v[e[0]]], reference_[v[e[1]]])) {
        dropped_[c] = 1, changed = true;
        break;
      }
  }
  if (changed) rebuild_meshless_cells();
}

}  // namespace kerf
