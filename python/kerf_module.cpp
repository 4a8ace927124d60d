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
#include "app/session.h"
#include "app/summary_json.h"
#include "core/check.h"
#include "core/interrupt.h"
#include "kerf/version.h"
#include "problem/scene_json.h"
#include "problem/scene_reader.h"
#include "studies/study.h"

namespace py = pybind11;

namespace kerf {
namespace {

/// A point or vector from Python: 2 (2D) or 3 numbers (SI units).
Vec3 point_of(const std::vector<double>& v, const char* what) {
  KERF_CHECK(v.size() == 2 || v.size() == 3, what, " has ", v.size(), " coordinates; expected 2 (2D) or 3");
  return Vec3(v[0], v[1], v.size() == 3 ? v[2] : 0.0);
}

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
  RunRecord record;

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
  return Result{outcome.directory, to_python(outcome.summary), outcome.final_body,
                record_of_summary(outcome.summary, outcome.directory)};
}

/// kerf.Session: a run stepped from Python (app/session.h). Its state arrays
/// view the session's own memory (no copy): read again after a step, or
/// keep a view, which the next steps update in place while the body keeps
/// its nodes (a cut that remeshes or splits cells changes them).
class PythonSession {
 public:
  PythonSession(const py::object& source, const std::vector<std::string>& overrides, const std::string& out,
                bool quiet, bool force) {
    const Scene scene = load_scene(source, overrides);
    RunOptions options;
    options.out_dir = out;
    options.quiet = quiet;
    options.force = force;
    options.keep_final_body = true;
    py::gil_scoped_release free_python;
    const InterruptScope interrupt;  // for this call alone: between calls Python keeps its own Ctrl-C
    session_ = std::make_unique<Session>(scene, options);
  }
  void step(int count) {
    KERF_CHECK(count >= 1, "Session.step(count): count is ", count, "; expected 1 or more");
    py::gil_scoped_release free_python;
    const InterruptScope interrupt;
    for (int i = 0; i < count; ++i) session_->step();
  }
  void run_to_end() {
    py::gil_scoped_release free_python;
    const InterruptScope interrupt;
    while (!session_->done()) session_->step();
  }
  Result finish() {
    finished_ = true;  // also when it fails: its summary then says why
    RunOutcome outcome;
    {
      py::gil_scoped_release free_python;
      const InterruptScope interrupt;
      outcome = session_->finish();
    }
    return Result{outcome.directory, to_python(outcome.summary), outcome.final_body,
                  record_of_summary(outcome.summary, outcome.directory)};
  }
  /// Leaving a `with` block finishes the session (results readable even after an exception in the block).
  void close() {
    if (!finished_ && !session_->failed()) finish();  // a failed one's summary says why already
  }
  Session& session() { return *session_; }
  /// A property's getter: the session's vector `state` as nodes x dofs_per_node, read-only, keeping the
  /// session alive as long as the array lives.
  static auto state_property(const Vector& (Session::*state)()) {
    return [state](const py::object& self) {
      Session& session = self.cast<PythonSession&>().session();
      const Vector& values = (session.*state)();
      const auto per_node = static_cast<std::size_t>(session.dofs_per_node());
      py::array_t<double> array({static_cast<std::size_t>(values.size()) / per_node, per_node},
                                {per_node * sizeof(double), sizeof(double)}, values.data(), self);
      array.attr("setflags")(py::arg("write") = false);
      return py::array(array);
    };
  }

 private:
  std::unique_ptr<Session> session_;
  bool finished_ = false;
};

/// Session.move_sphere or push_sphere: `call` with the sphere and a vector from Python.
template <void (Session::*call)(Index, const Vec3&)>
auto sphere_hand(const char* what) {
  return [what](PythonSession& s, Index sphere, const std::vector<double>& v) {
    (s.session().*call)(sphere, point_of(v, what));
  };
}

/// A run's record as Python values: what read_outcome gives C++.
py::dict record_counts(const RunRecord& r) {
  const RunCounts& c = r.report.counts;
  py::dict d;
  d["nodes"] = c.nodes, d["dofs"] = c.dofs, d["elements"] = c.elements, d["neighbors_mean"] = c.neighbors_mean;
  return d;
}

py::dict record_probes(const RunRecord& r) {
  py::dict d;
  for (const auto& [name, reading] : r.probes) d[py::str(name)] = reading.values;
  return d;
}

py::dict record_timing(const RunRecord& r) {
  auto stats = [](const DurationStats& s) {
    py::dict d;
    d["median"] = s.median_ms, d["mean"] = s.mean_ms, d["max"] = s.max_ms, d["count"] = s.count;
    return d;
  };
  py::dict phases;
  for (std::size_t p = 0; p < phase_names.size(); ++p)
    phases[py::str(std::string(phase_names[p]) + "_s")] = r.report.phases.seconds(static_cast<Phase>(p));
  py::dict d;  // the summary's "timing"
  d["setup_s"] = r.report.setup_seconds, d["solve_s"] = r.report.solve_seconds, d["phases"] = phases;
  d["step_ms"] = stats(r.step_ms), d["cut_update_ms"] = stats(r.cut_update_ms);
  return d;
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
      .def_readonly("record", &Result::record, "the summary typed, as kerf.read_outcome reads it from the folder")
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
  py::class_<PythonSession>(m, "Session",
                            "A run stepped from Python: kerf.Session(scene), then step() and read the state "
                            "between steps; finish() (or leaving a `with` block) writes the summary")
      .def(py::init<const py::object&, const std::vector<std::string>&, const std::string&, bool, bool>(),
           py::arg("source"), py::arg("overrides") = std::vector<std::string>{}, py::arg("out") = "",
           py::arg("quiet") = true, py::arg("force") = false,
           "Opens a run of a scene (a kerf.Scene, a dict or a file's path, with overrides 'KEY=VALUE'): "
           "builds the body and writes step 0's output")
      .def("step", &PythonSession::step, py::arg("count") = 1,
           "Takes `count` steps of the scene's integrator (each with its cut growth and output)")
      .def("run", &PythonSession::run_to_end, "Takes every step left")
      .def(
          "extend_cut",
          [](PythonSession& s, Index cut, const std::vector<std::vector<double>>& vertices) {
            std::vector<Vec3> points;
            for (const std::vector<double>& v : vertices) points.push_back(point_of(v, "Session.extend_cut: a vertex"));
            s.session().extend_cut(cut, points);
          },
          py::arg("cut"), py::arg("vertices"),
          "Feeds a live cut (scene: live: true, or strip: []) its next vertices: a polyline's next vertex, a "
          "strip's next pair (the blade's two ends, m); their pieces appear by the end of the next step")
      .def("move_sphere", sphere_hand<&Session::move_sphere>("Session.move_sphere: the displacement"),
          py::arg("sphere"), py::arg("displacement"),
          "Moves a displacement-driven contact sphere's centre to `displacement` (m) from its scene position, "
          "from the next step on (within the path its scene gives it)")
      .def("push_sphere", sphere_hand<&Session::push_sphere>("Session.push_sphere: the force"), py::arg("sphere"),
           py::arg("force"),
          "Pushes a force-driven contact sphere with `force` (N) from the next step on (along its scene force, "
          "no larger)")
      .def("scale_loads", [](PythonSession& s, double factor) { s.session().scale_loads(factor); },
           py::arg("factor"), "The scene's body force and boundary loads times `factor` from the next step on")
      .def(
          "contact_force",
          [](PythonSession& s, Index sphere) {
            const Vec3 f = s.session().contact_force(sphere);
            return std::vector<double>{f[0], f[1], f[2]};
          },
          py::arg("sphere"), "The force (N) contact sphere `sphere` exerts on the body now")
      .def("finish", &PythonSession::finish,
           "Ends the run where it stands: summary.json with status 'ok'; returns the kerf.Result")
      .def_property_readonly("done", [](PythonSession& s) { return s.session().done(); })
      .def_property_readonly("steps_taken", [](PythonSession& s) { return s.session().steps_taken(); })
      .def_property_readonly("step_count", [](PythonSession& s) { return s.session().step_count(); })
      .def_property_readonly("time", [](PythonSession& s) { return s.session().time(); },
                             "the state's time (s; static: the load factor)")
      .def_property_readonly("dt", [](PythonSession& s) { return s.session().time_step(); })
      .def_property_readonly("displacement", PythonSession::state_property(&Session::displacement),
                             "each node's displacement (nodes x dofs per node, m): a read-only view of the "
                             "session's memory")
      .def_property_readonly("velocity", PythonSession::state_property(&Session::velocity),
                             "each node's velocity (nodes x dofs per node, m/s): a read-only view of the "
                             "session's memory")
      .def_property_readonly("probes", [](PythonSession& s) { return to_python(s.session().probes()); },
                             "the scene's probes now, as summary.json's 'probes'")
      .def("__enter__", [](py::object self) { return self; })
      .def("__exit__", [](PythonSession& s, const py::object&, const py::object&, const py::object&) {
        s.close();
        return false;
      });
  py::class_<RunRecord>(m, "Record",
                        "A run's summary.json read back typed (kerf.read_outcome), as the studies read it")
      .def_readonly("directory", &RunRecord::directory)
      .def_property_readonly("status",
                             [](const RunRecord& r) {
                               const char* words[] = {"running", "ok", "error", "interrupted"};
                               return std::string(words[static_cast<int>(r.status)]);
                             })
      .def_property_readonly("ok", &RunRecord::ok)
      .def_readonly("error", &RunRecord::error, "the message of a run that failed")
      .def_readonly("diverged", &RunRecord::diverged, "the solution blew up (NaN)")
      .def_property_readonly("counts", &record_counts, "nodes, dofs, elements, neighbors_mean")
      .def_property_readonly("probes", &record_probes,
                             "each probe's final values: one per axis, indentation one, energy kinetic, strain, "
                             "external_work, total")
      .def_property_readonly("timing", &record_timing, "as summary.json's timing: setup_s, solve_s, phases, step_ms, cut_update_ms")
      .def_property_readonly("extras", [](const RunRecord& r) { return r.report.extras; },
                             "the method's own figures (MLS conditioning, ...)");
  m.def("read_outcome", &read_outcome, py::arg("directory"),
        "A run's folder (kerf run --out, a study's runs/LABEL) read back as a kerf.Record; raises kerf.Error "
        "naming summary.json when there is none or it is not a run's");
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
