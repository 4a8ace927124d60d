#pragma once
// How many threads kerf runs and how they wait, set before libgomp loads
// (it reads its environment once, when the library is loaded): `kerf` sets
// the variables and then loads the program, which links libgomp
// (cli/launcher.cpp); another program sets them and starts itself again, once.
//
// - Threads: the cores this process is given, never more: its CPU affinity
//   (taskset, mpirun's binding), its cgroup's CPU quota (containers, CI), and
//   under mpirun without binding its share of the machine's cores among the
//   ranks on it. OMP_THREAD_LIMIT caps CHOLMOD, whose regions ask a fixed 4
//   threads; OpenBLAS (Debian's OpenMP build) follows OpenMP's count.
// - Waiting: passive (threads sleep at once at a barrier). libgomp's default
//   spins 300 000 times first (7 ms here): beside one CPU-bound process a
//   2-thread implicit step took 5 times its idle time, spinning threads
//   holding the core the preempted one needed. Idle, passive costs CHOLMOD's
//   factorization 2.8x; GOMP_SPINCOUNT=1000, if the user sets it, gives that
//   back (results/scaling.md, "Threads beside another process").
// A variable the user set is left alone; KERF_THREAD_POLICY=off leaves all.
// The variables kerf set are recorded in KERF_THREAD_POLICY with the
// process id, so that a kerf started by this one (a study's point, mpirun's
// ranks) sets its own instead of inheriting them as the user's.
#include <sched.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <string>
#include <thread>

namespace kerf {

struct CoreBudget {
  int cores = 1;
  std::string limited_by;  // "machine", "affinity", "cgroup quota", "MPI ranks on this machine"
};

namespace thread_policy_detail {

/// CPUs the cgroup's quota allows (cgroup v2 cpu.max up the hierarchy, or v1
/// cfs_quota_us), or 0 when unlimited or unknown.
inline double cgroup_cpu_quota() {
  double least = 0.0;
  auto take = [&](double quota, double period) {
    if (quota > 0.0 && period > 0.0 && (least == 0.0 || quota / period < least)) least = quota / period;
  };
  std::ifstream self("/proc/self/cgroup");
  std::string line, path;
  while (std::getline(self, line))
    if (line.rfind("0::", 0) == 0) path = line.substr(3);
  for (std::string dir = path;; dir = dir.substr(0, dir.find_last_of('/'))) {
    std::ifstream max("/sys/fs/cgroup" + dir + "/cpu.max");
    std::string quota;
    double period = 0.0;
    if (max >> quota >> period && quota != "max") take(std::atof(quota.c_str()), period);
    if (dir.empty() || dir == "/") break;
  }
  std::ifstream v1_quota("/sys/fs/cgroup/cpu/cpu.cfs_quota_us"), v1_period("/sys/fs/cgroup/cpu/cpu.cfs_period_us");
  double quota = 0.0, period = 0.0;
  if (v1_quota >> quota && v1_period >> period) take(quota, period);
  return least;
}

/// Ranks of this MPI job on this machine (Open MPI, MPICH), 1 outside mpirun.
inline int local_ranks() {
  for (const char* name : {"OMPI_COMM_WORLD_LOCAL_SIZE", "MPI_LOCALNRANKS"})
    if (const char* v = std::getenv(name)) return std::max(1, std::atoi(v));
  return 1;
}

/// Whether `name` holds what an earlier kerf process set (recorded in
/// `marker` as "|NAME=value"): then it is not the user's.
inline bool set_by_kerf(const std::string& marker, const char* name) {
  const char* value = std::getenv(name);
  return value && marker.find("|" + std::string(name) + "=" + value + "|") != std::string::npos;
}

}  // namespace thread_policy_detail

/// The cores this process may use (see above).
inline CoreBudget cores_given() {
  using namespace thread_policy_detail;
  const int machine = static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
  CoreBudget budget{machine, "machine"};
  cpu_set_t set;
  if (sched_getaffinity(0, sizeof(set), &set) == 0 && CPU_COUNT(&set) < budget.cores)
    budget = {CPU_COUNT(&set), "affinity"};
  if (const double quota = cgroup_cpu_quota(); quota > 0.0 && std::ceil(quota) < budget.cores)
    budget = {static_cast<int>(std::max(1.0, std::ceil(quota))), "cgroup quota"};
  // Unbound ranks (affinity still the whole machine) share its cores.
  if (const int ranks = local_ranks(); ranks > 1 && budget.cores == machine)
    budget = {std::max(1, machine / ranks), "MPI ranks on this machine"};
  return budget;
}

/// What the threads are in this process, for the summary: the wait policy
/// libgomp was given, and the cores and what limited them when kerf chose.
inline std::string wait_policy_in_effect() {
  if (const char* wait = std::getenv("OMP_WAIT_POLICY")) return wait;
  if (const char* spin = std::getenv("GOMP_SPINCOUNT")) return std::string("spin count ") + spin;
  return "libgomp default (spins 300 000 times, then sleeps)";
}
/// A field of KERF_THREAD_POLICY ("limited_by"), or "" when kerf did not choose.
inline std::string thread_policy_field(const std::string& field) {
  const char* marker = std::getenv("KERF_THREAD_POLICY");
  if (!marker) return "";
  const std::string text = marker, key = "|" + field + "=";
  const std::size_t at = text.find(key);
  if (at == std::string::npos) return "";
  const std::size_t begin = at + key.size();
  return text.substr(begin, text.find('|', begin) - begin);
}

/// Sets the thread count, limit and wait policy in the environment (unless
/// set); false when they are in place already (set by the user, or by this
/// very process).
inline bool set_thread_policy_environment() {
  using namespace thread_policy_detail;
  const char* previous = std::getenv("KERF_THREAD_POLICY");
  const std::string marker = previous ? previous : "";
  const std::string pid = std::to_string(::getpid());
  // Set by this very process (before it started itself again), or by the user: done.
  if (previous && (marker.rfind(pid + "|", 0) == 0 || marker.find('|') == std::string::npos)) return false;
  const CoreBudget budget = cores_given();
  const std::string cores = std::to_string(budget.cores);
  std::string record = pid + "|";
  auto set = [&](const char* name, const std::string& value) {
    if (std::getenv(name) && !set_by_kerf(marker, name)) return;  // the user's
    ::setenv(name, value.c_str(), 1);
    record += std::string(name) + "=" + value + "|";
  };
  set("OMP_THREAD_LIMIT", cores);
  set("OMP_NUM_THREADS", cores);
  if (!std::getenv("GOMP_SPINCOUNT")) set("OMP_WAIT_POLICY", "passive");
  ::setenv("KERF_THREAD_POLICY", (record + "limited_by=" + budget.limited_by + "|").c_str(), 1);
  return true;
}

/// For a program that links libgomp (loaded, and its variables read, before
/// main): sets them and starts the program again with them; returns at once
/// when they are in place. `kerf` itself sets them before it loads libgomp
/// (cli/launcher.cpp) and starts once.
inline void apply_thread_policy(char** argv) {
  if (set_thread_policy_environment()) ::execv("/proc/self/exe", argv);
  // If the exec fails, carry on with the library's defaults.
}

}  // namespace kerf
