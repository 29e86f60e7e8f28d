// Notation: M the affine map from a node's coordinates to the world (OpenSCAD's multmatrix
// products from the root down), dim(v) the dimension of node v's geometry (0 nothing rendered,
// 2 or 3), "rendered" a node outside every '%' and '*' subtree.
#include "csg/lower.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <filesystem>
#include <optional>

#include "common/errors.h"
#include "csg/openscad_shapes.h"
#include "csg/shapes2d.h"
#include "geometry/tolerance.h"
#include "io/mesh_reader.h"
#include "io/polygon_cleanup.h"

namespace bsp::csg {

namespace {

// A 3x4 affine map, row-major: p' = A p + t.
struct Affine {
  std::array<std::array<double, 4>, 3> m{{{1, 0, 0, 0}, {0, 1, 0, 0}, {0, 0, 1, 0}}};

  Vec3 apply(const Vec3& p) const {
    return {m[0][0] * p.x + m[0][1] * p.y + m[0][2] * p.z + m[0][3],
            m[1][0] * p.x + m[1][1] * p.y + m[1][2] * p.z + m[1][3],
            m[2][0] * p.x + m[2][1] * p.y + m[2][2] * p.z + m[2][3]};
  }
  double det() const {
    return m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1]) - m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0]) +
           m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0]);
  }
  Affine then(const Affine& inner) const {  // this ∘ inner
    Affine r;
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 4; ++j)
        r.m[i][j] = m[i][0] * inner.m[0][j] + m[i][1] * inner.m[1][j] + m[i][2] * inner.m[2][j] + (j == 3 ? m[i][3] : 0);
    return r;
  }
};

bool is(const Node& n, std::initializer_list<std::string_view> names) {
  return std::find(names.begin(), names.end(), n.name) != names.end();
}
bool is_union_like(const Node& n) { return is(n, {"group", "union", "render", "color", "multmatrix"}); }
bool is_container(const Node& n) {
  return is_union_like(n) || is(n, {"difference", "intersection", "intersection_for", "hull"});
}
bool is_primitive3(const Node& n) { return is(n, {"cube", "sphere", "cylinder", "polyhedron", "linear_extrude", "rotate_extrude"}); }
bool is_primitive2(const Node& n) { return is(n, {"square", "circle", "polygon"}); }
bool not_rendered(const Node& n) { return n.modifier == Modifier::Background || n.modifier == Modifier::Disable; }

std::string extension(const std::string& file) {
  std::string e = std::filesystem::path(file).extension().string();
  std::transform(e.begin(), e.end(), e.begin(), [](unsigned char c) { return std::tolower(c); });
  return e;
}

// Reads arguments of one node, naming the node and its line in every complaint.
class Args {
 public:
  Args(const Program& p, std::uint32_t node) : p_(p), n_(p.nodes[node]), node_(node) {}

  [[noreturn]] void fail(const std::string& problem) const {
    throw InputError(p_.path + ":" + std::to_string(n_.line) + ": " + n_.name + ": " + problem);
  }
  double number(std::string_view key, double fallback) const {
    const Value* v = n_.arg(key);
    if (!v || v->type == Value::Type::Undef) return fallback;
    return finite(*v, key);
  }
  bool boolean(std::string_view key, bool fallback) const {
    const Value* v = n_.arg(key);
    if (!v || v->type == Value::Type::Undef) return fallback;
    if (v->type != Value::Type::Bool) fail("argument '" + std::string(key) + "' must be true or false");
    return v->boolean;
  }
  // A number applies to every axis, as in cube(size = 5) and scale = 2.
  std::vector<double> numbers(std::string_view key, std::size_t n, double fallback) const {
    const Value* v = n_.arg(key);
    if (!v || v->type == Value::Type::Undef) return std::vector<double>(n, fallback);
    if (v->type == Value::Type::Number) return std::vector<double>(n, finite(*v, key));
    return vector(*v, key, n);
  }
  std::vector<double> vector(const Value& v, std::string_view key, std::size_t n) const {
    if (v.type != Value::Type::Vector || v.items.size() != n)
      fail("argument '" + std::string(key) + "' must be a vector of " + std::to_string(n) + " numbers");
    std::vector<double> out;
    for (const Value& item : v.items) out.push_back(finite(item, key));
    return out;
  }
  const Value& required(std::string_view key) const {
    const Value* v = n_.arg(key);
    if (!v) fail("argument '" + std::string(key) + "' is missing");
    return *v;
  }
  Resolution resolution() const { return {number("$fn", 0), number("$fs", 2), number("$fa", 12)}; }
  std::uint32_t node() const { return node_; }
  const Node& n() const { return n_; }
  const Program& program() const { return p_; }

 private:
  double finite(const Value& v, std::string_view key) const {
    if (v.type != Value::Type::Number || !std::isfinite(v.number))
      fail("argument '" + std::string(key) + "' must be a finite number");
    return v.number;
  }
  const Program& p_;
  const Node& n_;
  std::uint32_t node_;
};

// OpenSCAD writes the matrix as the first, unnamed argument.
Affine multmatrix(const Args& a) {
  const Value* given = a.n().arg("m") ? a.n().arg("m") : a.n().arg("");
  if (!given) a.fail("the matrix is missing");
  const Value& v = *given;
  if (v.type != Value::Type::Vector || v.items.size() < 3 || v.items.size() > 4) a.fail("'m' must be a 4x4 matrix");
  Affine m;
  for (int i = 0; i < 3; ++i) {
    const std::vector<double> row = a.vector(v.items[i], "m", 4);
    std::copy(row.begin(), row.end(), m.m[i].begin());
  }
  if (v.items.size() == 4) {
    const std::vector<double> last = a.vector(v.items[3], "m", 4);
    if (last != std::vector<double>{0, 0, 0, 1}) a.fail("a projective matrix (last row not 0 0 0 1) is not an affine map");
  }
  return m;
}

bool is_2d_format(const Node& import) {
  const std::string ext = extension(import.arg("file") ? import.arg("file")->text : "");
  return ext == ".dxf" || ext == ".svg";
}

// OpenSCAD refuses these, or evaluates them by means bspbench lacks; one line says which.
[[noreturn]] void refuse(const Args& a) {
  const Node& n = a.n();
  if (is(n, {"text", "surface", "offset", "minkowski", "projection", "resize", "roof", "fill"}))
    a.fail("not supported by bspbench csg (only set operations, transforms, extrusions and hulls of polyhedra)");
  if (n.name == "import" && is_2d_format(n))
    a.fail("import of 2D formats (" + extension(n.arg("file")->text) + ") is not supported by bspbench csg");
  a.fail("unknown node");
}

// dim(v) for every node: primitives by kind, containers by their first rendered child that has
// geometry (OpenSCAD takes the first child's dimension and ignores the others). Nodes are stored
// in pre-order, so children come after their parent and a reverse sweep sees them first.
std::vector<std::uint8_t> dimensions(const Program& p) {
  std::vector<std::uint8_t> dim(p.nodes.size(), 0);
  for (std::size_t i = p.nodes.size(); i-- > 0;) {
    const Node& n = p.nodes[i];
    if (not_rendered(n)) continue;
    if (is_primitive3(n)) dim[i] = 3;
    else if (is_primitive2(n) || is(n, {"text", "offset", "projection"})) dim[i] = 2;
    else if (n.name == "import") dim[i] = is_2d_format(n) ? 2 : 3;
    else if (is(n, {"surface", "minkowski", "resize"})) dim[i] = 3;
    else
      for (std::uint32_t c : n.children)
        if (dim[c] != 0) {
          dim[i] = dim[c];
          break;
        }
  }
  return dim;
}


class Lowering {
 public:
  explicit Lowering(const Program& p) : p_(p), dim_(dimensions(p)), dir_(std::filesystem::path(p.path).parent_path()) {}

  Postfix run() {
    std::vector<std::uint32_t> roots = p_.roots;
    if (const auto root = first_root_modifier()) roots = {*root};
    for (const std::uint32_t r : roots)
      if (dim_[r] == 2)
        throw InputError(p_.path + ": the program has no 3D object (its first top-level object is 2D): bspbench csg evaluates 3D programs");
      else if (dim_[r] == 3)
        break;
    lower_children(roots, Affine{}, StepKind::Union, static_cast<std::uint32_t>(p_.nodes.size()));
    return std::move(out_);
  }

 private:
  // One container being lowered: its children are emitted one by one, then its step.
  struct Frame {
    std::vector<std::uint32_t> children;
    Affine m;
    StepKind op;
    std::uint32_t node;
    std::size_t first_step = 0, first_leaf = 0;  // what the program held when the container opened
    std::size_t next = 0;
    std::uint32_t operands = 0;
  };

  // One 2D container being evaluated: the shapes of its children so far.
  struct Frame2 {
    std::uint32_t node;
    Affine m;
    std::size_t next = 0;
    std::vector<Shape2> operands;
  };

  // The first '!' node outside every '%' and '*' subtree. Nodes are in pre-order, so a forward
  // sweep marks a node's children after the node itself.
  std::optional<std::uint32_t> first_root_modifier() const {
    std::vector<bool> hidden(p_.nodes.size(), false);
    for (std::uint32_t i = 0; i < p_.nodes.size(); ++i) {
      const Node& n = p_.nodes[i];
      hidden[i] = hidden[i] || not_rendered(n);
      if (!hidden[i] && n.modifier == Modifier::Root) return i;
      for (const std::uint32_t c : n.children) hidden[c] = hidden[i];
    }
    return std::nullopt;
  }

  void lower_children(const std::vector<std::uint32_t>& roots, const Affine& m, StepKind op, std::uint32_t node) {
    std::vector<Frame> stack{{roots, m, op, node, out_.steps.size(), out_.leaves.size()}};
    while (!stack.empty()) {
      Frame& f = stack.back();
      if (f.next == f.children.size()) {
        close(f);
        stack.pop_back();
        if (!stack.empty()) ++stack.back().operands;
        continue;
      }
      const std::uint32_t c = f.children[f.next++];
      const Node& n = p_.nodes[c];
      if (not_rendered(n)) {
        ++out_.stats.not_rendered;
        continue;
      }
      if (dim_[c] == 2) {
        // OpenSCAD gives a child of the other dimension no geometry: an empty operand.
        ++out_.stats.ignored_wrong_dimension;
        out_.steps.push_back({StepKind::Empty, 0, c});
        ++f.operands;
        continue;
      }
      if (is_container(n)) {
        const Affine inner = n.name == "multmatrix" ? f.m.then(multmatrix(Args(p_, c))) : f.m;
        stack.push_back({n.children, inner, container_op(n), c, out_.steps.size(), out_.leaves.size()});
        continue;
      }
      emit_primitive(c, f.m);
      ++f.operands;
    }
  }

  static StepKind container_op(const Node& n) {
    if (n.name == "difference") return StepKind::Difference;
    if (is(n, {"intersection", "intersection_for"})) return StepKind::Intersection;
    if (n.name == "hull") return StepKind::Hull;
    return StepKind::Union;
  }

  // A union of one operand is that operand: no step. A container with no operands is empty.
  void close(const Frame& f) {
    if (f.op == StepKind::Hull && only_unions_since(f)) return hull_of_leaves(f);
    if (f.operands == 0) out_.steps.push_back({StepKind::Empty, 0, f.node});
    else if (f.operands > 1 || f.op == StepKind::Hull) out_.steps.push_back({f.op, f.operands, f.node});
  }

  bool only_unions_since(const Frame& f) const {
    return std::all_of(out_.steps.begin() + static_cast<std::ptrdiff_t>(f.first_step), out_.steps.end(), [](const Step& s) {
      return s.kind == StepKind::Leaf || s.kind == StepKind::Empty || s.kind == StepKind::Union;
    });
  }

  // The hull of a union of leaves is the hull of their vertices [OpenSCAD's applyHull takes its
  // children's points the same way]: computed here, once, and made a leaf, so every engine takes the
  // same hull polyhedron (an engine's own hull of snapped or rounded points would differ from it).
  void hull_of_leaves(const Frame& f) {
    std::vector<Vec3> points;
    for (std::size_t i = f.first_leaf; i < out_.leaves.size(); ++i)
      for (const Polygon& p : out_.leaves[i].polygons)
        for (const Vertex& v : p.verts) points.push_back(v.p);
    out_.leaves.resize(f.first_leaf);
    out_.steps.resize(f.first_step);
    emit_mesh(hull3(points), Affine{}, f.node);
  }

  void emit_primitive(std::uint32_t c, const Affine& m) { emit_mesh(named(c, [&] { return primitive(Args(p_, c)); }), m, c); }

  // What `make` throws, prefixed with the file, line and node unless it already names them.
  template <class F>
  auto named(std::uint32_t c, F make) -> decltype(make()) {
    try {
      return make();
    } catch (const InputError& e) {
      if (std::string_view(e.what()).rfind(p_.path + ":", 0) == 0) throw;
      Args(p_, c).fail(e.what());
    }
  }

  void emit_mesh(const Mesh& mesh, const Affine& m, std::uint32_t c) {
    if (mesh.faces.empty() || std::abs(m.det()) == 0.0) {
      out_.steps.push_back({StepKind::Empty, 0, c});
      return;
    }
    Leaf leaf{to_polygons(mesh, m), c};
    if (leaf.polygons.empty()) {
      out_.steps.push_back({StepKind::Empty, 0, c});
      return;
    }
    out_.steps.push_back({StepKind::Leaf, static_cast<std::uint32_t>(out_.leaves.size()), c});
    out_.leaves.push_back(std::move(leaf));
  }

  Mesh primitive(const Args& a) {
    const Node& n = a.n();
    if (n.name == "cube") {
      const std::vector<double> s = a.numbers("size", 3, 1);
      return cube({s[0], s[1], s[2]}, a.boolean("center", false));
    }
    if (n.name == "sphere") return sphere(a.number("r", 1), a.resolution());
    if (n.name == "cylinder") {
      const double r = a.number("r", 1);
      return cylinder(a.number("h", 1), a.number("r1", r), a.number("r2", r), a.boolean("center", false), a.resolution());
    }
    if (n.name == "polyhedron") return polyhedron(a);
    if (n.name == "linear_extrude") return extrude(a, true);
    if (n.name == "rotate_extrude") return extrude(a, false);
    if (n.name == "import") return import_mesh(a);
    refuse(a);  // throws
    return {};
  }

  static Mesh polyhedron(const Args& a) {
    Mesh mesh;
    const Value& points = a.required("points");
    if (points.type != Value::Type::Vector) a.fail("'points' must be a vector of points");
    for (const Value& p : points.items) {
      const std::vector<double> xyz = a.vector(p, "points", 3);
      mesh.points.push_back({xyz[0], xyz[1], xyz[2]});
    }
    const Value* faces = a.n().arg("faces");
    if (!faces || faces->type == Value::Type::Undef) faces = a.n().arg("triangles");
    if (!faces || faces->type != Value::Type::Vector) a.fail("'faces' must be a vector of faces");
    for (const Value& f : faces->items) {
      if (f.type != Value::Type::Vector) a.fail("each face must be a vector of point indices");
      std::vector<std::uint32_t> face;
      for (const Value& i : f.items) {
        if (i.type != Value::Type::Number || i.number < 0 || i.number >= static_cast<double>(mesh.points.size()) ||
            i.number != std::floor(i.number))
          a.fail("a face refers to a point that does not exist (there are " + std::to_string(mesh.points.size()) + ")");
        face.push_back(static_cast<std::uint32_t>(i.number));
      }
      // OpenSCAD lists a polyhedron's faces clockwise seen from outside; Mesh is counter-clockwise.
      std::reverse(face.begin(), face.end());
      if (face.size() >= 3) mesh.faces.push_back(std::move(face));
    }
    return mesh;
  }

  Mesh import_mesh(const Args& a) {
    const Value& file = a.required("file");
    if (file.type != Value::Type::String) a.fail("'file' must be a string");
    const std::string ext = extension(file.text);
    if (is_2d_format(a.n())) refuse(a);
    if (ext != ".stl" && ext != ".off") a.fail("import of '" + ext + "' files is not supported (STL and OFF are)");
    const std::filesystem::path path = std::filesystem::path(file.text).is_absolute() ? std::filesystem::path(file.text) : dir_ / file.text;
    const Scene scene = read_mesh(path.string());
    Mesh mesh;
    for (const Polygon& poly : scene.polygons) {
      std::vector<std::uint32_t> face;
      for (const Vertex& v : poly.verts) {
        face.push_back(static_cast<std::uint32_t>(mesh.points.size()));
        mesh.points.push_back(v.p);
      }
      mesh.faces.push_back(std::move(face));
    }
    return mesh;
  }

  Mesh extrude(const Args& a, bool linear) {
    const Shape2 shape = lower_2d(a.node());
    if (shape.rings.empty()) return {};
    if (linear) {
      LinearExtrude p;
      p.height = a.number("height", 100);
      p.center = a.boolean("center", false);
      p.twist = a.number("twist", 0);
      const double slices = a.number("slices", 0);  // below 1: OpenSCAD's default rule
      if (slices > kMaxFragments) a.fail("argument 'slices' is over " + std::to_string(kMaxFragments));
      p.slices = slices >= 1 ? static_cast<int>(slices) : 0;
      const std::vector<double> s = a.numbers("scale", 2, 1);
      p.scale = {s[0], s[1]};
      p.res = a.resolution();
      return linear_extrude(shape, Triangulator(triangulate), p);
    }
    RotateExtrude p;
    p.angle = a.number("angle", 360);
    p.res = a.resolution();
    return rotate_extrude(shape, triangulate(shape), p);
  }

  // The 2D subtree under an extrusion, evaluated bottom-up with a stack of open containers.
  Shape2 lower_2d(std::uint32_t extrusion) {
    std::vector<Frame2> stack{{extrusion, Affine{}, 0, {}}};
    for (;;) {
      Frame2& f = stack.back();
      const Node& n = p_.nodes[f.node];
      if (f.next == n.children.size()) {
        Shape2 result = combine_2d(f);
        stack.pop_back();
        if (stack.empty()) return result;
        stack.back().operands.push_back(std::move(result));
        continue;
      }
      const std::uint32_t c = n.children[f.next++];
      const Node& child = p_.nodes[c];
      if (not_rendered(child)) {
        ++out_.stats.not_rendered;
      } else if (dim_[c] == 3) {
        ++out_.stats.ignored_wrong_dimension;  // an empty operand, as OpenSCAD makes it
        f.operands.emplace_back();
      } else if (is_container(child)) {
        stack.push_back({c, child.name == "multmatrix" ? f.m.then(multmatrix(Args(p_, c))) : f.m, 0, {}});
      } else {
        f.operands.push_back(transform_2d(named(c, [&] { return primitive_2d(Args(p_, c)); }), f.m));
      }
    }
  }

  Shape2 combine_2d(Frame2& f) {
    const Node& n = p_.nodes[f.node];
    if (f.operands.empty()) return {};
    if (n.name == "hull") return hull2(f.operands);
    if (f.operands.size() == 1) return std::move(f.operands[0]);
    const Op2 op = n.name == "difference"                                   ? Op2::Difference
                   : is(n, {"intersection", "intersection_for"}) ? Op2::Intersection
                                                                            : Op2::Union;
    return boolean2(op, f.operands);
  }

  Shape2 primitive_2d(const Args& a) {
    const Node& n = a.n();
    if (n.name == "square") {
      const std::vector<double> s = a.numbers("size", 2, 1);
      return square({s[0], s[1]}, a.boolean("center", false));
    }
    if (n.name == "circle") return circle(a.number("r", 1), a.resolution());
    if (n.name == "polygon") return polygon_2d(a);
    refuse(a);
    return {};
  }

  static Shape2 polygon_2d(const Args& a) {
    std::vector<Vec2> points;
    const Value& pts = a.required("points");
    if (pts.type == Value::Type::Undef) return {};  // OpenSCAD: an empty polygon, with a warning
    if (pts.type != Value::Type::Vector) a.fail("'points' must be a vector of 2D points");
    for (const Value& p : pts.items) {
      const std::vector<double> xy = a.vector(p, "points", 2);
      points.push_back({xy[0], xy[1]});
    }
    std::vector<std::vector<std::size_t>> paths;
    if (const Value* v = a.n().arg("paths"); v && v->type == Value::Type::Vector) {
      for (const Value& path : v->items) {
        if (path.type != Value::Type::Vector) a.fail("each path must be a vector of point indices");
        std::vector<std::size_t> indices;
        for (const Value& i : path.items) {
          if (i.type != Value::Type::Number || i.number < 0 || i.number >= static_cast<double>(points.size()) ||
              i.number != std::floor(i.number))
            a.fail("a path refers to a point that does not exist (there are " + std::to_string(points.size()) + ")");
          indices.push_back(static_cast<std::size_t>(i.number));
        }
        paths.push_back(std::move(indices));
      }
    }
    return sanitize2(polygon(points, paths));  // OpenSCAD fills a polygon's paths even-odd
  }

  // The plane part of M (OpenSCAD drops z when it maps a 2D object); after a mirroring map the
  // rings are sanitized again, as OpenSCAD does, so outer rings stay counter-clockwise.
  static Shape2 transform_2d(Shape2 shape, const Affine& m) {
    const double det = m.m[0][0] * m.m[1][1] - m.m[0][1] * m.m[1][0];
    for (Ring& ring : shape.rings)
      for (Vec2& p : ring.points)
        p = {m.m[0][0] * p.x + m.m[0][1] * p.y + m.m[0][3], m.m[1][0] * p.x + m.m[1][1] * p.y + m.m[1][3]};
    if (det == 0) return {};
    return det < 0 ? sanitize2(shape) : shape;
  }

  // The mesh mapped by M as cleaned convex polygons facing outwards: a mirroring M reverses every
  // face, and faces that still enclose a negative volume (a polyhedron listed the other way round)
  // are reversed and counted.
  std::vector<Polygon> to_polygons(const Mesh& mesh, const Affine& m) {
    Box box;
    std::vector<Vec3> points;
    for (const Vec3& p : mesh.points) {
      points.push_back(m.apply(p));
      box.add(points.back());
    }
    const double eps = Tolerance::for_extent(box.diagonal()).plane_eps;
    const bool mirrored = m.det() < 0;
    std::vector<Polygon> out;
    SceneLoadStats load;
    for (const auto& face : mesh.faces) {
      Polygon poly;
      for (std::uint32_t i : face) poly.verts.push_back({points[i], 0, 0});
      if (mirrored) std::reverse(poly.verts.begin(), poly.verts.end());
      append_clean_polygon(std::move(poly), eps, out, load);
    }
    out_.stats.cleaned_faces += load.triangulated + load.dropped_degenerate + load.dropped_duplicate_vertex;
    if (enclosed_volume(out) < 0) {
      ++out_.stats.flipped_leaves;
      for (Polygon& p : out) std::reverse(p.verts.begin(), p.verts.end());
    }
    for (std::uint32_t i = 0; i < out.size(); ++i) out[i].source = i;
    return out;
  }

  const Program& p_;
  std::vector<std::uint8_t> dim_;
  std::filesystem::path dir_;
  Postfix out_;
};

}  // namespace

Postfix lower(const Program& program) { return Lowering(program).run(); }

std::vector<std::vector<Polygon>> Postfix::leaf_meshes() const {
  std::vector<std::vector<Polygon>> out;
  for (const Leaf& leaf : leaves) out.push_back(leaf.polygons);
  return out;
}

std::string describe(const Program& program, std::uint32_t node) {
  if (node >= program.nodes.size()) return "program";
  return program.nodes[node].name + " (line " + std::to_string(program.nodes[node].line) + ")";
}

}  // namespace bsp::csg
