//! \file delmesh_module.cpp
//! The Python module `delmesh`: mesh, check, solve and surfaces on numpy arrays.  Each function
//! runs the computation of the matching `delmesh` subcommand (apps/commands.h), so the same input
//! and seed give the same mesh, and an input the program refuses raises ValueError with the text
//! of the program's `error:` line in Python's terms (argument names for flags: python_terms).  Numbers are validated from their Python text (str(value)) by
//! the program's own option checks, so lam=float("nan") is refused as --lambda nan is.
//!
//! Threads: every call releases the GIL while the library works.  The library builds its
//! symbolic systems with GiNaC, which is not thread-safe, so calls from several Python threads
//! run one at a time (a process-wide mutex, always taken after releasing the GIL).  mesh() runs
//! del_mesh on a worker thread; the calling thread waits without the GIL and, every
//! poll_interval, takes the GIL to hand the queued progress reports to the callback and to run
//! Python's signal handlers: an exception from either (KeyboardInterrupt on Ctrl-C) sets the
//! run's interrupt flag, the run stops at its next check, the worker is joined and the exception
//! is raised.

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <cstdlib>
#include <deque>
#include <exception>
#include <functional>
#include <limits>
#include <mutex>
#include <optional>
#include <regex>
#include <sstream>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

#include "apps/command_line.h"
#include "apps/commands.h"
#include "apps/output_files.h"
#include "common/errors.h"
#include "common/run_limits.h"
#include "meshing/core/mesh_checker.h"
#include "meshing/driver/del_mesh.h"
#include "meshing/inputs/input_mesh.h"
#include "meshing/inputs/mesh_io.h"
#include "solvers/primitive_registry.h"

namespace py = pybind11;

namespace delmesh::python {

namespace {

using namespace delmesh::app;

//! How often a waiting mesh() call takes the GIL to deliver progress and run signal handlers.
constexpr std::chrono::milliseconds poll_interval{50};

// ---------------------------------------------------------------------------------------------
// One call into the library at a time
// ---------------------------------------------------------------------------------------------

std::mutex& library_mutex() {
  static std::mutex m;
  return m;
}

//! True on a thread that is inside a call (a progress callback calling delmesh again would wait
//! for itself).
thread_local bool inside_call = false;

//! Held for the duration of a library call: releases the GIL, then takes the library mutex.
class LibraryCall {
 public:
  LibraryCall() {
    if (inside_call) throw std::runtime_error("delmesh: a progress callback cannot call delmesh");
    inside_call = true;
    release_.emplace();
    lock_ = std::unique_lock<std::mutex>(library_mutex());
  }
  ~LibraryCall() {
    lock_ = {};
    release_.reset();
    inside_call = false;
  }
  LibraryCall(const LibraryCall&) = delete;
  LibraryCall& operator=(const LibraryCall&) = delete;

 private:
  std::optional<py::gil_scoped_release> release_;
  std::unique_lock<std::mutex> lock_;
};

//! Issues each warning as a Python RuntimeWarning (the program prints them as `warning:` lines).
//! Needs the GIL.
void warn_all(const std::vector<std::string>& warnings) {
  for (const std::string& w : warnings) {
    if (PyErr_WarnEx(PyExc_RuntimeWarning, w.c_str(), 2) != 0) throw py::error_already_set();
  }
}

// ---------------------------------------------------------------------------------------------
// Python values as the program's option texts
// ---------------------------------------------------------------------------------------------

std::string text_of(const py::handle& value) { return py::str(value); }

//! A number option: its text passes the program's finite-number check, then reads as a double.
double finite_option(const std::string& option, const py::handle& value) {
  const std::string text = text_of(value);
  require_finite_number(option, text);
  return std::strtod(text.c_str(), nullptr);
}

//! A whole-number option: its text passes the program's range check, then reads as an integer.
std::uint64_t whole_option(const std::string& option, const py::handle& value, unsigned long long min,
                           unsigned long long max) {
  const std::string text = text_of(value);
  require_whole_number(option, text, min, max);
  return std::strtoull(text.c_str(), nullptr, 10);
}

//! A comma-separated option (--box, --point, ...): a string as it is, a sequence of numbers
//! joined by commas.
std::string list_option(const py::handle& value) {
  if (py::isinstance<py::str>(value)) return value.cast<std::string>();
  std::string text;
  for (const py::handle item : py::iterable(py::reinterpret_borrow<py::object>(value))) {
    text += (text.empty() ? "" : ",") + text_of(item);
  }
  return text;
}

//! The text of E: a str (sympy expressions through str()).  Throws TypeError for anything else,
//! with a word on callables, which cannot be differentiated exactly.
std::string expr_text(const py::object& expr) {
  if (py::isinstance<py::str>(expr)) return expr.cast<std::string>();
  const std::string type = py::str(py::type::of(expr).attr("__name__"));
  const std::string module = py::str(py::type::of(expr).attr("__module__"));
  if (module.rfind("sympy", 0) == 0) return py::str(expr);
  if (PyCallable_Check(expr.ptr()))
    throw py::type_error("expr must be E(x, y, z) as a string (e.g. 'x**2+y**2+z**2-1') or a sympy expression, "
                         "not a Python function: delmesh differentiates E exactly, which a function does not allow");
  throw py::type_error("expr must be E(x, y, z) as a string or a sympy expression, not " + type);
}

//! A path (str or os.PathLike).
std::string path_option(const py::handle& value) {
  return py::module_::import("os").attr("fspath")(value).cast<std::string>();
}

//! A message of the program in Python's terms: each flag --some-option becomes the argument
//! some_option (--lambda becomes lam), so that "--expr needs --box" reads "expr needs box".
std::string python_terms(const std::string& message) {
  static const std::regex flag("--([a-z][a-z0-9]*(-[a-z0-9]+)*)");
  std::string out;
  auto last = message.cbegin();
  for (std::sregex_iterator it(message.begin(), message.end(), flag), end; it != end; ++it) {
    out.append(last, (*it)[0].first);
    std::string name = (*it)[1].str();
    std::replace(name.begin(), name.end(), '-', '_');
    out += name == "lambda" ? "lam" : name;
    last = (*it)[0].second;
  }
  out.append(last, message.cend());
  return out;
}

py::object from_json(const std::string& dumped) { return py::module_::import("json").attr("loads")(dumped); }

//! An n × 3 numpy array of T whose entry (i, k) is at(i, k).  Needs the GIL.
template <class T, class At>
py::array_t<T> rows_of_three(std::size_t n, const At& at) {
  py::array_t<T> a({static_cast<py::ssize_t>(n), py::ssize_t{3}});
  auto r = a.template mutable_unchecked<2>();
  for (std::size_t i = 0; i < n; ++i) {
    for (int k = 0; k < 3; ++k) r(i, k) = static_cast<T>(at(i, k));
  }
  return a;
}

// ---------------------------------------------------------------------------------------------
// mesh
// ---------------------------------------------------------------------------------------------

//! The soup of an N × 3 array of coordinates and an M × 3 array of integer vertex indices.
//! Throws InvalidInput on other shapes, non-integer or negative indices.
void read_soup(const py::object& vertices, const py::object& triangles, std::vector<Point3>& points,
               std::vector<std::array<std::size_t, 3>>& faces) {
  const py::module_ np = py::module_::import("numpy");
  const py::array v = np.attr("asarray")(vertices, "float64");
  if (v.ndim() != 2 || v.shape(1) != 3) {
    throw InvalidInput("vertices: expected an N x 3 array of coordinates, got shape " +
                       text_of(py::tuple(v.attr("shape"))));
  }
  const py::array t_any = np.attr("asarray")(triangles);
  if (t_any.size() > 0 && !np.attr("issubdtype")(t_any.dtype(), np.attr("integer")).cast<bool>()) {
    throw InvalidInput("triangles: expected integer vertex indices, got dtype " + text_of(t_any.dtype()));
  }
  const py::array t = np.attr("asarray")(t_any, "int64");
  if (t.ndim() != 2 || t.shape(1) != 3) {
    throw InvalidInput("triangles: expected an M x 3 array of vertex indices, got shape " +
                       text_of(py::tuple(t.attr("shape"))));
  }
  const auto vv = py::array_t<double, py::array::c_style | py::array::forcecast>(v).unchecked<2>();
  const auto tt = py::array_t<std::int64_t, py::array::c_style | py::array::forcecast>(t).unchecked<2>();
  points.clear();
  points.reserve(static_cast<std::size_t>(vv.shape(0)));
  for (py::ssize_t i = 0; i < vv.shape(0); ++i) points.emplace_back(vv(i, 0), vv(i, 1), vv(i, 2));
  faces.clear();
  faces.reserve(static_cast<std::size_t>(tt.shape(0)));
  for (py::ssize_t i = 0; i < tt.shape(0); ++i) {
    std::array<std::size_t, 3> f{};
    for (int k = 0; k < 3; ++k) {
      if (tt(i, k) < 0) {
        throw InvalidInput("triangles: triangle " + std::to_string(i) + " has the negative index " +
                           std::to_string(tt(i, k)));
      }
      f[k] = static_cast<std::size_t>(tt(i, k));
    }
    faces.push_back(f);
  }
}

struct MeshResult {
  py::array_t<double> vertices;        // N × 3
  py::array_t<std::int64_t> triangles;  // M × 3
  py::object stats;
  std::string status;
};

//! What a run on the worker gets from the call: the interrupt flag and the progress sink to put
//! in its DelMeshOptions, and the call's limits (also RunLimits::current() on the worker).
struct CallControls {
  const std::atomic<bool>* interrupt = nullptr;
  std::function<void(const ProgressReport&)> progress;  //!< empty without a progress callback
  const RunLimits* limits = nullptr;

  //! `options` with the flag, the sink, and the time left of the call's limit (from the call's start).
  DelMeshOptions applied_to(DelMeshOptions options) const {
    options.interrupt = interrupt;
    if (progress) options.progress = progress;
    if (const std::optional<double> left = limits->seconds_left())
      options.time_limit_seconds = std::max(*left, std::numeric_limits<double>::denorm_min());
    return options;
  }
};

//! work(controls) on a worker thread under the call's limits: a deadline `time_limit` seconds
//! (0: none) from now and an interrupt flag, in a RunLimits::Scope there, so that parsing and
//! compiling E, reading and validating an input mesh and the run itself all see them.  The
//! caller keeps serving progress and signals (file comment).  A phase stopped before the run
//! throws RunStopped, which reaches Python as TimeoutError (or the KeyboardInterrupt that set
//! the flag).  When a Python exception stops the call after `work` has returned its result (a
//! run stopped by the interrupt flag returns its partial mesh), that result goes to `partial`
//! if given, and the exception is raised.
template <class Result>
Result run_on_worker(double time_limit, const py::object& progress,
                     const std::function<Result(const CallControls&)>& work,
                     std::optional<Result>* partial = nullptr) {
  std::atomic<bool> interrupt{false};
  const RunLimits limits = RunLimits::after(time_limit, &interrupt);
  std::mutex m;
  std::condition_variable changed;
  std::deque<ProgressReport> reports;
  bool done = false;
  std::optional<Result> result;
  std::exception_ptr failure;

  CallControls controls;
  controls.interrupt = &interrupt;
  controls.limits = &limits;
  if (!progress.is_none()) {
    controls.progress = [&](const ProgressReport& report) {
      std::lock_guard<std::mutex> lock(m);
      reports.push_back(report);
      changed.notify_all();
    };
  }
  // Whatever leaves this function, the worker is stopped and joined first (it never takes the GIL).
  struct Joiner {
    std::atomic<bool>& interrupt;
    std::thread thread;
    ~Joiner() {
      if (thread.joinable()) {
        interrupt.store(true);
        thread.join();
      }
    }
  } worker{interrupt, std::thread([&] {
    try {
      const RunLimits::Scope scope(limits);
      Result r = work(controls);
      std::lock_guard<std::mutex> lock(m);
      result.emplace(std::move(r));
    } catch (...) {
      std::lock_guard<std::mutex> lock(m);
      failure = std::current_exception();
    }
    std::lock_guard<std::mutex> lock(m);
    done = true;
    changed.notify_all();
  })};

  std::optional<py::error_already_set> python_error;
  for (bool finished = false; !finished;) {
    std::deque<ProgressReport> delivered;
    {
      std::unique_lock<std::mutex> lock(m);
      changed.wait_for(lock, poll_interval, [&] { return done || !reports.empty(); });
      finished = done;
      delivered.swap(reports);
    }
    if (python_error) continue;  // stopping: wait for the worker only
    py::gil_scoped_acquire gil;
    try {
      for (const ProgressReport& report : delivered) progress(py::cast(report));
      if (PyErr_CheckSignals() != 0) throw py::error_already_set();
    } catch (py::error_already_set& e) {
      python_error.emplace(std::move(e));
      interrupt.store(true);
    }
  }
  worker.thread.join();
  if (python_error) {
    if (partial && result) partial->emplace(std::move(*result));
    py::gil_scoped_acquire gil;
    throw std::move(*python_error);
  }
  if (failure) std::rethrow_exception(failure);
  return std::move(*result);
}

//! certify()'s certificates (method auto) of a finished run's mesh, as JSON; null for a run
//! stopped by a limit or without triangles.  Runs on the worker, under the call's controls.
nlohmann::json certificate_of(const DelMeshResult& r, const SurfaceInput& input, std::uint64_t seed,
                              const CallControls& controls) {
  std::vector<Point3> points;
  std::vector<std::array<std::size_t, 3>> faces;
  mesh_to_soup(r.mesh, points, faces);
  const bool ended = r.status == MeshStatus::complete || r.status == MeshStatus::uncertified;
  if (!ended || faces.empty()) return nullptr;
  const TopologyCertificates c = certify_topology(points, faces, input, CertifyMethod::automatic, seed,
                                                  controls.interrupt, controls.limits->deadline());
  return nlohmann::json(c.to_json());
}

//! mesh()'s input_mesh given as (vertices, triangles) arrays instead of a path.
using InputSoup = std::optional<std::pair<std::vector<Point3>, std::vector<std::vector<std::size_t>>>>;

//! mesh()'s arguments as the command's request (the values checked as its flags are), and
//! `input_soup` set when input_mesh is a pair of arrays.
MeshRequest mesh_request(const py::object& expr, const py::object& box, const py::object& surface,
                         const py::object& input_mesh, const py::object& lam, const py::object& size_bound,
                         const std::string& phase, const py::object& seed, const py::object& max_points,
                         const py::object& time_limit, const py::object& threads, const std::string& solver,
                         const py::object& max_distance, InputSoup& input_soup) {
  MeshRequest request;
  if (!surface.is_none()) request.surface.surface = surface.cast<std::string>();
  if (!expr.is_none()) request.surface.expr = expr_text(expr);
  if (!box.is_none()) request.surface.box = list_option(box);
  if (!input_mesh.is_none() && (py::isinstance<py::tuple>(input_mesh) || py::isinstance<py::list>(input_mesh))) {
    const py::sequence pair = input_mesh;
    if (pair.size() != 2) throw InvalidInput("input_mesh: expected a path or a pair (vertices, triangles)");
    std::vector<std::array<std::size_t, 3>> triangles;
    input_soup.emplace();
    read_soup(pair[0], pair[1], input_soup->first, triangles);
    for (const auto& t : triangles) input_soup->second.push_back({t[0], t[1], t[2]});
  } else if (!input_mesh.is_none()) {
    request.input_mesh = path_option(input_mesh);
  }
  DelMeshOptions& options = request.options;
  options.lambda = finite_option("--lambda", lam);
  if (!size_bound.is_none()) options.size_bound = finite_option("--size-bound", size_bound);
  if (!max_distance.is_none()) options.max_distance = finite_option("--max-distance", max_distance);
  options.phase = parse_enum<MeshPhase>(phase, "--phase");
  options.solver = parse_enum<SolverBackend>(solver, "--solver");
  options.seed = whole_option("--seed", seed, 0, std::numeric_limits<std::uint64_t>::max());
  if (!max_points.is_none()) options.max_points = whole_option("--max-points", max_points, 1, max_count);
  if (!time_limit.is_none()) options.time_limit_seconds = finite_option("--time-limit", time_limit);
  if (!threads.is_none()) options.threads = static_cast<int>(whole_option("--threads", threads, 0, max_threads));
  return request;
}

//! The run of mesh() on the worker: planning (parsing and compiling E, or reading and validating
//! the mesh) under the call's limits, then the run; its statistics (as JSON text) and warnings go
//! to the caller, who issues the warnings once it has the GIL again.
DelMeshResult run_mesh_request(const MeshRequest& request, const InputSoup& input_soup, bool certify,
                               const CallControls& controls, std::string& statistics,
                               std::vector<std::string>& warnings) {
  if (request.input_mesh || input_soup) {
    // A triangle mesh, remeshed through its MeshOracle as `delmesh mesh --input-mesh` does.
    const MeshInputPlan plan =
        input_soup ? plan_mesh_input(request, validate_input_mesh(input_soup->first, input_soup->second, "input_mesh"),
                                     "input_mesh")
                   : plan_mesh_input(request);
    warnings = plan.warnings;
    DelMeshResult r = remesh(plan, controls.applied_to(plan.options));
    statistics = run_statistics(r, request.options.seed, std::nullopt).dump();
    return r;
  }
  const MeshPlan plan = plan_mesh(request);
  warnings = plan.warnings;
  DelMeshResult r = del_mesh(plan.input.surface, plan.input.box, controls.applied_to(plan.options));
  nlohmann::json stats = mesh_statistics(r, plan.input, request.options.seed, std::nullopt);
  if (certify) stats["certificate"] = certificate_of(r, plan.input, request.options.seed, controls);
  statistics = stats.dump();
  return r;
}

MeshResult mesh(const py::object& expr, const py::object& box, const py::object& surface,
                const py::object& input_mesh, const py::object& lam, const py::object& size_bound,
                const std::string& phase, const py::object& seed, const py::object& max_points,
                const py::object& time_limit, const py::object& threads, const py::object& progress,
                const std::string& solver, const py::object& max_distance, bool certify) {
  InputSoup input_soup;
  const MeshRequest request = mesh_request(expr, box, surface, input_mesh, lam, size_bound, phase, seed, max_points,
                                           time_limit, threads, solver, max_distance, input_soup);
  if (!progress.is_none() && !PyCallable_Check(progress.ptr())) throw py::type_error("progress must be callable");
  if (certify && (request.input_mesh || input_soup))
    throw InvalidInput("certify needs expr or surface (the certificate is proved on an implicit surface)");

  std::vector<Point3> points;
  std::vector<std::array<std::size_t, 3>> faces;
  std::string statistics, status;
  std::vector<std::string> warnings;
  std::optional<py::error_already_set> stopped;
  {
    LibraryCall call;
    std::optional<DelMeshResult> result;
    try {
      result = run_on_worker<DelMeshResult>(
          request.options.time_limit_seconds, progress,
          [&](const CallControls& controls) {
            return run_mesh_request(request, input_soup, certify, controls, statistics, warnings);
          },
          &result);
    } catch (py::error_already_set& e) {
      // Ctrl-C (or a progress callback's exception) after the run returned its partial mesh.
      if (!result) throw;
      stopped.emplace(std::move(e));
    }
    mesh_to_soup(result->mesh, points, faces);
    std::ostringstream s;
    s << result->status;
    status = s.str();
  }

  MeshResult out;
  out.vertices = rows_of_three<double>(points.size(), [&](std::size_t i, int k) { return points[i][k]; });
  out.triangles = rows_of_three<std::int64_t>(faces.size(), [&](std::size_t i, int k) { return faces[i][k]; });
  out.stats = from_json(statistics);
  out.status = status;
  if (stopped) {
    py::setattr(stopped->value(), "partial", py::cast(out));
    throw std::move(*stopped);
  }
  warn_all(warnings);
  return out;
}

// ---------------------------------------------------------------------------------------------
// check
// ---------------------------------------------------------------------------------------------

// ---------------------------------------------------------------------------------------------
// save
// ---------------------------------------------------------------------------------------------

void save(const py::object& path, const py::object& vertices, const py::object& triangles) {
  const std::string file = path_option(path);
  TriangleSoup soup;
  read_soup(vertices, triangles, soup.points, soup.triangles);
  for (std::size_t f = 0; f < soup.triangles.size(); ++f)
    for (std::size_t i : soup.triangles[f])
      if (i >= soup.points.size())
        throw InvalidInput("triangles: triangle " + std::to_string(f) + " refers to vertex " + std::to_string(i) +
                           " of " + std::to_string(soup.points.size()));
  const MeshFormat format = mesh_format(file);
  // Written as the program writes its outputs: to a temporary file renamed over the target.
  OutputSet outputs;
  outputs.add("path", file);
  const py::gil_scoped_release release;
  outputs.write({[&](std::ostream& s) { write_triangle_soup(soup, s, format); }});
}

py::object check(const py::object& vertices, const py::object& triangles, const py::object& lam) {
  std::optional<double> lambda;
  if (!lam.is_none()) {
    lambda = finite_option("--lambda", lam);
    require_bounds_lambda(*lambda);
  }
  std::vector<Point3> points;
  std::vector<std::array<std::size_t, 3>> faces;
  read_soup(vertices, triangles, points, faces);

  std::string report;
  std::vector<std::string> warnings;
  {
    LibraryCall call;
    const CheckVerdict verdict = check_verdict(check_mesh(points, faces), lambda);
    report = verdict.to_json().dump();
    warnings = verdict.warnings;
  }
  warn_all(warnings);
  return from_json(report);
}

// ---------------------------------------------------------------------------------------------
// certify
// ---------------------------------------------------------------------------------------------

py::object certify(const py::object& vertices, const py::object& triangles, const py::object& expr,
                   const py::object& box, const py::object& surface, const std::string& method,
                   const py::object& seed, const py::object& time_limit) {
  SurfaceArguments arguments;
  if (!surface.is_none()) arguments.surface = surface.cast<std::string>();
  if (!expr.is_none()) arguments.expr = expr_text(expr);
  if (!box.is_none()) arguments.box = list_option(box);
  const CertifyMethod chosen = parse_enum<CertifyMethod>(method, "method");
  const std::uint64_t seed_value = whole_option("--seed", seed, 0, std::numeric_limits<std::uint64_t>::max());
  const double limit = time_limit.is_none() ? 0 : finite_option("--time-limit", time_limit);
  std::vector<Point3> points;
  std::vector<std::array<std::size_t, 3>> faces;
  read_soup(vertices, triangles, points, faces);
  std::string report;
  {
    LibraryCall call;
    // Compiling E and both certificates run on the worker, under the call's limit and Ctrl-C.
    const TopologyCertificates c =
        run_on_worker<TopologyCertificates>(limit, py::none(), [&](const CallControls& controls) {
          const SurfaceInput input = arguments.resolve();
          return certify_topology(points, faces, input, chosen, seed_value, controls.interrupt,
                                  controls.limits->deadline());
        });
    report = c.to_json().dump();
  }
  return from_json(report);
}

// ---------------------------------------------------------------------------------------------
// solve
// ---------------------------------------------------------------------------------------------

struct SolveAnswer {
  std::string status;
  py::array_t<double> roots;      // K × 3
  py::array_t<double> undecided;  // U × 3 × 2
  std::vector<std::string> undecided_reasons;
  std::size_t boxes = 0;
  double seconds = 0;
  std::string solver;
  std::string description;
};

SolveAnswer solve(const std::string& primitive, const py::object& expr, const py::object& box,
                  const py::object& surface, const py::object& direction, const py::object& direction2,
                  const py::object& point, const py::object& plane_origin, const py::object& plane_normal,
                  const std::string& solver, const std::string& taylor_forms, const py::object& max_boxes,
                  const py::object& time_limit) {
  SolveRequest request;
  request.primitive = primitive;
  if (!surface.is_none()) request.surface.surface = surface.cast<std::string>();
  if (!expr.is_none()) request.surface.expr = expr_text(expr);
  if (!box.is_none()) request.surface.box = list_option(box);
  const std::pair<const char*, const py::object*> parameters[] = {{"--direction", &direction},
                                                                  {"--direction2", &direction2},
                                                                  {"--point", &point},
                                                                  {"--plane-origin", &plane_origin},
                                                                  {"--plane-normal", &plane_normal}};
  for (const auto& [option, value] : parameters) {
    if (!value->is_none()) request.parameters[option] = list_option(*value);
  }
  request.solver = solver;
  request.taylor_forms = taylor_forms;
  if (!max_boxes.is_none()) request.max_boxes = whole_option("--max-boxes", max_boxes, 1, max_count);
  if (!time_limit.is_none()) request.time_limit = finite_option("--time-limit", time_limit);

  std::optional<SolveOutcome> outcome;
  {
    LibraryCall call;
    // The time limit counts from the call: compiling the primitive's system tests it too.
    const RunLimits limits = RunLimits::after(request.time_limit, nullptr);
    const RunLimits::Scope scope(limits);
    outcome.emplace(solve_primitive(request));
  }
  const SolveOutcome& o = *outcome;
  SolveAnswer a;
  std::ostringstream status;
  status << o.result.status;
  a.status = status.str();
  a.roots = rows_of_three<double>(o.result.roots.size(),
                                  [&](std::size_t i, int k) { return o.result.roots[i].world[k]; });
  a.undecided = py::array_t<double>({static_cast<py::ssize_t>(o.undecided.size()), py::ssize_t{3}, py::ssize_t{2}});
  auto u = a.undecided.mutable_unchecked<3>();
  for (std::size_t i = 0; i < o.undecided.size(); ++i) {
    for (int k = 0; k < 3; ++k) {
      u(i, k, 0) = o.undecided[i][k][0];
      u(i, k, 1) = o.undecided[i][k][1];
    }
    std::ostringstream reason;
    reason << o.result.undecided[i].reason;
    a.undecided_reasons.push_back(reason.str());
  }
  a.boxes = o.result.counters.boxes;
  a.seconds = o.seconds;
  a.solver = o.solver;
  a.description = o.description;
  return a;
}

// ---------------------------------------------------------------------------------------------
// surfaces
// ---------------------------------------------------------------------------------------------

py::object surfaces() {
  std::string dumped;
  {
    LibraryCall call;
    dumped = catalog_json().dump();
  }
  return from_json(dumped);
}

}  // namespace

}  // namespace delmesh::python

PYBIND11_MODULE(delmesh, m) {
  using namespace delmesh::python;
  m.doc() =
      "delmesh: certified meshing of smooth closed implicit surfaces E(x,y,z) = 0 with DelMesh (Cheng, Dey,\n"
      "Ramos, Ray).  mesh() returns numpy arrays; check() is the independent checker; solve() one numerical\n"
      "primitive; surfaces() the catalog.  The functions run the computations of the `delmesh` program:\n"
      "the same input and seed give the same mesh, and an input the program refuses raises ValueError\n"
      "with the text of the program's `error:` line.  Each call releases the GIL; calls from several\n"
      "threads run one at a time.";
  m.attr("__version__") = DELMESH_VERSION;

  py::register_exception_translator([](std::exception_ptr p) {
    try {
      if (p) std::rethrow_exception(p);
    } catch (const std::invalid_argument& e) {
      PyErr_SetString(PyExc_ValueError, python_terms(delmesh::app::one_line(e.what())).c_str());
    } catch (const delmesh::app::OutputError& e) {
      PyErr_SetString(PyExc_OSError, delmesh::app::one_line(e.what()).c_str());
    } catch (const delmesh::RunStopped& e) {
      // A limit passed before there was a mesh to return (while compiling E or validating an input).
      PyErr_SetString(e.reason() == delmesh::StopReason::interrupted ? PyExc_KeyboardInterrupt : PyExc_TimeoutError,
                      delmesh::app::one_line(e.what()).c_str());
    }
  });

  py::class_<delmesh::ProgressReport>(m, "ProgressReport",
                                      "One progress report of mesh(): the argument of its progress callback.")
      .def_property_readonly(
          "phase", [](const delmesh::ProgressReport& r) { return std::string(enum_name(r.phase)); },
          "topology, geometry (the refinement) or certifying (the distance certificate)")
      .def_readonly("points", &delmesh::ProgressReport::points,
                    "the samples so far (when certifying: the samples the refinement ended with)")
      .def_readonly("elapsed", &delmesh::ProgressReport::elapsed_seconds,
                    "seconds since the run started (the clock of stats[\"seconds\"])")
      .def_property_readonly(
          "queued",
          [](const delmesh::ProgressReport& r) {
            py::dict queued;
            for (const delmesh::QueueSize& q : r.queued) queued[py::str(q.name)] = q.size;
            return queued;
          },
          "the refinement's queue sizes by check name ({} when certifying)")
      .def_property_readonly("text", &delmesh::ProgressReport::text, "the report as one line")
      .def("__str__", &delmesh::ProgressReport::text)
      .def("__repr__", [](const delmesh::ProgressReport& r) {
        std::ostringstream s;
        s << "<ProgressReport phase=" << r.phase << " points=" << r.points << " elapsed=" << r.elapsed_seconds << '>';
        return s.str();
      });
  py::class_<MeshResult>(m, "MeshResult", "The output of mesh(): Tri S|Sigma, its statistics and status.")
      .def_readonly("vertices", &MeshResult::vertices, "N x 3 float64 array of vertex coordinates")
      .def_readonly("triangles", &MeshResult::triangles,
                    "M x 3 int64 array of vertex indices, consistently outward oriented")
      .def_readonly("stats", &MeshResult::stats,
                    "the statistics as a dict: the JSON `delmesh mesh --stats` writes, without mesh_file")
      .def_readonly("status", &MeshResult::status,
                    "complete, uncertified, point_limit, time_limit or interrupted (see stats['unsettled'])")
      .def("__repr__", [](const MeshResult& r) {
        return "<delmesh.MeshResult status=" + r.status + ", " + std::to_string(r.vertices.shape(0)) +
               " vertices, " + std::to_string(r.triangles.shape(0)) + " triangles>";
      });

  py::class_<SolveAnswer>(m, "SolveResult", "The output of solve(), in world coordinates.")
      .def_readonly("status", &SolveAnswer::status, "complete, undecided, non_isolated, box_limit or time_limit")
      .def_readonly("roots", &SolveAnswer::roots, "K x 3 float64 array: a point of each certified root's box")
      .def_readonly("undecided", &SolveAnswer::undecided,
                    "U x 3 x 2 float64 array: the world bounding box [[x0,x1],[y0,y1],[z0,z1]] of each region "
                    "neither excluded nor certified")
      .def_readonly("undecided_reasons", &SolveAnswer::undecided_reasons, "why each region is undecided")
      .def_readonly("boxes", &SolveAnswer::boxes, "boxes the solver visited")
      .def_readonly("seconds", &SolveAnswer::seconds, "solver time")
      .def_readonly("solver", &SolveAnswer::solver, "subdivision, homotopy or univariate isolator")
      .def_readonly("description", &SolveAnswer::description, "the primitive's parameters as used")
      .def("__repr__", [](const SolveAnswer& a) {
        return "<delmesh.SolveResult status=" + a.status + ", " + std::to_string(a.roots.shape(0)) + " roots, " +
               std::to_string(a.undecided.shape(0)) + " undecided>";
      });

  m.def("mesh", &mesh, py::kw_only(), py::arg("expr") = py::none(), py::arg("box") = py::none(),
        py::arg("surface") = py::none(), py::arg("input_mesh") = py::none(), py::arg("lam") = delmesh::lambda0,
        py::arg("size_bound") = py::none(), py::arg("phase") = "all", py::arg("seed") = 1,
        py::arg("max_points") = py::none(), py::arg("time_limit") = py::none(), py::arg("threads") = py::none(),
        py::arg("progress") = py::none(), py::arg("solver") = "subdivision", py::arg("max_distance") = py::none(),
        py::arg("certify") = false,
        R"doc(Mesh a surface with DelMesh, as `delmesh mesh` does; returns a MeshResult.

Give exactly one of expr (E(x,y,z) as a string, or a sympy expression, the surface is E = 0; a
Python function raises TypeError) with box, surface (a catalog name, see surfaces(); a box
replaces the catalog's) or input_mesh (the path of a closed mesh, OFF/PLY/OBJ/STL, polygons
triangulated, or a pair (vertices, triangles) of N x 3 and M x 3 arrays: it is validated and
remeshed as by `delmesh mesh --input-mesh FILE`, with the same default termination floor, and the
statistics carry "input_mesh", whose "file" is "input_mesh" for arrays).

box: "x0,x1,y0,y1,z0,z1" or six numbers; the surface must lie strictly inside.
lam: lambda in (0, 1/3); Theorem 6.1 covers (0, 0.06] (guaranteed topology, radius-edge ratio
  <= 1+lam, roughness <= 2 beta(lam)); larger values run with a RuntimeWarning.
size_bound: also refine triangles whose surface Delaunay ball radius exceeds it.
certify: (expr or surface only) certify the output from scratch as certify() does (method
  "auto") and put that dict under stats["certificate"] (None for a run stopped by a limit or
  without triangles).
max_distance: (expr or surface only) also refine until the mesh is proved within it of the
  surface; complete only if the gradient-flow certificate proves that two-sided Hausdorff bound
  (statistics["distance"], which every expr or surface run reports).
phase: "topology" (SampleTopology only) or "all" (DelMesh).
seed: 0 <= seed < 2**64; the same input and seed give the same mesh as the program.
max_points, time_limit (seconds; 0 or None: none): a run stopped by a limit returns its partial
  mesh with status point_limit or time_limit.  The time limit counts from the call: one that
  passes before meshing starts (while E is compiled or input_mesh validated) raises TimeoutError.
threads: worker threads (None or 0: every hardware thread); the mesh does not depend on it.
progress: called on the calling thread with each ProgressReport (about every 0.5 s): phase, points,
elapsed, queued, text; str() of it is the text line.
solver: "subdivision" or "homotopy" (polynomial E only).

The GIL is released while meshing.  Ctrl-C (any exception raised by a signal handler or by
progress) stops the run at its next check and is raised once the run has stopped; when the run
had begun, the exception's attribute `partial` holds the partial MeshResult (status
interrupted), the mesh the program writes on Ctrl-C.
Raises ValueError, with the program's error message in Python's terms (argument names for the
program's flags), on invalid input.)doc");

  m.def("save", &save, py::arg("path"), py::arg("vertices"), py::arg("triangles"),
        R"doc(Write a triangle mesh as `delmesh mesh --out` does: OFF, PLY, OBJ, binary STL or VTK XML
PolyData (.vtp, without normals) by the extension of path (str or os.PathLike), through a
temporary file renamed over the target, so an existing file is replaced only by a complete one.

vertices: N x 3 coordinates; triangles: M x 3 integer vertex indices (as MeshResult gives them).
Raises ValueError on an unknown extension, bad shapes or indices, OSError if the file cannot be
written.)doc");

  m.def("check", &check, py::arg("vertices"), py::arg("triangles"), py::arg("lam") = py::none(),
        R"doc(The independent checker on a triangle soup, as `delmesh check --json` reports it; returns a dict.

vertices: N x 3 array of coordinates; triangles: M x 3 array of integer vertex indices.
Components, Euler characteristic, genus_per_component (None where the component is not a closed
orientable 2-manifold), closed / manifold / orientable with the counts of boundary edges and loops
and of non-manifold edges and vertices, min angle, max radius-edge ratio, max roughness.
lam: lambda in (0, 1/6): also "lambda", the bounds of Theorem 6.1 ("bounds") and which hold ("pass").
Raises ValueError on an index out of range, a repeated index in a triangle, a non-finite point.)doc");

  m.def("certify", &certify, py::arg("vertices"), py::arg("triangles"), py::kw_only(), py::arg("expr") = py::none(),
        py::arg("box") = py::none(), py::arg("surface") = py::none(), py::arg("method") = "auto",
        py::arg("seed") = 1, py::arg("time_limit") = py::none(),
        R"doc(Certify the topology of a triangle soup for a surface, as `delmesh check --certify --json`; returns a dict.

vertices: N x 3 array of coordinates; triangles: M x 3 array of integer vertex indices.  The surface
as for mesh(): expr with box, or a catalog surface (a box replaces the catalog's).
method: "auto" (restricted-Delaunay, then gradient-flow unless the first certified the mesh as
Tri S|Sigma), "restricted-delaunay", "gradient-flow" or "both" (each must certify).
The dict has "topology" {verdict: certified, refuted or undecided; method; reason;
hausdorff_upper_bound (a certified two-sided Hausdorff bound, with the gradient flow)}, and
"certificate" and "gradient_flow" for the certificates that ran.
seed: the generic directions.  time_limit (seconds from the call; 0 or None: none): a certificate
that reaches it is returned undecided with "time_limited": true; one passed while E is compiled
raises TimeoutError.  The GIL is released; Ctrl-C stops the certificate and is raised.
Raises ValueError, with the program's error message, on invalid input (a bad soup, a surface that
fails validation).)doc");

  // The primitives and their options come from the registry, so a registered primitive is
  // documented here as in `delmesh solve --help`.
  static const std::string solve_doc = [] {
    std::string doc = "Solve one numerical primitive with a certified solver, as `delmesh solve` does.\n\nprimitive: ";
    const auto& rows = delmesh::primitive_registry();
    for (std::size_t i = 0; i < rows.size(); ++i) {
      doc += (i ? ", " : "") + rows[i].name + " (";
      for (std::size_t k = 0; k < rows[i].options.size(); ++k) {
        std::string name = delmesh::option_flag(rows[i].options[k].option).substr(2);
        std::replace(name.begin(), name.end(), '-', '_');
        doc += (k ? ", " : "") + (rows[i].options[k].required ? name : "[" + name + "]");
      }
      doc += ")";
    }
    return doc + R"doc(; options in brackets are optional.  Vectors are three numbers or "a,b,c".  The surface as for mesh().
Returns a SolveResult: status, roots (K x 3), undecided (U x 3 x 2 world boxes) and their reasons.
The GIL is released while solving; time_limit (seconds, counted from the call) and max_boxes bound
the work: a limit that passes while the system is compiled raises TimeoutError, one that passes
while solving returns status time_limit.)doc";
  }();
  m.def("solve", &solve, py::arg("primitive"), py::kw_only(), py::arg("expr") = py::none(),
        py::arg("box") = py::none(), py::arg("surface") = py::none(), py::arg("direction") = py::none(),
        py::arg("direction2") = py::none(), py::arg("point") = py::none(), py::arg("plane_origin") = py::none(),
        py::arg("plane_normal") = py::none(), py::arg("solver") = "subdivision",
        py::arg("taylor_forms") = "automatic", py::arg("max_boxes") = py::none(), py::arg("time_limit") = py::none(),
        solve_doc.c_str());

  m.def("surfaces", &surfaces,
        "The catalog of named surfaces as `delmesh surfaces --json` lists it: a list of dicts {name, equation, "
        "box, components, genus_per_component, description, analytic_lfs}.");
}
