// kerf-view: `kerf view SCENE.yaml` (the `kerf` command hands its arguments
// here, so that a run, a check or a study never loads VTK's rendering).
//   kerf view SCENE.yaml [--set KEY=VALUE]... [--out DIR] [--size WxH] [--blade-depth M] [--script FILE]
#include <cstdio>
#include <cstdlib>
#include <iostream>
#include <string>
#include <vector>

#include "core/check.h"
#include "core/denormals.h"
#include "core/thread_policy.h"
#include "problem/scene_reader.h"
#include "viewer/view_script.h"
#include "viewer/view_window.h"

namespace kerf {
namespace {

constexpr const char* usage =
    "usage: kerf view SCENE.yaml [--set KEY=VALUE]... [--out DIR] [--size WxH] [--blade-depth M] [--script FILE]\n"
    "  the scene stepped in a window, its body coloured by von Mises stress; the left mouse button drags the\n"
    "  blade of the scene's first live cut (cuts[i].live), Ctrl+left turns the camera. --script plays mouse\n"
    "  events and screenshots from a file instead (viewer/view_script.h) and closes.\n";

struct ViewArguments {
  std::string scene, out, script;
  std::vector<std::string> overrides;
  ViewOptions view;
};

ViewArguments parse(const std::vector<std::string>& args) {
  ViewArguments a;
  for (std::size_t i = 0; i < args.size(); ++i) {
    const std::string& s = args[i];
    auto value = [&]() -> const std::string& {
      KERF_CHECK(i + 1 < args.size(), s, " needs a value\n", usage);
      return args[++i];
    };
    if (s == "--set") a.overrides.push_back(value());
    else if (s == "--out") a.out = value();
    else if (s == "--script") a.script = value();
    else if (s == "--blade-depth") a.view.blade_depth = std::stod(value());
    else if (s == "--size")
      KERF_CHECK(std::sscanf(value().c_str(), "%dx%d", &a.view.width, &a.view.height) == 2 && a.view.width > 0 &&
                     a.view.height > 0, "--size: expected WIDTHxHEIGHT in pixels, as 900x700\n", usage);
    else if (s.rfind("--set=", 0) == 0) a.overrides.push_back(s.substr(6));  // as `kerf run` takes it
    else if (s.rfind("--", 0) == 0) KERF_CHECK(false, "unknown option '", s, "'\n", usage);
    else if (a.scene.empty()) a.scene = s;
    else KERF_CHECK(false, "unexpected argument '", s, "'\n", usage);
  }
  KERF_CHECK(!a.scene.empty(), "kerf view needs a scene file\n", usage);
  return a;
}

int view(const ViewArguments& a) {
  Scene scene = read_scene(a.scene, a.overrides);
  KERF_CHECK(scene.dimension == 3, scene.locate("domain").describe(), ": kerf view draws 3D bodies; expected a 3D domain");
  KERF_CHECK(scene.solve.analysis == Analysis::dynamic, scene.locate("solve.analysis").describe(),
             ": kerf view steps a body in time; expected dynamic");
  auto set = [](const char* name) { return std::getenv(name) && *std::getenv(name); };
  KERF_CHECK(set("DISPLAY") || set("WAYLAND_DISPLAY"), "kerf view opens a window and no display is "
             "set (DISPLAY); expected a desktop session, ssh -X, or xvfb-run kerf view ...");
  ViewOptions options = a.view;
  for (std::size_t c = 0; c < scene.cuts.size() && !options.blade_cut; ++c)
    if (scene.cuts[c].live) options.blade_cut = static_cast<Index>(c);
  RunOptions run;
  run.out_dir = a.out;
  run.quiet = true;
  Session session(scene, run);
  {
    ViewWindow window(session, options);
    if (a.script.empty())
      window.interact();
    else
      play_view_script(a.script, window);
  }
  if (session.failed()) {
    std::cerr << "kerf: error: the run failed in the window; its summary.json says why\n";
    return 1;
  }
  std::cerr << "kerf: results in " << session.finish().directory << "\n";
  return 0;
}

}  // namespace
}  // namespace kerf

int main(int argc, char** argv) {
  kerf::apply_thread_policy(argv);
  kerf::flush_denormals_to_zero();
  try {
    return kerf::view(kerf::parse(std::vector<std::string>(argv + 1, argv + argc)));
  } catch (const std::exception& e) {
    std::cerr << "kerf: error: " << e.what() << "\n";
    return 1;
  }
}
