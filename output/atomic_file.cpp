#include "output/atomic_file.h"

#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>

#include "core/check.h"

namespace kerf {

std::string temporary_path(const std::string& path) { return path + ".tmp" + std::to_string(::getpid()); }

void commit_file(const std::string& temporary, const std::string& path) {
  std::error_code error;
  std::filesystem::rename(temporary, path, error);
  KERF_CHECK(!error, "cannot move ", temporary, " to ", path, ": ", error.message());
}

void write_file_atomically(const std::string& path, const std::string& content) {
  std::string temporary = temporary_path(path);
  std::FILE* file = std::fopen(temporary.c_str(), "wb");
  KERF_CHECK(file, "cannot write ", temporary, ": ", std::strerror(errno));
  bool ok = std::fwrite(content.data(), 1, content.size(), file) == content.size();
  ok = (std::fclose(file) == 0) && ok;
  KERF_CHECK(ok, "cannot write ", temporary, ": ", std::strerror(errno));
  commit_file(temporary, path);
}

}  // namespace kerf
