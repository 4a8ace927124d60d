#include "viewer/view_script.h"

#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "core/check.h"

namespace kerf {
namespace {

/// (x, y) pixels from fractions of the window.
std::array<int, 2> pixel(const ViewWindow& window, double x, double y) {
  return {static_cast<int>(std::lround(x * (window.width() - 1))),
          static_cast<int>(std::lround(y * (window.height() - 1)))};
}

void play_line(const std::string& command, std::istringstream& words, const std::filesystem::path& folder,
               ViewWindow& window, const std::string& where) {
  if (command == "steps") {
    int n = 0;
    KERF_CHECK(words >> n && n > 0, where, ": 'steps' needs a positive step count");
    window.step(n);
    return;
  }
  if (command == "screenshot") {
    std::string file;
    KERF_CHECK(words >> file, where, ": 'screenshot' needs a file name");
    window.screenshot((folder / file).string());
    return;
  }
  double x = 0, y = 0;
  KERF_CHECK(words >> x >> y && x >= 0 && x <= 1 && y >= 0 && y <= 1, where, ": '", command,
             "' needs X Y, fractions of the window from its lower left corner (0 to 1)");
  const auto [px, py] = pixel(window, x, y);
  if (command == "press")
    window.press(px, py);
  else if (command == "move")
    window.move(px, py);
  else if (command == "release")
    window.release(px, py);
  else
    throw Error(where + ": unknown command '" + command + "'; expected steps, press, move, release or screenshot");
}

}  // namespace

void play_view_script(const std::string& path, ViewWindow& window) {
  std::ifstream in(path);
  KERF_CHECK(in, path, ": cannot read the view script");
  const std::filesystem::path folder = std::filesystem::path(path).parent_path();
  std::string line;
  for (int number = 1; std::getline(in, line); ++number) {
    std::istringstream words(line.substr(0, line.find('#')));
    std::string command;
    if (!(words >> command)) continue;
    play_line(command, words, folder, window, path + ":" + std::to_string(number));
  }
}

}  // namespace kerf
