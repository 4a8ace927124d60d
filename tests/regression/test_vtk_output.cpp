// The ParaView files open with VTK's own reader and hold the documented fields.
#include <gtest/gtest.h>
#include <vtkCellData.h>
#include <vtkDataArray.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkUnstructuredGrid.h>
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
    // The quadratic tet keeps positive volumes in VTK's node order.
    double bounds[6];
    grid->GetCell(0)->GetBounds(bounds);
    EXPECT_GT(bounds[1], bounds[0]);
  }
}

}  // namespace
}  // namespace kerf
