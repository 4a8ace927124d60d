// libFuzzer target: the scene reader, end to end up to the run: YAML text
// and --set strings (the input's lines after a line "#--set" are overrides),
// then validation, the cuts' geometry and the resource estimate. Every bad
// input must end in kerf::Error (the message naming the key); any other
// exception, a crash or a sanitizer report is a finding.
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include "app/resource_estimate.h"
#include "app/run_scene.h"
#include "core/check.h"
#include "problem/scene_reader.h"

namespace {

/// The scene text, and one override per line after "#--set".
std::pair<std::string, std::vector<std::string>> split(const std::string& input) {
  const std::string marker = "\n#--set\n";
  const std::size_t at = input.find(marker);
  if (at == std::string::npos) return {input, {}};
  std::vector<std::string> overrides;
  std::size_t start = at + marker.size();
  while (start < input.size()) {
    std::size_t end = input.find('\n', start);
    if (end == std::string::npos) end = input.size();
    overrides.push_back(input.substr(start, end - start));
    start = end + 1;
  }
  return {input.substr(0, at), overrides};
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const auto [yaml, overrides] = split(std::string(reinterpret_cast<const char*>(data), size));
  try {
    // Relative mesh paths resolve in the seed corpus's own folder.
    const kerf::Scene scene = kerf::parse_scene(yaml, "fuzz.yaml", KERF_FUZZ_SCENE_DIR, overrides);
    kerf::refuse_unrunnable(scene);
    const kerf::ResourceEstimate estimate = kerf::estimate_resources(scene);
    (void)kerf::describe(estimate);
  } catch (const kerf::Error&) {
    // A refusal with a message: what every bad input must get.
  } catch (const std::exception& e) {
    std::fprintf(stderr, "not a kerf::Error: %s\n", e.what());
    std::abort();
  }
  return 0;
}
