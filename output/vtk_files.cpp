// Inside the VTK module only (output/vtk_module.h is the door): a body's
// snapshot as a .vtu file and a lattice as a .vti file, by VTK's XML writers.
#include "output/vtk_files.h"

#include <vtkCellArray.h>
#include <vtkCellData.h>
#include <vtkDoubleArray.h>
#include <vtkIdTypeArray.h>
#include <vtkImageData.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkUnsignedCharArray.h>
#include <vtkUnstructuredGrid.h>
#include <vtkXMLImageDataWriter.h>
#include <vtkXMLUnstructuredGridWriter.h>

#include "core/check.h"
#include "output/atomic_file.h"

namespace kerf {
namespace {

vtkNew<vtkDoubleArray> make_array(const OutputField& field, std::size_t tuples) {
  vtkNew<vtkDoubleArray> array;
  array->SetName(field.name.c_str());
  array->SetNumberOfComponents(field.components);
  array->SetNumberOfTuples(static_cast<vtkIdType>(tuples));
  KERF_CHECK(field.values.size() == tuples * field.components, "field '", field.name, "' has ", field.values.size(),
             " values; expected ", tuples * field.components);
  std::copy(field.values.begin(), field.values.end(), array->GetPointer(0));
  return array;
}

}  // namespace

void vtk_write_vtu(const BodySnapshot& s, const std::string& path) {
  vtkNew<vtkPoints> points;
  points->SetDataTypeToDouble();
  points->SetNumberOfPoints(static_cast<vtkIdType>(s.points.size()));
  for (std::size_t i = 0; i < s.points.size(); ++i)
    points->SetPoint(static_cast<vtkIdType>(i), s.points[i].data());
  vtkNew<vtkIdTypeArray> offsets, connectivity;
  offsets->SetNumberOfTuples(static_cast<vtkIdType>(s.offsets.size() + 1));
  offsets->SetValue(0, 0);
  for (std::size_t c = 0; c < s.offsets.size(); ++c) offsets->SetValue(static_cast<vtkIdType>(c + 1), s.offsets[c]);
  connectivity->SetNumberOfTuples(static_cast<vtkIdType>(s.connectivity.size()));
  for (std::size_t k = 0; k < s.connectivity.size(); ++k)
    connectivity->SetValue(static_cast<vtkIdType>(k), s.connectivity[k]);
  vtkNew<vtkCellArray> cells;
  cells->SetData(offsets, connectivity);
  vtkNew<vtkUnsignedCharArray> types;
  types->SetNumberOfTuples(static_cast<vtkIdType>(s.cell_types.size()));
  for (std::size_t c = 0; c < s.cell_types.size(); ++c) types->SetValue(static_cast<vtkIdType>(c), s.cell_types[c]);

  vtkNew<vtkUnstructuredGrid> grid;
  grid->SetPoints(points);
  grid->SetCells(types, cells);
  for (const OutputField& f : s.point_fields) {
    auto array = make_array(f, s.points.size());
    grid->GetPointData()->AddArray(array);
    if (f.name == "displacement") grid->GetPointData()->SetVectors(array);
  }
  for (const OutputField& f : s.cell_fields) grid->GetCellData()->AddArray(make_array(f, s.cell_types.size()));

  std::string temporary = temporary_path(path);
  vtkNew<vtkXMLUnstructuredGridWriter> writer;
  writer->SetFileName(temporary.c_str());
  writer->SetInputData(grid);
  writer->SetDataModeToAppended();
  writer->EncodeAppendedDataOff();
  KERF_CHECK(writer->Write() == 1, "VTK could not write ", temporary);
  commit_file(temporary, path);
}

void vtk_write_vti(const LatticeSnapshot& l, const std::string& path) {
  vtkNew<vtkImageData> image;
  image->SetDimensions(static_cast<int>(l.count[0]), static_cast<int>(l.count[1]), static_cast<int>(l.count[2]));
  image->SetSpacing(l.spacing, l.spacing, l.spacing);
  image->SetOrigin(l.origin.data());
  double direction[9];
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) direction[3 * r + c] = l.axes[c][r];  // the axes are its columns
  image->SetDirectionMatrix(direction);
  const std::size_t points = static_cast<std::size_t>(l.count[0]) * l.count[1] * l.count[2];
  image->GetPointData()->SetScalars(make_array(OutputField{"phi", 1, l.values}, points));
  std::string temporary = temporary_path(path);
  vtkNew<vtkXMLImageDataWriter> writer;
  writer->SetFileName(temporary.c_str());
  writer->SetInputData(image);
  writer->SetDataModeToAppended();
  writer->EncodeAppendedDataOff();
  KERF_CHECK(writer->Write() == 1, "VTK could not write ", temporary);
  commit_file(temporary, path);
}

}  // namespace kerf
