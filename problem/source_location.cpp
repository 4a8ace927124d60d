#include "problem/source_location.h"

#include <sstream>

namespace kerf {

std::string SourceLocation::describe() const {
  std::ostringstream out;
  if (command_line)
    out << file << ": key '" << key << "' (set on the command line)";
  else if (line > 0)
    out << file << ":" << line << ":" << column << ": key '" << key << "'";
  else if (!file.empty())
    out << file << ": key '" << key << "'";
  else
    out << "key '" << key << "'";
  return out.str();
}

}  // namespace kerf
