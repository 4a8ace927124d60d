#pragma once
// Where a scene value came from, for error messages: file, line, column and
// dotted key ("scene.yaml:12:5: key 'material.poisson'").
#include <map>
#include <string>

namespace kerf {

/// Where a value came from, for error messages: "scene.yaml:12:5 (material.poisson)".
struct SourceLocation {
  std::string file;
  int line = 0;    // 1-based; 0 = unknown (built in code); a missing key points at its parent
  int column = 0;  // 1-based
  std::string key; // dotted path, e.g. "boundary.1.traction"
  bool command_line = false;  // the value came from --set
  std::string text;           // the value as written ("'0.5'", "nothing (the key is missing)"); "" in code
  std::string describe() const;
};

/// Every key a scene file's reader looked at, by dotted path: the validation
/// names them in its messages. Empty for a scene built in code.
using KeyLocations = std::map<std::string, SourceLocation>;

}  // namespace kerf
