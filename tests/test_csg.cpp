// bspbench csg: OpenSCAD's CSG format parsed, lowered to set programs, evaluated by merging solid
// trees and proved against CGAL; and every example model OpenSCAD ships, evaluated or refused.
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>

#include "cli_runner.h"
#include "common/errors.h"
#include "csg/lower.h"
#include "csg/program.h"
#include "experiments/csg/evaluate.h"
#include "split/registry.h"

namespace bsp {
namespace {

using csg::Modifier;
using csg::Value;

csg::Postfix lowered(const std::string& text) { return csg::lower(csg::parse_program(text, "t.csg")); }

std::string error_of(const std::string& text) {
  try {
    lowered(text);
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

TEST(CsgProgram, ReadsNestedBlocksArgumentsAndModifiers) {
  const csg::Program p = csg::parse_program(
      "group() {\n  multmatrix([[1, 0, 0, 2], [0, 1, 0, 0], [0, 0, 1, 0], [0, 0, 0, 1]]) {\n"
      "    %cube(size = [1, 2, 3], center = true);\n    #sphere($fn = 8, r = 1e-1);\n  }\n}\n"
      "/* a comment */ polyhedron(points = [], faces = [], convexity = 1); // another\n"
      "import(file = \"a \\\"b\\\".stl\", layer = \"\", origin = [0, 0], scale = 1, t = undef, u = -inf);\n",
      "t.csg");
  ASSERT_EQ(p.roots.size(), 3u);
  const csg::Node& mm = p.nodes[p.nodes[p.roots[0]].children[0]];
  EXPECT_EQ(mm.name, "multmatrix");
  EXPECT_EQ(mm.line, 2u);
  ASSERT_EQ(mm.children.size(), 2u);
  const csg::Node& cube = p.nodes[mm.children[0]];
  EXPECT_EQ(cube.modifier, Modifier::Background);
  EXPECT_EQ(cube.line, 3u);
  ASSERT_EQ(cube.arg("size")->items.size(), 3u);
  EXPECT_EQ(cube.arg("size")->items[2].number, 3);
  EXPECT_TRUE(cube.arg("center")->boolean);
  const csg::Node& sphere = p.nodes[mm.children[1]];
  EXPECT_EQ(sphere.modifier, Modifier::Highlight);
  EXPECT_DOUBLE_EQ(sphere.arg("r")->number, 0.1);
  EXPECT_EQ(sphere.arg("$fn")->number, 8);
  const csg::Node& import = p.nodes[p.roots[2]];
  EXPECT_EQ(import.line, 8u);
  EXPECT_EQ(import.arg("file")->text, "a \"b\".stl");
  EXPECT_EQ(import.arg("t")->type, Value::Type::Undef);
  EXPECT_TRUE(std::isinf(import.arg("u")->number));
}

TEST(CsgProgram, MalformedTextNamesTheFileAndLine) {
  const auto message = [](const std::string& text) {
    try {
      csg::parse_program(text, "bad.csg");
    } catch (const InputError& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  EXPECT_EQ(message("cube(size = [1, 2);"), "bad.csg:1: expected ']' to close a vector, found ')'");
  EXPECT_EQ(message("group() {\n cube();\n"), "bad.csg:3: 'group' block not closed");
  EXPECT_EQ(message("cube(size = 1)\nsphere();"), "bad.csg:2: expected ';' or '{' after 'cube(...)', found 's'");
  EXPECT_EQ(message("}"), "bad.csg:1: '}' closes no block");
  EXPECT_EQ(message("cube(size = 1 + 2);"), "bad.csg:1: expected ')' to close the arguments of 'cube', found '+'");
  EXPECT_EQ(message("cube(size = x);"), "bad.csg:1: expected a literal value, found 'x' (the CSG format holds no expressions)");
  EXPECT_EQ(message("cube(size = 1.2.3);"), "bad.csg:1: malformed number '1.2.3'");
  std::string deep = "cube(size = ";
  for (int i = 0; i <= csg::kMaxValueDepth; ++i) deep += "[";
  EXPECT_EQ(message(deep), "bad.csg:1: vectors nested deeper than 64");
}

// A union that nests as deep as the input must not recurse: 100000 levels of group().
TEST(CsgProgram, DeepNestingNeedsNoCallStack) {
  std::string text;
  constexpr int kDepth = 100000;
  for (int i = 0; i < kDepth; ++i) text += "group() {\n";
  text += "cube(size = 1);\n";
  for (int i = 0; i < kDepth; ++i) text += "}\n";
  const csg::Postfix p = lowered(text);
  ASSERT_EQ(p.leaves.size(), 1u);
  EXPECT_EQ(p.steps.size(), 1u);  // a union of one operand is that operand
}

TEST(CsgLower, TransformsReachTheLeavesAndMirroringKeepsFacesOutward) {
  const csg::Postfix p = lowered(
      "multmatrix([[-1, 0, 0, 5], [0, 1, 0, 0], [0, 0, 1, 0], [0, 0, 0, 1]]) { cube(size = [1, 2, 3]); }");
  ASSERT_EQ(p.leaves.size(), 1u);
  Box box;
  double volume = 0;
  for (const Polygon& poly : p.leaves[0].polygons) {
    for (const Vertex& v : poly.verts) box.add(v.p);
    for (std::size_t i = 1; i + 1 < poly.verts.size(); ++i)
      volume += dot(poly.verts[0].p, cross(poly.verts[i].p, poly.verts[i + 1].p)) / 6;
  }
  EXPECT_EQ(box.lo.x, 4);
  EXPECT_EQ(box.hi.x, 5);
  EXPECT_EQ(box.hi.z, 3);
  EXPECT_NEAR(volume, 6, 1e-12);  // outward: positive
  EXPECT_EQ(p.stats.flipped_leaves, 0u);
}

TEST(CsgLower, OpenScadSemanticsOfEmptyHiddenAndWrongDimensionChildren) {
  // A difference whose first child is empty is empty; '%' and '*' are not rendered; a 2D child of
  // a 3D union is ignored and counted.
  const csg::Postfix p = lowered(
      "difference() { group() { } cube(size = 1); }\n%cube(size = 2);\n*cube(size = 3);\n"
      "union() { square(size = [1, 1]); sphere(r = 1); }\n");
  EXPECT_EQ(p.stats.not_rendered, 2u);
  EXPECT_EQ(p.stats.ignored_wrong_dimension, 1u);  // the union is 2D, as its first child is: an empty operand
  std::vector<StepKind> kinds;
  for (const Step& s : p.steps) kinds.push_back(s.kind);
  EXPECT_EQ(kinds, (std::vector<StepKind>{StepKind::Empty, StepKind::Leaf, StepKind::Difference, StepKind::Empty,
                                          StepKind::Union}));
  // OpenSCAD renders intersection(){cube(10); square(5);} empty: the square is an empty operand.
  const csg::Postfix mixed = lowered("intersection() { cube(size = 10); square(size = [5, 5]); }");
  ASSERT_EQ(mixed.steps.size(), 3u);
  EXPECT_EQ(mixed.steps[1].kind, StepKind::Empty);
  EXPECT_EQ(mixed.steps[2].kind, StepKind::Intersection);
  // Modifiers combine: a node both highlighted and disabled is dropped; a '!' inside a '%' subtree is
  // not the root.
  EXPECT_EQ(lowered("#*cube(size = 1);\nsphere(r = 1);").leaves.size(), 1u);
  const csg::Postfix rooted = lowered("%group() { !cube(size = 1); }\nsphere(r = 1);\ncylinder(h = 1, r = 1);");
  EXPECT_EQ(rooted.leaves.size(), 2u);
  EXPECT_EQ(error_of("square(size = 1);\ncube(size = 1);"),
            "t.csg: the program has no 3D object (its first top-level object is 2D): bspbench csg evaluates 3D programs");
}

TEST(CsgLower, RefusedNodesNameTheFileLineAndNode) {
  EXPECT_EQ(error_of("linear_extrude(height = 1) {\n  text(text = \"a\", size = 10);\n}"),
            "t.csg:2: text: not supported by bspbench csg (only set operations, transforms, extrusions and hulls of polyhedra)");
  EXPECT_EQ(error_of("linear_extrude(height = 1) {\n offset(r = 1) { square(size = 1); }\n}").substr(0, 14), "t.csg:2: offse");
  EXPECT_EQ(error_of("minkowski() { cube(size = 1); sphere(r = 1); }").substr(0, 19), "t.csg:1: minkowski:");
  EXPECT_EQ(error_of("linear_extrude(height = 1) { import(file = \"a.dxf\"); }"),
            "t.csg:1: import: import of 2D formats (.dxf) is not supported by bspbench csg");
  EXPECT_EQ(error_of("linear_extrude(height = 1) { import(file = \"a.svg\"); }"),
            "t.csg:1: import: import of 2D formats (.svg) is not supported by bspbench csg");
  EXPECT_EQ(error_of("cube(size = 1);\nimport(file = \"missing.stl\");"), "t.csg:2: import: missing.stl: no such file");
  EXPECT_EQ(error_of("frobnicate();"), "t.csg:1: frobnicate: unknown node");
  EXPECT_EQ(error_of("cube(size = [1, 2]);"), "t.csg:1: cube: argument 'size' must be a vector of 3 numbers");
  EXPECT_EQ(error_of("sphere(r = nan);"), "t.csg:1: sphere: argument 'r' must be a finite number");
  EXPECT_EQ(error_of("polyhedron(points = [[0, 0, 0]], faces = [[0, 1, 2]]);"),
            "t.csg:1: polyhedron: a face refers to a point that does not exist (there are 1)");
  // Bounded memory: an object of too many faces, or too many slices, is refused before it is made.
  EXPECT_EQ(error_of("sphere($fn = 8000, r = 1);"), "t.csg:1: sphere: the object would have 32000002 faces, over 16777216");
  EXPECT_EQ(error_of("linear_extrude(height = 1, slices = 1e10) { square(size = 1); }"),
            "t.csg:1: linear_extrude: argument 'slices' is over 4194304");
  // Refused nodes that are not rendered are not refused.
  EXPECT_EQ(error_of("%text(text = \"a\");\ncube(size = 1);"), "");
}

// A program evaluated by merges against volumes known in closed form, in both kernels.
TEST(CsgEvaluate, ProgramsOfBoxesHaveTheirClosedFormVolumes) {
  const std::string text =
      "difference() {\n  cube(size = [4, 4, 4]);\n  cube(size = [1, 1, 1]);\n"
      "  multmatrix([[1, 0, 0, 3], [0, 1, 0, 3], [0, 0, 1, 3], [0, 0, 0, 1]]) { cube(size = [2, 2, 2]); }\n}\n"
      "multmatrix([[1, 0, 0, 10], [0, 1, 0, 0], [0, 0, 1, 0], [0, 0, 0, 1]]) {\n"
      "  intersection() { cube(size = [2, 2, 2]); multmatrix([[1, 0, 0, 1], [0, 1, 0, 1], [0, 0, 1, 1], [0, 0, 0, 1]]) { cube(size = [2, 2, 2]); } }\n}\n";
  const csg::Program program = csg::parse_program(text, "boxes.csg");
  const csg::Postfix postfix = csg::lower(program);
  for (const Kernel kernel : {Kernel::Exact, Kernel::Float}) {
    for (const char* heuristic : {"first", "octree"}) {
      SCOPED_TRACE(std::string(kernel_name(kernel)) + " " + heuristic);
      const auto splitter = make_splitter(heuristic, {}, 1);
      experiments::CsgSettings settings;
      settings.kernel = kernel;
      settings.check.points = 2000;
      const experiments::CsgEvaluation e = experiments::evaluate_program(program, postfix, *splitter, settings);
      EXPECT_NEAR(e.check.volume, 64 - 1 - 1 + 1, 1e-9);
      EXPECT_TRUE(e.check.ok()) << to_json(e.check).dump();
      EXPECT_EQ(e.check.mismatches, 0u);
      EXPECT_GT(e.check.compared, 1000u);
      EXPECT_EQ(e.steps.size(), 3u);  // the difference, the intersection, the top-level union
      EXPECT_EQ(e.leaves.size(), 5u);
    }
  }
}

// The settings of the proof tests below: one kernel, 2000 points.
experiments::CsgSettings proof_settings(Kernel kernel) {
  experiments::CsgSettings settings;
  settings.kernel = kernel;
  settings.check.points = 2000;
  return settings;
}

// A hull of a set operation (not of leaves) is proved in both kernels: the truth and CGAL's volume
// take the hull the evaluation built, as they take leaves.
TEST(CsgEvaluate, HullOfADifferenceIsProvedInBothKernels) {
  const csg::Program program = csg::parse_program(
      "hull() { difference() { cube(size = [4, 4, 4], center = true); sphere($fn = 16, r = 2.5); } }", "hull.csg");
  const csg::Postfix postfix = csg::lower(program);
  ASSERT_EQ(postfix.steps.back().kind, StepKind::Hull);
  for (const Kernel kernel : {Kernel::Exact, Kernel::Float}) {
    SCOPED_TRACE(kernel_name(kernel));
    const auto splitter = make_splitter("octree", {}, 1);
    experiments::CsgSettings settings = proof_settings(kernel);
    const experiments::CsgEvaluation e = experiments::evaluate_program(program, postfix, *splitter, settings);
    EXPECT_TRUE(e.check.ok()) << to_json(e.check).dump();
    EXPECT_NEAR(e.check.volume, 64, 1e-6);  // the corners stay: the hull is the cube (snapped, in the exact kernel)
  }
}

// The proof must catch a wrong program: evaluating a union where the program says difference.
TEST(CsgEvaluate, PlantedWrongOperationIsCaughtByTheProof) {
  const csg::Program program = csg::parse_program(
      "difference() { cube(size = [4, 4, 4]); sphere($fn = 12, r = 2); }", "planted.csg");
  csg::Postfix postfix = csg::lower(program);
  const csg::Postfix good = postfix;
  for (Step& s : postfix.steps)
    if (s.kind == StepKind::Difference) s.kind = StepKind::Union;
  for (const Kernel kernel : {Kernel::Exact, Kernel::Float}) {
    SCOPED_TRACE(kernel_name(kernel));
    const auto splitter = make_splitter("octree", {}, 1);
    experiments::CsgSettings settings = proof_settings(kernel);
    const experiments::CsgEvaluation right = experiments::evaluate_program(program, good, *splitter, settings);
    EXPECT_TRUE(right.check.ok()) << to_json(right.check).dump();
    settings.truth = &good;  // the planted program's result proved against the true program
    const experiments::CsgEvaluation planted = experiments::evaluate_program(program, postfix, *splitter, settings);
    EXPECT_FALSE(planted.check.ok());
    EXPECT_GT(planted.check.mismatches, 100u);
    EXPECT_FALSE(planted.check.volume_ok());
  }
}

// The csg kind in a sweep: ours proved, CGAL's step-by-step volume equal to ours, the run's command
// repeating its merge cost, and a peer past its timeout recorded as timed out, not failed.
TEST(CsgSweep, RunsProveMatchTheirPeersAndRecordATimedOutPeer) {
  const auto dir = testing::fresh_test_dir("csg_sweep");
  std::ofstream(dir / "csg.json") << R"({"name": "csg-test", "csg": [
      {"programs": ["drilled-plate:k=4", "sphere-union:k=3"], "engines": ["bspbench", "cgal", "manifold"],
       "heuristics": ["octree", "first"], "kernels": ["exact", "float"], "points": 500},
      {"programs": ["drilled-plate:k=150"], "engines": ["cgal"], "peer_timeout": 0.05}]})";
  const testing::CliResult r = testing::run_bspbench(
      "sweep --suite '" + (dir / "csg.json").string() + "' --out '" + (dir / "r.json").string() + "' --journal-dir '" +
          (dir / "j").string() + "' --threads 1",
      dir);
  ASSERT_EQ(r.code, 0) << r.err;
  const auto report = nlohmann::json::parse(testing::slurp(dir / "r.json"));
  EXPECT_TRUE(report["failures"].empty()) << report["failures"].dump();
  std::map<std::string, double> cgal_volume;
  std::size_t ours = 0, timed_out = 0;
  for (const auto& run : report["runs"]) {
    const auto& id = run["id"];
    if (id["engine"] == "cgal" && run["validation"]["status"] == "ok") cgal_volume[id["program"]] = run["metrics"]["volume"];
    if (id["engine"] == "cgal" && id["program"] == "drilled-plate:k=150") {
      EXPECT_EQ(run["validation"]["status"], "timeout");
      ++timed_out;
    }
    if (id["engine"] == "manifold") {
      EXPECT_TRUE(run["validation"]["status"] == "ok" || run["validation"]["status"] == "missing");
    }
  }
  for (const auto& run : report["runs"]) {
    const auto& id = run["id"];
    if (id["engine"] != "bspbench") continue;
    ++ours;
    SCOPED_TRACE(id["command"].get<std::string>());
    EXPECT_EQ(run["validation"]["violations"], 0);
    EXPECT_EQ(run["invariants"]["violations"], 0);
    EXPECT_NEAR(run["metrics"]["volume"].get<double>(), cgal_volume.at(id["program"]), 1e-9 * cgal_volume.at(id["program"]));
    if (id["kernel"] != "exact" || id["heuristic"] != "octree") continue;
    const std::string command = id["command"];
    const testing::CliResult again = testing::run_bspbench(command.substr(9) + " --json", dir);
    ASSERT_EQ(again.code, 0) << again.err;
    const auto out = nlohmann::json::parse(again.out);
    EXPECT_EQ(out["result"]["nodes"], run["metrics"]["result_nodes"]);
    EXPECT_EQ(out["check"]["volume"], run["metrics"]["volume"]);
  }
  EXPECT_EQ(ours, 8u);  // 2 programs x 2 heuristics x 2 kernels
  EXPECT_EQ(timed_out, 1u);
  std::filesystem::remove_all(dir);
}

TEST(CsgSweep, BadBlocksAreOneLineErrors) {
  const auto dir = testing::fresh_test_dir("csg_bad");
  const std::vector<std::pair<std::string, std::string>> cases = {
      {R"({"programs": ["drilled-plate"]})", "needs its size: drilled-plate:k=K"},
      {R"({"programs": ["cube-union:k=3"]})", "unknown csg program 'cube-union'"},
      {R"({"programs": ["drilled-plate:k=3"], "engines": ["blender"]})", "unknown engine 'blender'"},
      {R"({"programs": ["drilled-plate:k=3"], "peer_timeout": 0})", "peer_timeout"},
      {R"({"programs": []})", "name at least one program"}};
  for (const auto& [block, message] : cases) {
    std::ofstream(dir / "s.json") << R"({"name": "bad", "csg": [)" + block + "]}";
    const testing::CliResult r = testing::run_bspbench("sweep --suite '" + (dir / "s.json").string() + "' --out '" + (dir / "r.json").string() + "'", dir);
    EXPECT_EQ(r.code, 2) << block;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
    EXPECT_NE(r.err.find(message), std::string::npos) << r.err;
  }
  std::filesystem::remove_all(dir);
}

// The examples OpenSCAD 2021.01 ships (Debian's openscad, /usr/share/openscad/examples), each
// exported to CSG by OpenSCAD itself: the 3D models without refused nodes evaluate and prove; every
// other one is refused with one line naming the node that bspbench does not evaluate, or saying the
// model is 2D. One test per model, so ctest spreads them over its workers.
const std::filesystem::path kExamples = "/usr/share/openscad/examples";

const std::vector<std::string> kEvaluated = {
    "CSG-modules", "CSG",        "animation",  "assert",     "candleStand", "echo",       "example001",
    "example002",  "example003", "example004", "example005", "example006",  "example011", "example012",
    "example014",  "example016", "example017", "example018", "example019",  "example020", "example022",
    "example023",  "example024", "functions",  "linear_extrude", "logo"};
// The refused ones with what their one line names: the first refused node, or the 2D model.
const std::map<std::string, std::string> kRefused = {
    {"GEB", "offset"},          {"LetterBlock", "text"},      {"children", "text"},
    {"children_indexed", "text"}, {"example007", "import of 2D formats (.dxf)"},
    {"example008", "import of 2D formats (.dxf)"}, {"example009", "import of 2D formats (.dxf)"},
    {"example010", "surface"},  {"example013", "import of 2D formats (.dxf)"}, {"example015", "no 3D object"},
    {"example021", "projection"}, {"logo_and_text", "text"}, {"offset", "offset"},
    {"polygon_areas", "no 3D object"}, {"projection", "projection"}, {"recursion", "no 3D object"},
    {"rotate_extrude", "text"}, {"sign", "text"},         {"surface_image", "projection"},
    {"text_on_cube", "text"},   {"module_recursion", "no 3D object"}, {"list_comprehensions", "no 3D object"}};

bool have_openscad() {
  return std::filesystem::exists(kExamples) && std::system("openscad --version > /dev/null 2>&1") == 0;
}

std::vector<std::string> all_example_names() {
  std::vector<std::string> out = kEvaluated;
  for (const auto& [name, reason] : kRefused) out.push_back(name);
  std::sort(out.begin(), out.end());
  return out;
}

TEST(CsgExamples, TheListsNameEveryModelOpenScadShips) {
  if (!have_openscad()) GTEST_SKIP() << "Debian's openscad is not installed (.ci/setup installs it)";
  std::vector<std::string> shipped;
  for (const auto& entry : std::filesystem::recursive_directory_iterator(kExamples))
    if (entry.path().extension() == ".scad") shipped.push_back(entry.path().stem().string());
  std::sort(shipped.begin(), shipped.end());
  EXPECT_EQ(shipped, all_example_names());
  EXPECT_EQ(kEvaluated.size(), 26u);
}

class CsgExample : public ::testing::TestWithParam<std::string> {};

// The example's folder copied (imports are relative to it), the model exported by openscad.
std::filesystem::path exported(const std::string& name, const std::filesystem::path& dir) {
  for (const auto& entry : std::filesystem::recursive_directory_iterator(kExamples)) {
    if (entry.path().stem() != name || entry.path().extension() != ".scad") continue;
    std::filesystem::copy(entry.path().parent_path(), dir, std::filesystem::copy_options::recursive);
    const auto scad = dir / entry.path().filename(), csg_file = dir / (name + ".csg");
    const std::string cmd = "cd '" + dir.string() + "' && openscad -o '" + csg_file.string() + "' '" + scad.string() +
                            "' > /dev/null 2>&1";
    if (std::system(cmd.c_str()) != 0) return {};
    return csg_file;
  }
  return {};
}

TEST_P(CsgExample, EvaluatesAndProvesOrIsRefusedWithItsReason) {
  if (!have_openscad()) GTEST_SKIP() << "Debian's openscad is not installed (.ci/setup installs it)";
  const std::string name = GetParam();
  const auto dir = testing::fresh_test_dir("csg_example");
  const auto csg_file = exported(name, dir / "model");
  ASSERT_FALSE(csg_file.empty()) << "openscad could not export " << name;
  const testing::CliResult r = testing::run_bspbench("csg '" + csg_file.string() + "' --points 500 --json", dir);
  if (kRefused.count(name) == 0) {
    ASSERT_EQ(r.code, 0) << r.err;
    const nlohmann::json check = nlohmann::json::parse(r.out)["check"];
    EXPECT_TRUE(check["ok"].get<bool>()) << "mismatches " << check["mismatches"] << ", border edges " << check["border_edges"]
                                          << ", volume " << check["volume"] << " against " << check["corefine_volume"]
                                          << " (" << check["reference"] << ") " << check["corefine_error"];
    EXPECT_EQ(check["mismatches"], 0);
    EXPECT_EQ(check["border_edges"], 0);
    // A program of nothing (echo; example023, whose polygons OpenSCAD exports without points) has no
    // leaf to draw points near; every other one is compared.
    if (name != "echo" && name != "example023") {
      EXPECT_GT(check["compared"].get<int>(), 0);
    }
  } else {
    EXPECT_EQ(r.code, 2) << r.out.substr(0, 200);
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
    EXPECT_NE(r.err.find(csg_file.string()), std::string::npos) << r.err;
    EXPECT_NE(r.err.find(kRefused.at(name)), std::string::npos) << r.err;
  }
  std::filesystem::remove_all(dir);
}

// Test names allow letters, digits and '_' only.
std::string example_test_name(const ::testing::TestParamInfo<std::string>& info) {
  std::string out = info.param;
  std::replace(out.begin(), out.end(), '-', '_');
  return out;
}

INSTANTIATE_TEST_SUITE_P(OpenScad, CsgExample, ::testing::ValuesIn(all_example_names()), example_test_name);

}  // namespace
}  // namespace bsp
