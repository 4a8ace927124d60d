// Ctrl-C in the middle of a run, through the real `kerf` binary: it stops
// between steps, exits non-zero, says so in summary.json, and every file it
// wrote stays readable.
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>
#include <vtkNew.h>
#include <vtkUnstructuredGrid.h>
#include <vtkXMLUnstructuredGridReader.h>

#include <chrono>
#include <fstream>
#include <nlohmann/json.hpp>
#include <regex>
#include <thread>

#include "support/test_support.h"

namespace kerf {
namespace {

int count_lines(const std::string& path) {
  std::ifstream in(path);
  std::string line;
  int n = 0;
  while (std::getline(in, line)) ++n;
  return n;
}

TEST(Interrupt, CtrlCLeavesEveryFileReadable) {
  std::string dir = testing::output_directory("interrupted");
  std::string kerf = std::string(KERF_BINARY_DIR) + "/app/kerf";
  std::string scene = testing::source_path("scenes/block_drop.yaml");
  pid_t pid = fork();
  ASSERT_GE(pid, 0);
  if (pid == 0) {
    execl(kerf.c_str(), "kerf", "run", scene.c_str(), "--out", dir.c_str(), "--quiet", "--set", "solve.duration=1000",
          "--set", "output.vtk={every: 2}", static_cast<char*>(nullptr));
    _exit(127);
  }
  // Wait until a few steps are on disk, then press Ctrl-C.
  auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(60);
  while (count_lines(dir + "/probes.csv") < 4 && std::chrono::steady_clock::now() < deadline)
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  ASSERT_GE(count_lines(dir + "/probes.csv"), 4) << "the run did not get going";
  kill(pid, SIGINT);
  int status = 0;
  waitpid(pid, &status, 0);
  ASSERT_TRUE(WIFEXITED(status)) << "kerf died from a signal instead of stopping";
  EXPECT_EQ(WEXITSTATUS(status), 1);

  std::ifstream in(dir + "/summary.json");
  nlohmann::ordered_json summary = nlohmann::ordered_json::parse(in);
  EXPECT_EQ(summary["status"], "error");
  EXPECT_NE(summary["error"].get<std::string>().find("interrupted"), std::string::npos);

  // Every .vtu the collection lists opens.
  std::ifstream pvd(dir + "/block_drop.pvd");
  std::string text((std::istreambuf_iterator<char>(pvd)), std::istreambuf_iterator<char>());
  std::regex file_entry("file=\"([^\"]+)\"");
  int files = 0;
  for (std::sregex_iterator it(text.begin(), text.end(), file_entry), end; it != end; ++it, ++files) {
    vtkNew<vtkXMLUnstructuredGridReader> reader;
    reader->SetFileName((dir + "/" + (*it)[1].str()).c_str());
    reader->Update();
    EXPECT_GT(reader->GetOutput()->GetNumberOfPoints(), 0) << (*it)[1].str();
  }
  EXPECT_GE(files, 2);
}

}  // namespace
}  // namespace kerf
