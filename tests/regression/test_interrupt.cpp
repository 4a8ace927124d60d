// Ctrl-C (SIGINT) and SIGTERM in the middle of every kind of run, through
// the real `kerf` binary: it stops at the next step, Newton iteration or
// study point, exits 1, says "interrupted" (and which signal) in summary.json,
// and every file it wrote stays readable.
#include <fcntl.h>
#include <stdlib.h>
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>
#include <vtkNew.h>
#include <vtkDataSet.h>
#include <vtkXMLGenericDataObjectReader.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <functional>
#include <nlohmann/json.hpp>
#include <regex>
#include <thread>

#include "support/test_support.h"

namespace kerf {
namespace {

using Json = nlohmann::ordered_json;
using Clock = std::chrono::steady_clock;

int count_lines(const std::string& path) {
  std::ifstream in(path);
  std::string line;
  int n = 0;
  while (std::getline(in, line)) ++n;
  return n;
}

std::string read_text(const std::string& path) {
  std::ifstream in(path);
  return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
}

struct Stopped {
  int status = 0;      // as waitpid gives it
  std::string messages;  // what kerf printed on stderr
};

/// Starts `kerf args...` (stderr to dir/stderr.txt), waits until `ready()`
/// (at most a minute), sends `signal`, and waits for the end (killing it and
/// failing after a minute more).
Stopped run_and_signal(const std::vector<std::string>& args, const std::string& dir,
                       const std::function<bool()>& ready, int signal) {
  const std::string kerf = std::string(KERF_BINARY_DIR) + "/cli/kerf", log = dir + ".stderr.txt";
  std::vector<char*> argv{const_cast<char*>("kerf")};
  for (const std::string& a : args) argv.push_back(const_cast<char*>(a.c_str()));
  argv.push_back(nullptr);
  std::filesystem::remove(log);  // `ready` must not see an earlier run's words
  const pid_t pid = fork();
  if (pid == 0) {
    const int fd = open(log.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    dup2(fd, 2);
    execv(kerf.c_str(), argv.data());
    _exit(127);
  }
  Stopped out;
  if (pid < 0) return ADD_FAILURE() << "fork failed", out;
  const auto started = Clock::now();
  while (!ready() && Clock::now() - started < std::chrono::seconds(60) && waitpid(pid, &out.status, WNOHANG) == 0)
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  EXPECT_TRUE(ready()) << "the run did not get going (or ended first): " << read_text(log);
  kill(pid, signal);
  const auto signalled = Clock::now();
  while (waitpid(pid, &out.status, WNOHANG) == 0) {
    if (Clock::now() - signalled > std::chrono::seconds(60)) {
      kill(pid, SIGKILL);
      waitpid(pid, &out.status, 0);
      ADD_FAILURE() << "still running a minute after the signal";
      break;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  out.messages = read_text(log);
  return out;
}

/// Exit 1 (not death by the signal), the signal named in the message.
void expect_stopped_by(const Stopped& run, const std::string& signal_name) {
  ASSERT_TRUE(WIFEXITED(run.status)) << "kerf died from a signal instead of stopping: " << run.messages;
  EXPECT_EQ(WEXITSTATUS(run.status), 1) << run.messages;
  EXPECT_NE(run.messages.find("interrupted (" + signal_name), std::string::npos) << run.messages;
}

/// summary.json says "interrupted", every file the collections list opens, and
/// the probe table holds whole rows.
void expect_readable_interrupted_run(const std::string& dir, const std::string& signal_name) {
  std::ifstream in(dir + "/summary.json");
  const Json summary = Json::parse(in);
  EXPECT_EQ(summary["status"], "interrupted");
  EXPECT_NE(summary["error"].get<std::string>().find("interrupted (" + signal_name), std::string::npos)
      << summary["error"];
  int files = 0;
  for (const auto& entry : std::filesystem::directory_iterator(dir)) {
    if (entry.path().extension() != ".pvd") continue;
    const std::string text = read_text(entry.path());
    std::regex file_entry("file=\"([^\"]+)\"");
    for (std::sregex_iterator it(text.begin(), text.end(), file_entry), end; it != end; ++it, ++files) {
      vtkNew<vtkXMLGenericDataObjectReader> reader;  // the body's .vtu and the Enrichment Grid's .vti
      reader->SetFileName((dir + "/" + (*it)[1].str()).c_str());
      reader->Update();
      auto* data = vtkDataSet::SafeDownCast(reader->GetOutput());
      EXPECT_TRUE(data && data->GetNumberOfPoints() > 0) << (*it)[1].str();
    }
  }
  EXPECT_GE(files, 2) << "the run wrote fewer than two steps before the signal";
  const std::string table = read_text(dir + "/probes.csv");
  EXPECT_TRUE(!table.empty() && table.back() == '\n') << "the last row of probes.csv is cut short";
}

struct InterruptCase {
  std::string name, scene;
  std::vector<std::string> overrides;
  int signal;
  std::string signal_name;
};

void PrintTo(const InterruptCase& c, std::ostream* out) { *out << c.name; }

class InterruptedRun : public ::testing::TestWithParam<InterruptCase> {};

TEST_P(InterruptedRun, StopsWithReadableOutputAndSaysInterrupted) {
  const InterruptCase& c = GetParam();
  const std::string dir = testing::output_directory("interrupted_" + c.name);
  std::vector<std::string> args{"run", testing::source_path(c.scene), "--out", dir, "--quiet"};
  for (const std::string& o : c.overrides) args.insert(args.end(), {"--set", o});
  // A few steps on disk first.
  const Stopped run = run_and_signal(args, dir, [&] { return count_lines(dir + "/probes.csv") >= 6; }, c.signal);
  expect_stopped_by(run, c.signal_name);
  expect_readable_interrupted_run(dir, c.signal_name);
}

// Each kind of run, each long enough that the signal lands mid-run: implicit
// dynamics, static load steps (Newton in each), explicit dynamics with a
// cut growing through the Enrichment Grid, and FEM remeshing at each new segment.
INSTANTIATE_TEST_SUITE_P(
    EveryKindOfRun, InterruptedRun,
    ::testing::Values(
        InterruptCase{"implicit_ctrl_c", "scenes/block_drop.yaml", {"solve.duration=1000", "output.vtk={every: 2}"},
                      SIGINT, "SIGINT"},
        InterruptCase{"implicit_sigterm", "scenes/block_drop.yaml", {"solve.duration=1000", "output.vtk={every: 2}"},
                      SIGTERM, "SIGTERM"},
        InterruptCase{"static_sigterm", "scenes/block_drop.yaml", {"solve.analysis=static", "solve.load_steps=1000"},
                      SIGTERM, "SIGTERM"},
        InterruptCase{"explicit_cut_update_sigterm", "scenes/cutting_2d.yaml",
                      {"solve.dt=2e-7", "output.vtk={every: 20}"}, SIGTERM, "SIGTERM"},
        InterruptCase{"remesh_ctrl_c", "scenes/cutting_2d.yaml",
                      {"discretization.method=fem", "discretization.fem.element=tri3", "discretization.fem.size=0.001",
                       "cuts.0.fem=remesh", "solve.dt=2e-7", "output.vtk={every: 20}"},
                      SIGINT, "SIGINT"}),
    [](const auto& info) { return info.param.name; });

// gmsh cannot stop midway: a long meshing (a 1.4-million-cell mesh, a
// minute's work) says so and shows it is alive every 10 s, and a signal while
// it meshes is honoured by the watchdog within its grace, summary.json saying
// interrupted.
TEST(InterruptedRun, WhileMeshingShowsProgressStopsWithinTheGraceAndSaysInterrupted) {
  const std::string dir = testing::output_directory("interrupted_meshing");
  std::filesystem::remove_all(dir);
  // --force: the whole run is estimated at about 7 GB, which a smaller machine
  // would refuse before meshing; stopped while gmsh meshes, it peaks near 0.4 GB.
  const std::vector<std::string> args{"run", testing::source_path("scenes/cantilever.yaml"), "--out", dir, "--force",
                                      "--set", "discretization.fem.element=tet4", "--set",
                                      "discretization.fem.size=0.0005"};
  setenv("KERF_MEMORY_LIMIT_MB", "2000", 1);  // as on a small machine: --force must carry it
  const auto started = Clock::now();
  const std::string log = dir + ".stderr.txt";
  auto alive_line = [&] { return read_text(log).find("still setting up (gmsh meshing about") != std::string::npos; };
  const Stopped run = run_and_signal(args, dir, alive_line, SIGTERM);
  expect_stopped_by(run, "SIGTERM");
  EXPECT_NE(run.messages.find("meshing about 1."), std::string::npos) << run.messages;
  EXPECT_NE(run.messages.find(", 10 s so far"), std::string::npos) << run.messages;
  EXPECT_LT(Clock::now() - started, std::chrono::seconds(40)) << "not stopped within the grace";
  std::ifstream in(dir + "/summary.json");
  const Json summary = Json::parse(in);
  EXPECT_EQ(summary["status"], "interrupted");
  EXPECT_NE(summary["error"].get<std::string>().find("could not stop within"), std::string::npos) << summary["error"];
}

// A study stops at its point, not after it: no later point starts, and every
// summary it left says ok or interrupted (none "running").
TEST(InterruptedStudy, StopsAtTheSignalAndLeavesEveryPointReadable) {
  const std::string dir = testing::output_directory("interrupted_study");
  std::filesystem::remove_all(dir);
  auto points_started = [&] {
    if (!std::filesystem::exists(dir + "/scenes")) return 0;
    return static_cast<int>(std::distance(std::filesystem::directory_iterator(dir + "/scenes"), {}));
  };
  const Stopped run = run_and_signal({"study", "hertz", "--quick", "--quiet", "--out", dir}, dir,
                                     [&] { return points_started() >= 2; }, SIGTERM);
  expect_stopped_by(run, "SIGTERM");
  const int started = points_started();
  EXPECT_LE(started, 3) << "the study went on after the signal";
  int summaries = 0;
  for (const auto& entry : std::filesystem::directory_iterator(dir + "/runs")) {
    if (!std::filesystem::exists(entry.path() / "summary.json")) continue;
    std::ifstream in(entry.path() / "summary.json");
    const std::string status = Json::parse(in)["status"];
    EXPECT_TRUE(status == "ok" || status == "interrupted") << entry.path() << ": " << status;
    ++summaries;
  }
  EXPECT_GE(summaries, 1);
}

}  // namespace
}  // namespace kerf
