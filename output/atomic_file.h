#pragma once
// Files written so that a crash or Ctrl-C never leaves a half-written one:
// write beside the target, then rename over it.
#include <string>

namespace kerf {

void write_file_atomically(const std::string& path, const std::string& content);
/// The temporary name to write to before `commit_file` renames it into place.
std::string temporary_path(const std::string& path);
void commit_file(const std::string& temporary, const std::string& path);

}  // namespace kerf
