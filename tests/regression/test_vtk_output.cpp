// The ParaView files open with VTK's own reader and hold the documented fields.
#include <gtest/gtest.h>
#include <vtkCellData.h>
#include <vtkCell.h>
#include <vtkDataArray.h>
#include <vtkIdList.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkUnstructuredGrid.h>
#include <vtkImageData.h>
#include <vtkMatrix3x3.h>
#include <vtkXMLImageDataReader.h>
#include <vtkXMLUnstructuredGridReader.h>

#include <filesystem>
#include <fstream>

#include "app/run_scene.h"
#include "problem/scene_reader.h"
#include "core/check.h"
#include "support/test_support.h"

namespace kerf {
namespace {

TEST(VtkOutput, SeriesOpensWithVtkReaderAndHoldsTheFields) {
  for (const char* element : {"tet4", "tet10"}) {
    std::string dir = testing::output_directory(std::string("vtk_") + element);
    Scene scene = read_scene(testing::source_path("scenes/cantilever.yaml"),
                             {"output.dir=" + dir, std::string("discretization.fem.element=") + element,
                              "discretization.fem.size=0.01", "solve.load_steps=2"});
    RunOutcome outcome = run_scene(scene, {"", true});
    ASSERT_TRUE(std::filesystem::exists(dir + "/cantilever.pvd"));
    std::ifstream pvd(dir + "/cantilever.pvd");
    std::string text((std::istreambuf_iterator<char>(pvd)), std::istreambuf_iterator<char>());
    EXPECT_NE(text.find("cantilever_0002.vtu"), std::string::npos);  // initial state + two load steps

    vtkNew<vtkXMLUnstructuredGridReader> reader;
    reader->SetFileName((dir + "/cantilever_0002.vtu").c_str());
    reader->Update();
    vtkUnstructuredGrid* grid = reader->GetOutput();
    EXPECT_EQ(grid->GetNumberOfPoints(), outcome.summary["counts"]["nodes"].get<long>());
    EXPECT_EQ(grid->GetNumberOfCells(), outcome.summary["counts"]["elements"].get<long>());
    EXPECT_EQ(grid->GetCellType(0), std::string(element) == "tet4" ? 10 : 24);
    vtkDataArray* displacement = grid->GetPointData()->GetArray("displacement");
    ASSERT_NE(displacement, nullptr);
    EXPECT_EQ(displacement->GetNumberOfComponents(), 3);
    ASSERT_NE(grid->GetCellData()->GetArray("stress"), nullptr);
    EXPECT_EQ(grid->GetCellData()->GetArray("stress")->GetNumberOfComponents(), 9);
    ASSERT_NE(grid->GetCellData()->GetArray("von_mises"), nullptr);
    // The tip sags: some point moved down by the probe's amount or more.
    double range[2];
    displacement->GetRange(range, 2);
    EXPECT_LE(range[0], outcome.summary["probes"]["tip"]["displacement"][2].get<double>() * 0.99);
    // VTK's quadratic tetra puts its mid-edge nodes on edges (0,1) (1,2) (0,2)
    // (0,3) (1,3) (2,3): every cell must match (gmsh's 8 and 9 are swapped).
    if (std::string(element) == "tet10") {
      const int edges[6][2] = {{0, 1}, {1, 2}, {0, 2}, {0, 3}, {1, 3}, {2, 3}};
      for (vtkIdType c = 0; c < grid->GetNumberOfCells(); ++c) {
        vtkIdList* ids = grid->GetCell(c)->GetPointIds();
        for (int m = 0; m < 6; ++m) {
          double a[3], b[3], mid[3];
          grid->GetPoint(ids->GetId(edges[m][0]), a);
          grid->GetPoint(ids->GetId(edges[m][1]), b);
          grid->GetPoint(ids->GetId(4 + m), mid);
          for (int k = 0; k < 3; ++k) ASSERT_NEAR(mid[k], 0.5 * (a[k] + b[k]), 1e-12) << "cell " << c << " edge " << m;
        }
      }
    }
  }
}

// A growing cut: its surface is a part of its own with the opening across it,
// and the Enrichment Grid's phi a .vti lattice (in the cut's frame) in [-1, 1].
TEST(VtkOutput, GrowingCutWritesItsSurfaceAndTheGridsPhi) {
  const std::string dir = testing::output_directory("vtk_growing_cut");
  Scene scene = read_scene(testing::source_path("scenes/cutting_2d.yaml"), {"output.dir=" + dir, "output.vtk.every=50"});
  run_scene(scene, {"", true});
  std::ifstream pvd(dir + "/cutting_2d.pvd");
  std::string text((std::istreambuf_iterator<char>(pvd)), std::istreambuf_iterator<char>());
  EXPECT_NE(text.find("part=\"1\" file=\"cutting_2d_cut_0002.vtu\""), std::string::npos) << text;
  EXPECT_NE(text.find("part=\"2\" file=\"cutting_2d_phi_cut0_0002.vti\""), std::string::npos) << text;
  // Every step lists every part (ParaView's reader reads only the parts of
  // the first step; tests/paraview opens a cut that appears later).
  auto count = [&](const std::string& part) {
    int n = 0;
    for (auto at = text.find(part); at != std::string::npos; at = text.find(part, at + 1)) ++n;
    return n;
  };
  EXPECT_GT(count("part=\"0\""), 2);
  EXPECT_EQ(count("part=\"1\" file=\"cutting_2d_cut_"), count("part=\"0\""));
  EXPECT_EQ(count("part=\"2\" file=\"cutting_2d_phi_cut0_"), count("part=\"0\""));

  vtkNew<vtkXMLUnstructuredGridReader> reader;
  reader->SetFileName((dir + "/cutting_2d_cut_0002.vtu").c_str());
  reader->Update();
  vtkUnstructuredGrid* cut = reader->GetOutput();
  EXPECT_EQ(cut->GetNumberOfCells(), 20);  // every segment present at the end
  EXPECT_EQ(cut->GetCellType(0), 3);       // VTK_LINE
  vtkDataArray* opening = cut->GetPointData()->GetArray("opening");
  ASSERT_NE(opening, nullptr);
  // The cut is open behind its tip: the faces part in y.
  EXPECT_GT(opening->GetComponent(10, 1), 1e-7);
  ASSERT_NE(cut->GetCellData()->GetArray("appears"), nullptr);

  vtkNew<vtkXMLImageDataReader> image_reader;
  image_reader->SetFileName((dir + "/cutting_2d_phi_cut0_0002.vti").c_str());
  image_reader->Update();
  vtkImageData* image = image_reader->GetOutput();
  vtkDataArray* phi = image->GetPointData()->GetArray("phi");
  ASSERT_NE(phi, nullptr);
  EXPECT_GT(image->GetNumberOfPoints(), 1000);
  double low = 2.0, high = -2.0;
  for (vtkIdType p = 0; p < phi->GetNumberOfTuples(); ++p)
    low = std::min(low, phi->GetTuple1(p)), high = std::max(high, phi->GetTuple1(p));
  EXPECT_NEAR(low, -1.0, 1e-12);
  EXPECT_NEAR(high, 1.0, 1e-12);
  // The lattice's first axis runs along the cut (+x), its second along the normal.
  EXPECT_NEAR(image->GetDirectionMatrix()->GetElement(0, 0), 1.0, 1e-12);
  EXPECT_NEAR(image->GetDirectionMatrix()->GetElement(1, 1), 1.0, 1e-12);
}

// FEM's cut is in the series too (the same generic snapshot reads the opening
// through the remeshed cells on either face): the kinked crack is closed at its
// tips and open at its kinks, 3.5 mm either side of its centre, about as much
// as at the centre (an elliptical opening would give sqrt(1 - 0.35^2) = 0.94 of it).
TEST(VtkOutput, FemRemeshedCrackWritesItsSurfaceWithTheOpening) {
  const std::string dir = testing::output_directory("vtk_fem_crack");
  Scene scene = read_scene(testing::source_path("scenes/crack_kinked_2d.yaml"),
                           {"output.dir=" + dir, "discretization.method=fem", "discretization.fem.element=tri6",
                            "discretization.fem.size=0.001"});
  const auto summary = run_scene(scene, {"", true}).summary;
  const auto& p = summary["probes"];
  const Eigen::Vector2d centre(
      p["upper_face"]["displacement"][0].get<double>() - p["lower_face"]["displacement"][0].get<double>(),
      p["upper_face"]["displacement"][1].get<double>() - p["lower_face"]["displacement"][1].get<double>());
  vtkNew<vtkXMLUnstructuredGridReader> reader;
  reader->SetFileName((dir + "/crack_kinked_2d_cut_0001.vtu").c_str());
  reader->Update();
  vtkUnstructuredGrid* cut = reader->GetOutput();
  ASSERT_EQ(cut->GetNumberOfCells(), 3);
  vtkDataArray* opening = cut->GetPointData()->GetArray("opening");
  ASSERT_NE(opening, nullptr);
  auto at = [&](vtkIdType v) { return Eigen::Vector2d(opening->GetComponent(v, 0), opening->GetComponent(v, 1)); };
  for (vtkIdType tip : {0, 3}) EXPECT_LT(at(tip).norm(), 0.05 * centre.norm()) << "tip " << tip;
  for (vtkIdType kink : {1, 2}) {
    std::printf("kink %lld opens %.3e m, the centre %.3e m\n", static_cast<long long>(kink), at(kink).norm(),
                centre.norm());
    EXPECT_GT(at(kink).norm(), 0.8 * centre.norm()) << "kink " << kink;
    EXPECT_LT(at(kink).norm(), 1.0 * centre.norm()) << "kink " << kink;
  }
}

}  // namespace
}  // namespace kerf
