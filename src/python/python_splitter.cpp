#include "python_splitter.h"

#include <algorithm>
#include <cmath>
#include <string>
#include <variant>
#include <vector>

#include <pybind11/numpy.h>
#include <pybind11/stl.h>

namespace py = pybind11;

namespace bsp::python {

namespace {

// The node a Python splitter is asked about, valid during that call only (then `ctx` is null and
// every access raises).
struct Node {
  const SplitContext* ctx = nullptr;

  const SplitContext& at() const {
    if (!ctx) throw std::runtime_error("a Node is valid only during the splitter's call");
    return *ctx;
  }
  void check_in(std::uint32_t id) const {
    const auto& ids = at().ids;
    if (std::find(ids.begin(), ids.end(), id) == ids.end()) throw py::index_error("fragment " + std::to_string(id) + " is not in the node");
  }
};

py::array_t<std::uint32_t> node_fragments(const Node& n) {
  const auto ids = n.at().ids;
  py::array_t<std::uint32_t> out(static_cast<py::ssize_t>(ids.size()));
  std::copy(ids.begin(), ids.end(), out.mutable_data());
  return out;
}

// (m, 4): each fragment's plane n·x + d = 0, in the order of `fragments`.
py::array_t<double> node_planes(const Node& n) {
  const SplitContext& c = n.at();
  py::array_t<double> out({static_cast<py::ssize_t>(c.ids.size()), py::ssize_t{4}});
  auto w = out.mutable_unchecked<2>();
  for (std::size_t i = 0; i < c.ids.size(); ++i) {
    const Plane& p = c.planes[c.frags.plane(c.ids[i])];
    const auto r = static_cast<py::ssize_t>(i);
    w(r, 0) = p.n.x, w(r, 1) = p.n.y, w(r, 2) = p.n.z, w(r, 3) = p.d;
  }
  return out;
}

py::array_t<double> node_points(const Node& n, std::uint32_t id) {
  n.check_in(id);
  const auto pts = n.at().frags.points(id);
  py::array_t<double> out({static_cast<py::ssize_t>(pts.size()), py::ssize_t{3}});
  auto w = out.mutable_unchecked<2>();
  for (std::size_t i = 0; i < pts.size(); ++i) {
    const auto r = static_cast<py::ssize_t>(i);
    w(r, 0) = pts[i].x, w(r, 1) = pts[i].y, w(r, 2) = pts[i].z;
  }
  return out;
}

// The node's fragments against fragment id's plane: how many lie in front, behind, span it, lie on it.
py::dict node_sides(const Node& n, std::uint32_t id) {
  n.check_in(id);
  const SplitContext& c = n.at();
  const SideCounts s = c.frags.count_sides(c.ids, c.planes[c.frags.plane(id)], c.tol.plane_eps);
  py::dict d;
  d["front"] = s.front, d["back"] = s.back, d["spanning"] = s.spanning, d["coplanar"] = s.coplanar;
  return d;
}

// The callable's answer as a choice, or an error message.
std::variant<SplitChoice, std::string> read_answer(const py::object& answer, const Node& node) {
  if (answer.is_none()) return SplitChoice::none();
  if (py::isinstance<py::int_>(answer)) {
    const auto id = answer.cast<long long>();
    const auto& ids = node.at().ids;
    if (id < 0 || std::find(ids.begin(), ids.end(), static_cast<std::uint32_t>(id)) == ids.end())
      return "the splitter returned fragment " + std::to_string(id) + ", which is not in the node";
    return SplitChoice::of_fragment(static_cast<std::uint32_t>(id));
  }
  const auto plane = py::cast<std::vector<double>>(answer);
  if (plane.size() != 4 || !std::all_of(plane.begin(), plane.end(), [](double x) { return std::isfinite(x); }) ||
      plane[0] * plane[0] + plane[1] * plane[1] + plane[2] * plane[2] == 0)
    return std::string("the splitter returned a plane that is not four finite numbers with a nonzero normal");
  return SplitChoice::free_plane({{plane[0], plane[1], plane[2]}, plane[3]});
}

}  // namespace

PythonSplitter::PythonSplitter(py::function choose) : PythonSplitter(std::move(choose), std::make_shared<Error>()) {}

PythonSplitter::~PythonSplitter() = default;

SplitChoice PythonSplitter::choose(const SplitContext& ctx) {
  if (*error_) return SplitChoice::none();
  Node node{&ctx};
  py::object handle = py::cast(node);
  try {
    const py::object answer = choose_(handle);
    const auto choice = read_answer(answer, node);
    handle.cast<Node&>().ctx = nullptr;
    if (const auto* c = std::get_if<SplitChoice>(&choice)) return *c;
    PyErr_SetString(PyExc_ValueError, std::get<std::string>(choice).c_str());
    throw py::error_already_set();
  } catch (py::error_already_set& e) {
    *error_ = std::move(e);
  } catch (const py::cast_error& e) {
    PyErr_SetString(PyExc_TypeError, (std::string("the splitter returned neither a fragment id, a plane nor None: ") + e.what()).c_str());
    *error_ = py::error_already_set();
  }
  handle.cast<Node&>().ctx = nullptr;
  return SplitChoice::none();
}

std::unique_ptr<Splitter> PythonSplitter::clone() const {
  return std::unique_ptr<Splitter>(new PythonSplitter(choose_, error_));
}

void PythonSplitter::check() const {
  if (*error_) throw **error_;
}

void register_node(py::module_& m) {
  py::class_<Node>(m, "Node", "the node a Python splitter chooses a plane for (valid during that call)")
      .def_property_readonly("fragments", &node_fragments, "the node's fragment ids")
      .def_property_readonly("depth", [](const Node& n) { return n.at().depth; }, "the root has depth 1")
      .def_property_readonly("planes", &node_planes, "(m, 4): each fragment's plane (nx, ny, nz, d), as `fragments`")
      .def("points", &node_points, py::arg("fragment"), "a fragment's vertices, (k, 3)")
      .def("source", [](const Node& n, std::uint32_t id) { n.check_in(id); return n.at().frags.source(id); },
           py::arg("fragment"), "the input polygon the fragment is part of")
      .def("sides", &node_sides, py::arg("fragment"),
           "the node's fragments against this fragment's plane: front, back, spanning, coplanar");
}

}  // namespace bsp::python
