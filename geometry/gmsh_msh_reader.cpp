#include "geometry/gmsh_meshing.h"

#include <gmsh.h>
#include <poll.h>
#include <sys/prctl.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <csignal>
#include <cstring>
#include <filesystem>
#include <fstream>

#include "core/check.h"
#include "geometry/gmsh_session.h"

namespace kerf {
namespace {

// Child-to-parent message: a status byte, then either an error text or the mesh.
enum : char { ok_status = 'M', error_status = 'E' };

void write_all(int fd, const void* data, std::size_t bytes) {
  const char* p = static_cast<const char*>(data);
  while (bytes > 0) {
    ssize_t n = ::write(fd, p, bytes);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) ::_exit(3);
    p += n;
    bytes -= static_cast<std::size_t>(n);
  }
}

/// A crash in gmsh ends this child alone and the parent reports it: crash
/// handlers inherited from the parent (a sanitizer's, a fuzzer's) would
/// report it as the parent's own. The child dies with the parent.
void become_a_disposable_child() {
  for (int signal : {SIGSEGV, SIGBUS, SIGFPE, SIGILL, SIGABRT, SIGINT, SIGTERM}) std::signal(signal, SIG_DFL);
  ::prctl(PR_SET_PDEATHSIG, SIGKILL);
}

[[noreturn]] void child_read(const std::string& path, int dimension, MshOrder order, int fd) {
  become_a_disposable_child();
  std::string error;
  Mesh mesh;
  int file_order = 0;
  bool read = false;
  try {
    ensure_gmsh_initialized();
    gmsh::open(path);
    extract_gmsh_mesh(dimension, path, mesh);
    file_order = mesh.order;
    if (order == MshOrder::second && mesh.order == 1) {
      gmsh::model::mesh::setOrder(2);
      extract_gmsh_mesh(dimension, path, mesh);
    }
    read = true;
  } catch (const std::exception& e) {
    error = e.what();
  } catch (const std::string& message) {  // gmsh throws its messages as strings
    error = message;
  } catch (...) {
    error = "gmsh raised an unknown exception";
  }
  if (!error.empty() && error.find_first_not_of(" \n") == std::string::npos) error = "gmsh could not read it";
  if (!read && error.empty()) error = "gmsh could not read it";
  if (!read) {
    char status = error_status;
    write_all(fd, &status, 1);
    write_all(fd, error.data(), error.size());
    ::_exit(0);
  }
  char status = ok_status;
  std::int64_t header[5] = {mesh.dimension, mesh.order, static_cast<std::int64_t>(mesh.nodes.size()),
                            static_cast<std::int64_t>(mesh.cells.size()), file_order};
  write_all(fd, &status, 1);
  write_all(fd, header, sizeof header);
  write_all(fd, mesh.nodes.data(), mesh.nodes.size() * sizeof(Vec3));
  write_all(fd, mesh.cells.data(), mesh.cells.size() * sizeof(Index));
  ::_exit(0);
}

/// The child's whole answer; a child still reading after a minute plus a
/// minute per 100 MB of file is killed (gmsh can loop on a malformed file).
std::string answer_within_deadline(int fd, pid_t child, const std::string& path) {
  std::error_code ignored;
  const double megabytes = static_cast<double>(std::filesystem::file_size(path, ignored)) / 1e6;
  const double limit = 60.0 + 0.6 * (ignored ? 0.0 : megabytes);
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::duration<double>(limit);
  std::string message;
  char buffer[1 << 16];
  for (;;) {
    pollfd ready{fd, POLLIN, 0};
    const int polled = ::poll(&ready, 1, 1000);  // a second at a time
    if (polled < 0 && errno == EINTR) continue;
    if (polled == 0) {
      if (std::chrono::steady_clock::now() < deadline) continue;
      ::kill(child, SIGKILL);
      while (::waitpid(child, nullptr, 0) < 0 && errno == EINTR) {
      }
      throw Error(path + ": gmsh was still reading this file after " + std::to_string(static_cast<int>(limit)) +
                  " s (stopped): the mesh file is malformed or far larger than it looks");
    }
    const ssize_t n = ::read(fd, buffer, sizeof buffer);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) break;
    message.append(buffer, static_cast<std::size_t>(n));
  }
  return message;
}

/// Cheap checks before gmsh sees the file.
void precheck(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  KERF_CHECK(in, path, ": cannot open the mesh file");
  std::string first;
  std::getline(in, first);
  if (!first.empty() && first.back() == '\r') first.pop_back();
  KERF_CHECK(first == "$MeshFormat", path, ":1: not a gmsh mesh: expected the first line to be "
             "'$MeshFormat', found '", first.substr(0, 40), "'");
}

}  // namespace

Mesh gmsh_read_msh(const std::string& path, int dimension, MshOrder order, int* file_order) {
  precheck(path);
  int fds[2];
  KERF_CHECK(::pipe(fds) == 0, "cannot create a pipe to read ", path, ": ", std::strerror(errno));
  std::fflush(nullptr);
  pid_t pid = ::fork();
  KERF_CHECK(pid >= 0, "cannot fork to read ", path, ": ", std::strerror(errno));
  if (pid == 0) {
    ::close(fds[0]);
    child_read(path, dimension, order, fds[1]);
  }
  ::close(fds[1]);
  const std::string message = answer_within_deadline(fds[0], pid, path);
  ::close(fds[0]);
  int status = 0;
  while (::waitpid(pid, &status, 0) < 0 && errno == EINTR) {
  }
  if (WIFSIGNALED(status))
    throw Error(path + ": gmsh crashed reading this file (signal " + std::to_string(WTERMSIG(status)) + ", " +
                strsignal(WTERMSIG(status)) + "): the mesh file is malformed");
  KERF_CHECK(WIFEXITED(status) && WEXITSTATUS(status) == 0 && !message.empty(), path,
             ": the gmsh reader process failed (exit status ", WEXITSTATUS(status), ")");
  if (message[0] == error_status) throw Error(path + ": gmsh could not read the mesh: " + message.substr(1));
  std::int64_t header[5];
  KERF_CHECK(message[0] == ok_status && message.size() >= 1 + sizeof header, path,
             ": the gmsh reader process sent a truncated answer");
  std::memcpy(header, message.data() + 1, sizeof header);
  Mesh mesh;
  mesh.dimension = static_cast<int>(header[0]);
  mesh.order = static_cast<int>(header[1]);
  std::size_t node_bytes = static_cast<std::size_t>(header[2]) * sizeof(Vec3);
  std::size_t cell_bytes = static_cast<std::size_t>(header[3]) * sizeof(Index);
  KERF_CHECK(message.size() == 1 + sizeof header + node_bytes + cell_bytes, path,
             ": the gmsh reader process sent a truncated answer");
  mesh.nodes.resize(static_cast<std::size_t>(header[2]));
  mesh.cells.resize(static_cast<std::size_t>(header[3]));
  const char* p = message.data() + 1 + sizeof header;
  std::memcpy(static_cast<void*>(mesh.nodes.data()), p, node_bytes);
  std::memcpy(mesh.cells.data(), p + node_bytes, cell_bytes);
  if (file_order) *file_order = static_cast<int>(header[4]);
  return mesh;
}

}  // namespace kerf
