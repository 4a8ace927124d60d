// The `kerf` Python module (its compiled part, kerf._kerf): scenes from a file
// or a dict, --set overrides, runs and studies, the summary as a dict, the
// final body's points and point fields as numpy arrays that view kerf's own
// memory (no copy), kerf's errors as kerf.Error and a signal as KeyboardInterrupt.
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <filesystem>
#include <fstream>
#include <memory>
#include <string>
#include <vector>

#include "app/run_scene.h"
#include "core/check.h"
#include "core/interrupt.h"
#include "kerf/version.h"
#include "problem/scene_json.h"
#include "problem/scene_reader.h"
#include "studies/study.h"

namespace py = pybind11;

namespace kerf {
namespace {

using json = nlohmann::ordered_json;

/// kerf's JSON as Python objects (dicts, lists, floats), through Python's own parser.
py::object to_python(const json& value) {
  return py::module_::import("json").attr("loads")(
      value.dump(-1, ' ', false, json::error_handler_t::replace));
}

/// A kerf.Scene, a dict holding a scene (JSON is YAML: kerf's reader reads
/// it, and its errors name the key; mesh paths start at the working
/// directory), or a scene file's path.
Scene load_scene(const py::object& source, const std::vector<std::string>& overrides) {
  if (py::isinstance<Scene>(source)) {
    KERF_CHECK(overrides.empty(), "overrides apply when a scene is read: kerf.load_scene(source, overrides)");
    return source.cast<Scene>();
  }
  if (py::isinstance<py::dict>(source)) {
    const std::string text = py::module_::import("json").attr("dumps")(source).cast<std::string>();
    return parse_scene(text, "<dict>", std::filesystem::current_path().string(), overrides);
  }
  const std::string path = py::str(py::module_::import("os").attr("fspath")(source));
  return read_scene(path, overrides);
}

/// A numpy array over `values` (rows of `columns` doubles, `stride` bytes
/// apart), read-only, keeping `owner` alive as long as the array lives.
py::array view(const double* values, std::size_t rows, std::size_t columns, std::size_t stride,
               std::shared_ptr<const BodySnapshot> owner) {
  auto* kept = new std::shared_ptr<const BodySnapshot>(std::move(owner));
  py::capsule base(kept, [](void* p) { delete static_cast<std::shared_ptr<const BodySnapshot>*>(p); });
  py::array_t<double> array({rows, columns}, {stride, sizeof(double)}, values, base);
  array.attr("setflags")(py::arg("write") = false);
  return array;
}

struct Result {
  std::string directory;
  py::object summary;
  std::shared_ptr<const BodySnapshot> body;

  py::array points() const {
    if (body->points.empty()) return py::array_t<double>(std::vector<py::ssize_t>{0, 3});
    return view(body->points.data()->data(), body->points.size(), 3, sizeof(Vec3), body);
  }
  py::dict point_fields() const { return fields(body->point_fields); }
  py::dict cell_fields() const { return fields(body->cell_fields); }

 private:
  py::dict fields(const std::vector<OutputField>& list) const {
    py::dict views;
    for (const OutputField& f : list)
      views[py::str(f.name)] = view(f.values.data(), f.values.size() / f.components, f.components,
                                    f.components * sizeof(double), body);
    return views;
  }
};

Result run(const py::object& source, const std::vector<std::string>& overrides, const std::string& out, bool quiet,
           bool force) {
  const Scene scene = load_scene(source, overrides);
  refuse_unrunnable(scene);
  RunOptions options;
  options.out_dir = out;
  options.quiet = quiet;
  options.force = force;
  options.keep_final_body = true;
  RunOutcome outcome;
  {
    py::gil_scoped_release free_python;  // a long run; its own threads
    outcome = run_scene(scene, options);
  }
  return Result{outcome.directory, to_python(outcome.summary), outcome.final_body};
}

py::object study(const std::string& name, bool quick, const std::string& out, bool quiet) {
  StudyOptions options;
  options.quick = quick;
  options.out_dir = out.empty() ? "results/" + name : out;
  options.quiet = quiet;
  {
    py::gil_scoped_release free_python;
    const InterruptScope interrupt;  // one for the study: a signal between its runs is kept
    run_study(name, options);
  }
  std::ifstream file(options.out_dir + "/" + name + ".json");
  if (!file) return py::none();
  return to_python(json::parse(file));
}

}  // namespace
}  // namespace kerf

PYBIND11_MODULE(_kerf, m) {
  using namespace kerf;
  m.doc() = "kerf: soft-tissue cutting, tetrahedral FEM against enriched meshless methods";
  m.attr("__version__") = version;
  static py::exception<Error> error(m, "Error", PyExc_RuntimeError);
  // Translators registered later are tried first: a signal before any other error.
  py::register_exception_translator([](std::exception_ptr p) {
    try {
      if (p) std::rethrow_exception(p);
    } catch (const Interrupted& e) {
      PyErr_SetString(PyExc_KeyboardInterrupt, e.what());
    } catch (const Error& e) {
      error(e.what());
    }
  });

  py::class_<Scene>(m, "Scene", "A scene read and validated: kerf.load_scene")
      .def_property_readonly("name", [](const Scene& s) { return s.name; })
      .def("to_dict", [](const Scene& s) { return to_python(scene_to_json(s)); },
           "The resolved scene (every key, defaults filled in), as summary.json's 'scene'");
  m.def(
      "load_scene", [](const py::object& source, const std::vector<std::string>& overrides) {
        Scene scene = load_scene(source, overrides);
        refuse_unrunnable(scene);
        return scene;
      },
      py::arg("source"), py::arg("overrides") = std::vector<std::string>{},
      "A scene from a file's path or a dict, with overrides 'KEY=VALUE' as --set takes them; raises kerf.Error "
      "naming the file, line and key of what is wrong");

  py::class_<Result>(m, "Result", "What a run leaves: the summary, its folder, and the body at its end")
      .def_readonly("directory", &Result::directory)
      .def_readonly("summary", &Result::summary, "summary.json as a dict")
      .def_property_readonly("probes", [](const Result& r) -> py::object { return r.summary["probes"]; })
      .def_property_readonly("points", &Result::points,
                             "the reference positions of the body's output points (n x 3, m), a read-only view")
      .def_property_readonly("point_fields", &Result::point_fields,
                             "every point field ParaView gets (displacement; meshless: stress, von_mises, ...), "
                             "read-only views")
      .def_property_readonly("cell_fields", &Result::cell_fields,
                             "every cell field ParaView gets (FEM: stress, von_mises per cell), read-only views")
      .def_property_readonly("displacement",
                             [](const Result& r) -> py::object {  // an object, not an accessor of a dict gone
                               const py::dict fields = r.point_fields();
                               return fields["displacement"];
                             },
                             "the displacement of each output point at the end (n x 3, m)");
  m.def("run", &run, py::arg("scene"), py::arg("overrides") = std::vector<std::string>{}, py::arg("out") = "",
        py::arg("quiet") = true, py::arg("force") = false,
        "Runs a scene (a kerf.Scene, a dict, or a file's path) as `kerf run` does, writing its files in out "
        "(default: the scene's output.dir); returns a kerf.Result. Ctrl-C stops it as KeyboardInterrupt, the "
        "files written so far readable");
  m.def("studies", [] {
    std::vector<std::pair<std::string, std::string>> list;
    for (const StudyEntry& s : all_studies()) list.emplace_back(s.name, s.summary);
    return list;
  }, "The studies: (name, what it shows)");
  m.def("study", &study, py::arg("name"), py::arg("quick") = false, py::arg("out") = "", py::arg("quiet") = true,
        "Runs a study as `kerf study NAME` does (into out, default results/NAME); returns its NAME.json as a dict");
}
