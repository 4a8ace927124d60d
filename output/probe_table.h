#pragma once
// probes.csv: a header, then one row per output step, each row written whole
// and flushed, so an interrupted run leaves every finished row readable.
#include <cstdio>
#include <string>
#include <vector>

namespace kerf {

class ProbeTable {
 public:
  ProbeTable(const std::string& path, const std::vector<std::string>& columns);
  ~ProbeTable();
  ProbeTable(const ProbeTable&) = delete;
  ProbeTable& operator=(const ProbeTable&) = delete;
  void append(const std::vector<double>& row);

 private:
  std::FILE* file_ = nullptr;
  std::string path_;
  std::size_t columns_;
};

}  // namespace kerf
