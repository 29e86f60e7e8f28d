// The Python module `bspbench._core` (pybind11), re-exported by bspbench/__init__.py: scenes
// (generated, read from files, or NumPy arrays), builds with any heuristic (built-in, a plugin's,
// or a Python callable), metrics and checks as dicts, orders as NumPy arrays, set operations on
// solids, suites. An edge like the CLI: names are resolved here, the library below takes objects.
//
// The GIL: builds by C++ heuristics, checks, merges and sweeps release it (they may use every
// core). A build whose splitter is a Python callable holds it throughout and runs on one thread,
// the callable being called from that thread only (docs/python.md).
#include <omp.h>
#include <pybind11/functional.h>
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <atomic>
#include <limits>

#include <nlohmann/json.hpp>

#include "catalog.h"
#include "solid_pairs.h"
#include "common/errors.h"
#include "common/revision.h"
#include "common/version.h"
#include "experiments/draw/draw.h"
#include "experiments/heuristic_choice.h"
#include "experiments/merge/set_operation.h"
#include "experiments/plugin_loader.h"
#include "io/mesh_reader.h"
#include "python_splitter.h"
#include "split/registry.h"
#include "suite/catalog.h"
#include "sweep/runner.h"
#include "tree/traverse.h"
#include "validate/order_check.h"
#include "validate/tree_invariants.h"

namespace py = pybind11;

namespace bsp::python {

namespace {

// Marks a call that looks heuristics up with the GIL released (build, merge, run_suite) for its
// length: the registry is read without a lock, so no plugin is registered while one runs.
class Lookup {
 public:
  Lookup() { ++running(); }
  ~Lookup() { --running(); }
  Lookup(const Lookup&) = delete;
  Lookup& operator=(const Lookup&) = delete;
  static std::atomic<int>& running() {
    static std::atomic<int> n{0};
    return n;
  }
};

// JSON as Python objects, through the json module: dicts, lists, numbers, strings.
py::object to_python(const nlohmann::json& j) { return py::module_::import("json").attr("loads")(j.dump()); }

// key=value assignments from a dict of Python values (numbers and strings as the CLI writes them).
ParamAssignments assignments(const py::dict& params) {
  ParamAssignments out;
  for (const auto& [k, v] : params) out.emplace_back(py::str(k), py::str(v));
  return out;
}

Scene generated(const std::string& name, std::optional<std::uint64_t> n, std::uint64_t seed, const py::dict& params) {
  ParamAssignments given = assignments(params);
  if (n) given.emplace_back("n", std::to_string(*n));
  const GeneratorInfo& g = find_generator(name);
  if (std::any_of(g.params.begin(), g.params.end(), [](const ParamSpec& p) { return p.name == "seed"; }))
    given.emplace_back("seed", std::to_string(seed));
  py::gil_scoped_release release;
  return make_scene(name, given);
}

// An (m, k, 3) array: m polygons of k vertices each, counter-clockwise seen from their front.
Scene from_array(const py::array_t<double, py::array::c_style | py::array::forcecast>& a, const std::string& name) {
  if (a.ndim() != 3 || a.shape(2) != 3 || a.shape(1) < 2)
    throw InputError(name + ": expected an array of shape (polygons, vertices >= 2, 3), not of " + std::to_string(a.ndim()) +
                     " dimensions");
  Scene s;
  s.name = name;
  const auto v = a.unchecked<3>();
  for (py::ssize_t i = 0; i < a.shape(0); ++i) {
    Polygon p;
    p.source = static_cast<std::uint32_t>(i);
    for (py::ssize_t j = 0; j < a.shape(1); ++j) p.verts.push_back({{v(i, j, 0), v(i, j, 1), v(i, j, 2)}});
    s.polygons.push_back(std::move(p));
  }
  check_scene(s, name);
  return s;
}

py::array_t<double> polygon_array(const Polygon& p) {
  py::array_t<double> out({static_cast<py::ssize_t>(p.verts.size()), py::ssize_t{3}});
  auto w = out.mutable_unchecked<2>();
  for (std::size_t i = 0; i < p.verts.size(); ++i) {
    const Vec3& q = p.verts[i].p;
    w(static_cast<py::ssize_t>(i), 0) = q.x, w(static_cast<py::ssize_t>(i), 1) = q.y, w(static_cast<py::ssize_t>(i), 2) = q.z;
  }
  return out;
}

template <class T>
py::array_t<T> to_array(const std::vector<T>& v) {
  py::array_t<T> out(static_cast<py::ssize_t>(v.size()));
  std::copy(v.begin(), v.end(), out.mutable_data());
  return out;
}

Vec3 to_vec3(const std::array<double, 3>& a) { return {a[0], a[1], a[2]}; }

Shape shape_of(const std::string& name) {
  const auto s = shape_named(name);
  if (!s) throw UsageError("shape must be strict, coarse or leafy, not '" + name + "'");
  return *s;
}

// A built tree with the scene it was built from (measures and checks need both).
struct BuiltTree {
  Tree tree;
  std::shared_ptr<Scene> scene;
};

BuiltTree build(const std::shared_ptr<Scene>& scene, const std::string& heuristic, const py::dict& params,
                std::uint64_t seed, const std::string& shape) {
  BuildOptions options;
  options.shape = shape_of(shape);
  const Lookup lookup;
  const auto choice = experiments::HeuristicChoice::of(heuristic, assignments(params));
  py::gil_scoped_release release;
  return {choice.build(scene->polygons, options, seed), scene};
}

// OpenMP's thread count for this thread, restored when it goes out of scope.
class OneThread {
 public:
  OneThread() : threads_(omp_get_max_threads()) { omp_set_num_threads(1); }
  ~OneThread() { omp_set_num_threads(threads_); }
  OneThread(const OneThread&) = delete;
  OneThread& operator=(const OneThread&) = delete;

 private:
  int threads_;
};

BuiltTree build_python(const std::shared_ptr<Scene>& scene, py::function splitter, const std::string& shape) {
  BuildOptions options;
  options.shape = shape_of(shape);
  // No subtree handed off as a task: the callable is called with the GIL held, from this thread
  // only, on one OpenMP thread.
  options.min_task_fragments = std::numeric_limits<std::size_t>::max();
  PythonSplitter s(std::move(splitter));
  const OneThread one;
  return {build_tree(scene->polygons, s, options), scene};
}

py::object metrics(const BuiltTree& t, std::uint32_t views, std::uint32_t rays, std::uint64_t seed) {
  MetricsSettings settings;
  settings.views = views;
  settings.rays = rays;
  settings.seed = seed;
  nlohmann::json j;
  {
    py::gil_scoped_release release;
    j = to_json(experiments::measure_drawing(t.tree, t.scene->polygons, settings));
  }
  return to_python(j);
}

py::object validate(const BuiltTree& t, int views) {
  ValidationSettings settings;
  settings.views = views;
  nlohmann::json j;
  {
    py::gil_scoped_release release;
    j = to_json(validate_tree(t.tree, settings));
  }
  j["ok"] = j["violations"] == 0;  // every sampled pixel's hits in the traversal's order
  return to_python(j);
}

py::object invariants(const BuiltTree& t) {
  const InvariantReport r = check_tree_invariants(t.tree, t.scene->polygons);
  return to_python({{"violations", r.violations}, {"first_problems", r.first_problems}, {"ok", r.ok()}});
}

py::array_t<std::uint32_t> order(const BuiltTree& t, const std::array<double, 3>& eye, bool back_to_front) {
  return to_array(visibility_order(t.tree, to_vec3(eye), back_to_front ? Order::BackToFront : Order::FrontToBack));
}

py::array_t<std::uint32_t> fragment_sources(const BuiltTree& t) {
  std::vector<std::uint32_t> out(t.tree.fragments.size());
  for (std::size_t i = 0; i < out.size(); ++i) out[i] = t.tree.fragments[i].source;
  return to_array(out);
}

py::object merge(const Scene& a, const Scene& b, const std::string& op, const std::string& heuristic, const py::dict& params,
                 std::uint64_t seed, std::uint64_t points) {
  const Lookup lookup;
  const auto splitter = experiments::per_node_splitter(heuristic, assignments(params), seed);
  SolidCheckSettings settings;
  settings.points = points;
  settings.seed = seed;
  const SetOp set_op = parse_set_op(op);
  nlohmann::json j;
  {
    py::gil_scoped_release release;
    const experiments::SetOperationRun run = experiments::run_set_operation(a, b, set_op, *splitter, settings);
    j = {{"merge", to_json(run.stats)}, {"result", to_json(solid_size(run.result))}, {"check", to_json(run.check)},
         {"a", to_json(solid_size(run.operands.a.solid))}, {"b", to_json(solid_size(run.operands.b.solid))}};
  }
  return to_python(j);
}

py::object run_suite(const std::string& suite_name, int threads, const std::string& journal_dir, bool fresh) {
  const Lookup lookup;
  const suite::Suite suite = suite::find_suite(suite_name);
  sweep::SweepOptions options;
  options.threads = threads;
  options.journal_dir = journal_dir;
  options.fresh = fresh;
  nlohmann::json report;
  {
    py::gil_scoped_release release;
    report = sweep::run_sweep(suite, options);
  }
  return to_python(report);
}

py::list heuristic_list() {
  py::list out;
  for (const HeuristicInfo& h : heuristics()) {
    const PluginIdentity* from = heuristic_plugin(h.name);
    out.append(to_python({{"name", h.name}, {"summary", h.summary}, {"params", specs_to_json(h.params)},
                          {"autopartition", h.autopartition}, {"plugin", from ? from->text() : ""}}));
  }
  return out;
}

py::dict load_plugin(const std::string& path) {
  if (Lookup::running() > 0)
    throw std::runtime_error("load_plugin: a build, merge or suite is running in another thread; load plugins first");
  const PluginIdentity& p = experiments::load_plugin(path);
  py::dict d;
  d["name"] = p.name, d["version"] = p.version, d["hash"] = p.hash, d["path"] = p.path;
  return d;
}

}  // namespace

PYBIND11_MODULE(_core, m) {
  m.doc() = "bspbench: BSP tree heuristics, built, measured and checked (docs/python.md)";
  m.attr("__version__") = BSPBENCH_VERSION_STRING;
  m.attr("revision") = git_revision();
  py::register_exception<UsageError>(m, "UsageError", PyExc_ValueError);
  py::register_exception<InputError>(m, "InputError", PyExc_ValueError);
  py::register_exception<PluginError>(m, "PluginError", PyExc_RuntimeError);

  py::class_<Scene, std::shared_ptr<Scene>>(m, "Scene")
      .def_readonly("name", &Scene::name)
      .def("__len__", [](const Scene& s) { return s.polygons.size(); })
      .def_property_readonly("polygons", [](const Scene& s) {
        py::list out;
        for (const Polygon& p : s.polygons) out.append(polygon_array(p));
        return out;
      }, "each polygon as a (vertices, 3) array")
      .def("info", [](const Scene& s) { return to_python(scene_json(s)); }, "name, parameters, size, hash and bounds")
      .def("__repr__", [](const Scene& s) { return "<bspbench.Scene " + s.name + ", " + std::to_string(s.polygons.size()) + " polygons>"; });

  m.def("scene", &generated, py::arg("name"), py::arg("n") = py::none(), py::arg("seed") = 1, py::arg("params") = py::dict(),
        "a generated scene (bspbench scenes lists them); params as a dict of the generator's parameters");
  m.def("load_mesh", [](const std::string& path) { py::gil_scoped_release r; return read_mesh(path); }, py::arg("path"),
        "a mesh file (OBJ, OFF, PLY, STL) as a scene");
  m.def("from_array", &from_array, py::arg("polygons"), py::arg("name") = "array",
        "a scene from an (m, k, 3) array: m polygons of k vertices, counter-clockwise seen from the front");

  py::class_<BuiltTree>(m, "Tree")
      .def_property_readonly("nodes", [](const BuiltTree& t) { return t.tree.nodes.size(); })
      .def_property_readonly("fragments", [](const BuiltTree& t) { return t.tree.fragments.size(); })
      .def_property_readonly("build_seconds", [](const BuiltTree& t) { return t.tree.stats.build_seconds; })
      .def("metrics", &metrics, py::arg("views") = 8, py::arg("rays") = 1000, py::arg("seed") = 1,
           "the metrics `bspbench build` prints, as a dict")
      .def("validate", &validate, py::arg("views") = 8, "back-to-front orders checked against Embree's ray casts")
      .def("invariants", &invariants, "the tree's structural invariants (validate/tree_invariants.h)")
      .def("order", &order, py::arg("eye"), py::arg("back_to_front") = true, "fragment indices in visibility order")
      .def("fragment_sources", &fragment_sources, "for each fragment, the input polygon it is part of")
      .def("fragment", [](const BuiltTree& t, std::size_t i) {
        if (i >= t.tree.fragments.size()) throw py::index_error("no fragment " + std::to_string(i));
        return polygon_array(t.tree.fragments[i].polygon());
      }, py::arg("index"), "one fragment as a (vertices, 3) array");

  m.def("build", &build, py::arg("scene"), py::arg("heuristic") = "naylor", py::arg("params") = py::dict(),
        py::arg("seed") = 1, py::arg("shape") = "strict", "a tree built by a registered heuristic or search");
  m.def("build_with", &build_python, py::arg("scene"), py::arg("splitter"), py::arg("shape") = "strict",
        "a tree whose planes a Python callable picks (splitter(node) -> fragment id, plane or None)");
  m.def("heuristics", &heuristic_list, "every registered heuristic with its parameters");
  m.def("load_plugin", &load_plugin, py::arg("path"), "loads a plugin (docs/plugins.md) and registers its heuristics");
  m.def("merge", &merge, py::arg("a"), py::arg("b"), py::arg("op") = "union", py::arg("heuristic") = "naylor",
        py::arg("params") = py::dict(), py::arg("seed") = 1, py::arg("points") = 20000,
        "a set operation on two closed solids by merging their trees, proved against CGAL");
  m.def("solid_pair", [](const std::string& pair, std::uint64_t n, std::uint64_t seed) {
    const auto operands = find_solid_pair(pair).operands(n, seed);
    py::gil_scoped_release release;
    return std::pair{make_scene(operands[0].scene, operands[0].params), make_scene(operands[1].scene, operands[1].params)};
  }, py::arg("pair"), py::arg("n") = 200, py::arg("seed") = 1, "two closed solids of a generated pair (bspbench scenes)");
  m.def("run_suite", &run_suite, py::arg("suite"), py::arg("threads") = 0, py::arg("journal_dir") = "results/journal",
        py::arg("fresh") = false, "runs a suite (a built-in's name or a suite file) and returns its report");

  register_node(m);
}

}  // namespace bsp::python
