// hexdyn._hexdyn: the compiled part of the Python module `hexdyn` (bindings/python/hexdyn/).
// Thin: it converts at the edge and adds no logic. Every call goes through the C++ entry
// points of <hexdyn/hexdyn.hpp> (the dynamics functions through dynamics.cpp);
// the arrays are those of result_layout (io/result_layout.hpp), the list the HDF5 writer
// writes, handed to numpy without a copy. The GIL is released
// while a scene is read and computed. Errors cross as the exception family of
// core/errors.hpp (hexdyn.ConfigError ... , registered below), with the CLI's one-line
// message.
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>
#include <yaml-cpp/yaml.h>

#include <atomic>
#include <chrono>
#include <cmath>
#include <condition_variable>
#include <cstdio>
#include <exception>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <thread>
#include <utility>
#include <variant>
#include <vector>

#include "dynamics.hpp"
#include "edge.hpp"
#include "hexdyn/hexdyn.hpp"
#include "hexdyn/io/result_layout.hpp"
#include "hexdyn/pipeline/pipeline.hpp"
#include "hexdyn/process/interrupt.hpp"
#include "hexdyn/sweep/sweep.hpp"

namespace py = pybind11;

namespace {

using hexdyn_python::guard_yaml;
using hexdyn_python::overrides_of;
using hexdyn_python::to_numpy;

/// One computed scene: the C++ result (for write) and the files it read, by the identity
/// and absolute path they had when read (config/inputs.hpp), which its outputs must not be.
struct RunHandle {
  hexdyn::RunResult result;
  std::vector<hexdyn::InputFile> inputs;
};

/// How often a computing hexdyn.run looks for Ctrl-C (Python's signal handlers run in the
/// main thread, between bytecodes, so the computation runs in a thread of its own).
constexpr auto kSignalPoll = std::chrono::milliseconds(20);

/// Runs `compute` in a thread of its own while this thread (the caller's, GIL released) looks
/// for Python's signals every kSignalPoll: on KeyboardInterrupt (or any exception a signal
/// handler raises), the computation is cancelled (core/cancel.hpp: it stops at its next
/// sample), joined, and the Python exception raised. Exceptions of `compute` are rethrown.
template <class F>
void run_interruptible(F&& compute) {
  std::atomic<bool> cancel{false};
  std::exception_ptr error;
  std::mutex m;
  std::condition_variable cv;
  bool done = false;
  std::thread worker([&] {
    try {
      const hexdyn::CancelScope scope(&cancel);
      compute();
    } catch (...) {
      error = std::current_exception();
    }
    const std::lock_guard<std::mutex> lock(m);
    done = true;
    cv.notify_all();
  });
  {
    py::gil_scoped_release no_gil;
    std::unique_lock<std::mutex> lock(m);
    while (!cv.wait_for(lock, kSignalPoll, [&] { return done; })) {
      lock.unlock();
      bool raised = false;
      {
        py::gil_scoped_acquire gil;
        raised = PyErr_CheckSignals() != 0;
        if (raised) {
          cancel = true;
          // Keep the Python exception across the join (the GIL is released meanwhile).
          py::error_already_set pending;
          {
            py::gil_scoped_release again;
            worker.join();
          }
          throw pending;
        }
      }
      lock.lock();
    }
  }
  worker.join();
  if (error) std::rethrow_exception(error);
}

/// The Ipopt back end (allocation.solver: ipopt) runs Ipopt with Debian's sequential
/// MUMPS, whose stand-in MPI library keeps global state and is not documented as
/// thread-safe: scenes with that back end run one at a time in this process. The default
/// back end (active set) keeps no state outside its call and runs in parallel.
std::mutex ipopt_mutex;

/// A dataset as Python sees it: numbers as numpy arrays of the file's dtype (float64,
/// int8, int32; a 0-d array for a scalar), a list of strings as a numpy array of str
/// objects, a scalar text as str.
py::object to_python(hexdyn::LayoutDataset&& d) {
  if (auto* v = std::get_if<std::vector<double>>(&d.values)) return to_numpy(std::move(*v), d.dims);
  if (auto* v8 = std::get_if<std::vector<std::int8_t>>(&d.values))
    return to_numpy(std::move(*v8), d.dims);
  if (auto* v32 = std::get_if<std::vector<std::int32_t>>(&d.values))
    return to_numpy(std::move(*v32), d.dims);
  if (auto* texts = std::get_if<std::vector<std::string>>(&d.values)) {
    py::object np_asarray = py::module_::import("numpy").attr("asarray");
    py::list items;
    for (const std::string& t : *texts) items.append(py::str(t));
    return np_asarray(items, py::arg("dtype") = py::dtype("O"));
  }
  return py::str(std::get<std::string>(d.values));
}

/// The scene's warnings (Scene::warnings) as Python UserWarnings, attributed to the caller of
/// hexdyn.run or hexdyn.validate.
void warn(const std::vector<std::string>& warnings) {
  if (warnings.empty()) return;
  const py::object warn = py::module_::import("warnings").attr("warn");
  const py::object category = py::module_::import("builtins").attr("UserWarning");
  for (const std::string& w : warnings) warn("hexdyn: " + w, category, 2);
}

/// A file's layout as Python sees it: ({path: array}, {attribute: value}, {path: units}), the
/// units of the datasets the writer gives a `units` attribute (their declaration's, when not
/// ""); /meta attributes by name, any other object's as "OBJECT/NAME" ("/terrain/type").
py::tuple layout_to_python(hexdyn::ResultLayout&& layout) {
  py::dict datasets, attributes, units;
  for (hexdyn::LayoutDataset& d : layout.datasets) {
    const char* path = d.spec->path;
    if (d.spec->units[0] != '\0') units[py::str(path)] = py::str(d.spec->units);
    datasets[py::str(path)] = to_python(std::move(d));
  }
  for (const hexdyn::LayoutAttribute& a : layout.attributes) {
    const std::string object = a.spec->object;
    const std::string key = object == hexdyn::schema::kMetaGroup ? std::string(a.spec->name)
                                                                 : object + "/" + a.spec->name;
    std::visit([&](const auto& v) { attributes[py::str(key)] = py::cast(v); }, a.value);
  }
  return py::make_tuple(datasets, attributes, units);
}

/// run(scene, overrides, allow_large) → (handle, {path: array}, {attribute: value},
/// {path: units}): the units of the datasets the writer gives a `units` attribute (their
/// declaration's, when not "").
py::tuple run_file(const std::string& scene_path, const std::vector<std::string>& override_texts,
                   bool allow_large) {
  auto handle = std::make_shared<RunHandle>();
  hexdyn::ResultLayout layout;
  const std::vector<hexdyn::Override> overrides = overrides_of(override_texts);
  std::vector<std::string> warnings;
  run_interruptible([&] {
    guard_yaml(scene_path, [&] {
      const hexdyn::Scene scene = hexdyn::load_scene(scene_path, overrides, &handle->inputs);
      warnings = scene.warnings;
      const hexdyn::PreparedScene prep = hexdyn::prepare_scene(scene);
      hexdyn::check_run_size(prep.grid.size(), prep.model.legs(), prep.model.joints(), allow_large);
      std::unique_lock<std::mutex> lock(ipopt_mutex, std::defer_lock);
      if (scene.allocation.solver == hexdyn::AllocationSolver::kIpopt) lock.lock();
      handle->result = hexdyn::run_prepared_scene(scene, prep);
      return 0;
    });
    layout = hexdyn::result_layout(handle->result);
  });
  warn(warnings);
  py::tuple file = layout_to_python(std::move(layout));
  return py::make_tuple(handle, file[0], file[1], file[2]);
}

/// robustness(scene, overrides, threads) → ({path: array}, {attribute: value}, {path: units}):
/// the scene's robustness study (robustness/robustness.hpp) on `threads` threads, as the file
/// `hexdyn robustness` writes holds it.
py::tuple robustness_file(const std::string& scene_path,
                          const std::vector<std::string>& override_texts, int threads) {
  hexdyn::ResultLayout layout;
  const std::vector<hexdyn::Override> overrides = overrides_of(override_texts);
  std::vector<std::string> warnings;
  run_interruptible([&] {
    guard_yaml(scene_path, [&] {
      std::vector<hexdyn::InputFile> inputs;
      const hexdyn::Scene scene = hexdyn::load_scene(scene_path, overrides, &inputs);
      warnings = scene.warnings;
      std::unique_lock<std::mutex> lock(ipopt_mutex, std::defer_lock);
      if (scene.allocation.solver == hexdyn::AllocationSolver::kIpopt) lock.lock();
      const hexdyn::RobustnessResult r = hexdyn::run_robustness(scene, std::max(1, threads));
      layout = hexdyn::robustness_layout(scene, inputs, r);
      return 0;
    });
  });
  warn(warnings);
  return layout_to_python(std::move(layout));
}

/// write(handle, path): the CLI's checks on the output path (a new path or a regular file
/// that is none of the files the run read, by the identities and absolute paths recorded
/// when they were read: no input is read again, so it works after they are gone), then the
/// file, atomically. Holds the GIL: serial HDF5 is not thread-safe. While it writes, the
/// signals whose default action would end Python (SIGHUP, SIGQUIT, SIGTERM, SIGUSR1, SIGUSR2,
/// SIGALRM; those Python or the user handle are left alone) remove the temporary file and
/// end the process with one line and 128 + signal, as `hexdyn run` does.
void write_file(const RunHandle& handle, const std::string& path) {
  const hexdyn::FatalSignalScope signals(
      "hexdyn: write interrupted by {signal}: nothing written to " + path +
      " (an existing file there is kept, no temporary file left)");
  hexdyn::write_result_file(path, handle.result, handle.inputs);
}

/// validate(path, overrides) → dict: the report of `hexdyn validate` (sweep/validate.hpp).
py::dict validate_file(const std::string& path, const std::vector<std::string>& override_texts) {
  hexdyn::ValidationReport report;
  {
    py::gil_scoped_release no_gil;
    report =
        guard_yaml(path, [&] { return hexdyn::validate_file(path, overrides_of(override_texts)); });
  }
  py::dict out;
  out["kind"] = hexdyn::validated_kind_name(report.kind);
  out["name"] = report.name;
  if (report.kind == hexdyn::ValidatedKind::kSweep) {
    out["scenarios"] = report.scenarios;
    out["out_of_range"] = report.out_of_range;
    out["first_out_of_range"] = report.first_out_of_range;
  }
  out["messages"] = report.messages;
  out["warnings"] = report.scene ? report.scene->warnings : std::vector<std::string>{};
  warn(report.scene ? report.scene->warnings : std::vector<std::string>{});
  return out;
}

/// A numpy float64 array of shape (rows, cols) holding a copy of `m`.
py::array matrix_to_numpy(const Eigen::MatrixXd& m) {
  std::vector<double> values(static_cast<std::size_t>(m.size()));
  for (Eigen::Index i = 0; i < m.rows(); ++i)
    for (Eigen::Index j = 0; j < m.cols(); ++j)
      values[static_cast<std::size_t>(i * m.cols() + j)] = m(i, j);
  return to_numpy(std::move(values),
                  {static_cast<std::size_t>(m.rows()), static_cast<std::size_t>(m.cols())});
}

py::array vector_to_numpy(const Eigen::VectorXd& v) {
  return to_numpy(std::vector<double>(v.data(), v.data() + v.size()),
                  {static_cast<std::size_t>(v.size())});
}

const char* friction_model_word(hexdyn::FrictionModel m) {
  switch (m) {
    case hexdyn::FrictionModel::kPyramid4:
      return "pyramid4";
    case hexdyn::FrictionModel::kPyramid8:
      return "pyramid8";
    case hexdyn::FrictionModel::kCone:
      return "cone";
  }
  return "pyramid4";
}

/// The per-leg variable layout (allocation/problem.hpp AllocationLayout::Leg) as dicts.
py::list legs_to_python(const hexdyn::AllocationLayout& layout) {
  py::list legs;
  for (int l = 0; l < layout.n_legs; ++l) {
    const hexdyn::AllocationLayout::Leg& leg = layout.legs[l];
    py::dict d;
    d["offset"] = leg.offset;
    d["count"] = leg.count;
    d["friction_row"] = leg.friction_row;
    d["friction_faces"] = leg.friction_faces;
    d["face_reach"] = leg.face_reach;
    d["cone"] = leg.cone;
    d["known_normal_force_N"] = leg.known_normal_force_N;
    d["W_R_contact"] = matrix_to_numpy(leg.W_R_contact);
    legs.append(d);
  }
  return legs;
}

/// ValueError unless t_s lies in [grid.front(), grid.back()], the span the run samples (the
/// motion, and a final touchdown's transient when it outlasts it), naming both.
void check_in_span(double t_s, const std::vector<double>& grid) {
  if (!grid.empty() && t_s >= grid.front() && t_s <= grid.back()) return;
  char text[160];
  std::snprintf(text, sizeof text,
                "sample_problem: t = %g s is outside the motion's span [%.9g, %.9g] s", t_s,
                grid.empty() ? 0.0 : grid.front(), grid.empty() ? 0.0 : grid.back());
  throw py::value_error(text);
}

/// sample_problem(scene, overrides, t) → dict: the allocation problem of the instant t
/// (pipeline/pipeline.hpp sample_problem), its layout and the run's answers.
py::dict sample_problem_file(const std::string& scene_path,
                             const std::vector<std::string>& override_texts, double t_s) {
  hexdyn::Scene scene;
  hexdyn::SampleProblem p;
  const std::vector<hexdyn::Override> overrides = overrides_of(override_texts);
  run_interruptible([&] {
    guard_yaml(scene_path, [&] {
      scene = hexdyn::load_scene(scene_path, overrides);
      const hexdyn::PreparedScene prep = hexdyn::prepare_scene(scene);
      check_in_span(t_s, prep.grid);
      std::unique_lock<std::mutex> lock(ipopt_mutex, std::defer_lock);
      if (scene.allocation.solver == hexdyn::AllocationSolver::kIpopt) lock.lock();
      p = hexdyn::sample_problem(scene, prep, t_s);
      return 0;
    });
  });
  const hexdyn::QpProblem& qp = p.qp;
  py::dict out;
  out["time"] = t_s;
  out["H"] = matrix_to_numpy(qp.H);
  out["g"] = vector_to_numpy(qp.g);
  out["C"] = matrix_to_numpy(qp.C);
  out["lower"] = vector_to_numpy(qp.lower);
  out["upper"] = vector_to_numpy(qp.upper);
  out["ineq_names"] = qp.ineq_names;
  py::list cones;
  for (const hexdyn::SecondOrderCone& c : qp.cones) {
    py::dict d;
    d["tangent1"] = c.tangent1;
    d["tangent2"] = c.tangent2;
    d["normal"] = c.normal;
    d["mu"] = c.mu;
    d["name"] = c.name;
    cones.append(d);
  }
  out["cones"] = cones;
  out["legs"] = legs_to_python(p.layout);
  out["variables"] = p.layout.variables;
  out["constant_excess_Nm"] = p.layout.constant_excess_Nm;
  out["constant_violation"] = p.layout.constant_violation;
  std::vector<std::int8_t> phase;
  for (int l = 0; l < p.legs; ++l) phase.push_back(static_cast<std::int8_t>(p.phase[l]));
  out["phase"] = to_numpy(std::move(phase), {static_cast<std::size_t>(p.legs)});
  out["x"] = vector_to_numpy(p.x);
  out["status"] = static_cast<int>(p.status);
  out["required_friction"] = p.required_friction;
  out["required_friction_leg"] = p.required_friction_leg;
  out["friction_coefficient"] = scene.contact.friction_coefficient;
  out["friction"] = friction_model_word(scene.allocation.friction);
  return out;
}

/// A new exception class hexdyn.NAME with the given bases.
py::object new_exception(py::module_& m, const char* name, py::tuple bases, const char* doc) {
  const std::string qualified = std::string("hexdyn.") + name;
  py::dict attrs;
  attrs["__doc__"] = doc;
  PyObject* type = PyErr_NewException(qualified.c_str(), bases.ptr(), attrs.ptr());
  if (type == nullptr) throw py::error_already_set();
  py::object cls = py::reinterpret_steal<py::object>(type);
  m.attr(name) = cls;
  return cls;
}

}  // namespace

PYBIND11_MODULE(_hexdyn, m) {
  m.doc() =
      "hexdyn's compiled part; use the package `hexdyn` (run, validate, sample_problem, "
      "forward_dynamics, inverse_dynamics, mass_matrix, Result).";
  m.attr("version") = hexdyn::kVersion;
  m.attr("git_commit") = hexdyn::kGitCommit;

  // The family of core/errors.hpp. The objects live as long as the module (kept in static
  // handles, never released: the interpreter owns them through the module).
  static py::object error = new_exception(m, "Error", py::make_tuple(py::handle(PyExc_Exception)),
                                          "Base of hexdyn's errors (C++ hexdyn::Error).");
  static py::object config_error = new_exception(
      m, "ConfigError", py::make_tuple(error, py::handle(PyExc_ValueError)),
      "A scene or sweep file, or an override, is wrong: missing, mistyped or out-of-range key, "
      "unreadable file (CLI exit status 2).");
  static py::object io_error =
      new_exception(m, "IoError", py::make_tuple(error, py::handle(PyExc_OSError)),
                    "An output file cannot be written (CLI exit status 2).");
  static py::object reach_error =
      new_exception(m, "ReachError", py::make_tuple(error),
                    "A foot target outside a leg's workspace (exit status 3).");
  static py::object planning_error = new_exception(m, "PlanningError", py::make_tuple(error),
                                                   "The motion cannot be planned (exit status 3).");
  static py::object solver_error = new_exception(m, "SolverError", py::make_tuple(error),
                                                 "A solver gave no usable answer (exit status 3).");
  static py::object internal_error =
      new_exception(m, "InternalError", py::make_tuple(error, py::handle(PyExc_RuntimeError)),
                    "A defect of hexdyn (CLI: 'internal error', exit status 4); please report it.");

  py::register_exception_translator([](std::exception_ptr p) {
    auto raise = [](const py::object& type, const std::string& message) {
      PyErr_SetString(type.ptr(), hexdyn::one_line(message).c_str());
    };
    try {
      if (p) std::rethrow_exception(p);
    } catch (const py::error_already_set&) {
      throw;
    } catch (const py::builtin_exception&) {
      throw;
    } catch (const hexdyn::ConfigError& e) {
      raise(config_error, e.what());
    } catch (const hexdyn::IoError& e) {
      raise(io_error, e.what());
    } catch (const hexdyn::ReachError& e) {
      raise(reach_error, e.what());
    } catch (const hexdyn::PlanningError& e) {
      raise(planning_error, e.what());
    } catch (const hexdyn::SolverError& e) {
      raise(solver_error, e.what());
    } catch (const hexdyn::Error& e) {
      raise(error, e.what());
    } catch (const std::bad_alloc&) {
      PyErr_SetString(PyExc_MemoryError, "hexdyn: out of memory");
    } catch (const std::exception& e) {
      raise(internal_error, std::string("internal error: ") + e.what());
    } catch (...) {
      raise(internal_error, "internal error: unknown C++ exception");
    }
  });

  py::class_<RunHandle, std::shared_ptr<RunHandle>>(m, "RunHandle",
                                                    "A computed scene, kept for Result.write.");
  m.def("run", &run_file, py::arg("scene"), py::arg("overrides"), py::arg("allow_large"),
        "Computes a scene: (handle, {HDF5 path: array}, {/meta attribute: value}, "
        "{HDF5 path: units}).");
  m.def("robustness", &robustness_file, py::arg("scene"), py::arg("overrides"), py::arg("threads"),
        "Runs a scene's robustness study: ({HDF5 path: array}, {/meta attribute: value}, "
        "{HDF5 path: units}) of its hexdyn-robustness/1 file.");
  m.def("write", &write_file, py::arg("handle"), py::arg("path"),
        "Writes a computed scene's hexdyn-result/5 file, with the CLI's checks on the path.");
  m.def("validate", &validate_file, py::arg("scene"), py::arg("overrides"),
        "Checks a scene or sweep file as `hexdyn validate` does.");
  m.def("sample_problem", &sample_problem_file, py::arg("scene"), py::arg("overrides"),
        py::arg("t"),
        "The allocation problem of one instant of a scene, its layout and the run's answers.");
  hexdyn_python::add_dynamics_functions(m);
}
