#include "output/probe_table.h"

#include <cerrno>
#include <cstring>

#include "core/check.h"

namespace kerf {

ProbeTable::ProbeTable(const std::string& path, const std::vector<std::string>& columns)
    : path_(path), columns_(columns.size()) {
  file_ = std::fopen(path.c_str(), "wb");
  KERF_CHECK(file_, "cannot write ", path, ": ", std::strerror(errno));
  std::string header;
  for (const auto& c : columns) header += (header.empty() ? "" : ",") + c;
  header += "\n";
  std::fputs(header.c_str(), file_);
  std::fflush(file_);
}

ProbeTable::~ProbeTable() {
  if (file_) std::fclose(file_);
}

void ProbeTable::append(const std::vector<double>& row) {
  KERF_CHECK(row.size() == columns_, "probe row has ", row.size(), " values; expected ", columns_);
  std::string line;
  char cell[32];
  for (std::size_t i = 0; i < row.size(); ++i) {
    std::snprintf(cell, sizeof cell, "%.10g", row[i]);
    if (i) line += ',';
    line += cell;  // (const char* + std::string met GCC 12's false -Wrestrict, PR 105329)
  }
  line += "\n";
  KERF_CHECK(std::fwrite(line.data(), 1, line.size(), file_) == line.size(), "cannot write ", path_);
  std::fflush(file_);
}

}  // namespace kerf
