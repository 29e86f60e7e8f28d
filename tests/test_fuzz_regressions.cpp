// Inputs the libFuzzer targets (tests/fuzz) found crashing, kept here so the normal suite keeps
// them fixed. Each must give an InputError (or be accepted), never another exception or a crash.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>

#include <nlohmann/json.hpp>

#include "cli_runner.h"
#include "common/errors.h"
#include "io/mesh_reader.h"
#include "io/polygon_cleanup.h"
#include "gate/regress.h"
#include "results/report.h"

namespace fs = std::filesystem;

namespace {

class FuzzFindings : public ::testing::Test {
 protected:
  void SetUp() override { dir_ = bsp::testing::fresh_test_dir("bspbench_fuzz_findings"); }
  void TearDown() override { fs::remove_all(dir_); }

  std::string write(const std::string& name, const std::string& content) const {
    std::ofstream(dir_ / name, std::ios::binary) << content;
    return (dir_ / name).string();
  }

  // read_mesh on `content` throws an InputError whose message contains `problem`.
  void expect_mesh_error(const std::string& name, const std::string& content, const std::string& problem) const {
    try {
      bsp::read_mesh(write(name, content));
      ADD_FAILURE() << name << " was accepted";
    } catch (const bsp::InputError& e) {
      EXPECT_NE(std::string(e.what()).find(problem), std::string::npos) << e.what();
    }
  }

  // The smallest report read_report accepts: one run with every field a reader uses.
  static nlohmann::json minimal_report() {
    const nlohmann::json run = {
        {"key", "k1"},
        {"id", {{"kind", "draw"}, {"scene", "city"}, {"heuristic", "first"}, {"shape", "strict"}, {"n", 10}, {"n_polygons", 10},
                {"scene_params", nlohmann::json::object()}, {"command", "bspbench build --scene city --n 10"}}},
        {"metrics", {{"nodes", 3}}},
        {"invariants", {{"violations", 0}}},
        {"validation", nullptr},
        {"timings", {{"build_cpu_seconds", 0.5}}},
        {"calibration_seconds", 0.1}};
    return {{"schema", "bspbench-report"}, {"version", bsp::results::kReportVersion},
            {"suite", {{"name", "s"}, {"definition_hash", "h"}, {"jobs", 1}}},
            {"shards", {{{"index", 0}, {"count", 1}, {"jobs", 1}}}},
            {"runs", {run}},
            {"failures", nlohmann::json::array()}};
  }

  fs::path dir_;
};

}  // namespace

// check_mesh_claims stepped past the end of a file whose last line is a comment without a newline
// (std::out_of_range from string_view::substr).
TEST_F(FuzzFindings, OffEndingInACommentWithoutNewline) {
  EXPECT_THROW(bsp::read_mesh(write("comment.off", "OFF\n# c\n#")), bsp::InputError);
  EXPECT_THROW(bsp::read_mesh(write("counts.off", "OFF\n3 1 0\n0 0 0\n#")), bsp::InputError);
}

// CGAL reads the OFF keyword as a run of letters and digits and the counts as ints, so
// "OFF\b" and "0-1" were not the header this check saw, and CGAL cast the face size -1 to size_t.
TEST_F(FuzzFindings, OffHeaderReadAsCgalReadsIt) {
  expect_mesh_error("keyword.off", "OFF\b# c\n0 1 0-1 0 0\n", "face 0 claims -1 vertices");
  expect_mesh_error("glued.off", "OFF\n0 1 0-1 0 1\n", "face 0 claims -1 vertices");
}

// CGAL's OFF scanner reads texture coordinates at an uninitialised index (a segfault even on a
// well-formed STOFF file), indexes vertex and face lines for colours without bounds checks, keeps
// reading colours once one line had one, casts colour channels to unsigned char and face indices
// to size_t unchecked.
TEST_F(FuzzFindings, OffTexturesColoursAndIndicesCgalCannotRead) {
  expect_mesh_error("textures.off", "STOFF\n# c\n4 2 0\n0 0 0\n1 0 0\n1 1 5\n0 1 0\n4 0 1 2 3\n3 0 1 2 255 0 0\n",
                    "texture coordinates (ST) is not supported");
  const std::string rest = "1 0 0\n0 1 0\n3 0 1 2\n";
  expect_mesh_error("two_channels.off", "COFF\n3 1 0\n0 0 0 1 2\n" + rest, "vertex 0 has a colour CGAL cannot read");
  expect_mesh_error("channel_300.off", "COFF\n3 1 0\n0 0 0 300 0 0\n" + rest, "vertex 0 has a colour");
  expect_mesh_error("map_index.off", "COFF\n3 1 0\n0 0 0 149\n" + rest, "vertex 0 has a colour");
  expect_mesh_error("then_none.off", "COFF\n3 1 0\n0 0 0 255 0 0\n" + rest, "vertex 1 has a colour CGAL cannot read");
  expect_mesh_error("face_colour.off", "COFF\n3 2 0\n0 0 0\n" + rest + "3 0 2 1 0.5 0.5\n", "face 1 has a colour");
  expect_mesh_error("negative_index.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 -1\n",
                    "face 0 refers to vertex -1 but the file has 3");
  const std::string coloured = "COFF\n3 1 0\n0 0 0 255 0 0\n1 0 0 0 255 0\n0 1 0 0 0 0.5 1\n3 0 1 2 7\n";
  EXPECT_EQ(bsp::read_mesh(write("coloured.off", coloured)).polygons.size(), 1u);
}

// CGAL's PLY reader dereferences a null pointer when a vertex coordinate is not float or double.
// CGAL reads a line's numbers with `stream >> double`, which fails on a run like "05e" (strtod would
// read 5 of it) and reads "1-2" as two numbers. A face line "0 05evr" after a face with a colour
// index had, to CGAL, no colour, and it read one past the end of the line (the mesh_reader fuzzer,
// after 865,301 runs; the file below is its input).
TEST_F(FuzzFindings, OffNumbersReadAsTheStreamReadsThem) {
  const std::string head = "COFF\n3 2 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2 4\n";
  expect_mesh_error("cut_exponent.off", head + "3 0 2 1 05evr\n", "face 1 has a colour CGAL cannot read");
  expect_mesh_error("joined_signs.off", head + "3 0 2 1 1-2 3\n", "face 1 has a colour CGAL cannot read");
  EXPECT_EQ(bsp::read_mesh(write("one_index.off", head + "3 0 2 1 05e1\n")).polygons.size(), 2u);
  using namespace std::string_literals;  // the input holds NUL bytes
  const std::string found = "COFF*\n#0\xe0\xf5\x02\x00\xd2\xd6  11F\n# c\n# c\n#c\n#\n0 04 0\n"
                            "0 \xff\xff\xff\xff\x00\x00\x00\x04#\n0 0 c\n#5 055c'\n#\n0 05OFF\n# c\n\n"
                            "0 05evrepzv\x92\x00\x00" "0 c\x9c\x9c\n# c\n #\"c\na"s;
  expect_mesh_error("fuzzer.off", found, "face 3 has a colour CGAL cannot read");
}

// CGAL's OFF header doubles the edge count in an int before it reads a vertex, so a claim of more
// than INT_MAX / 2 edges is signed overflow (UndefinedBehaviorSanitizer, the mesh_reader fuzzer
// with seed 1 after 92,385 runs; the second file is its input).
TEST_F(FuzzFindings, OffEdgeCountCgalCannotDouble) {
  const std::string triangle = "0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n";
  expect_mesh_error("edges.off", "OFF\n3 1 1333355555\n" + triangle, "header claims 1333355555 edges");
  expect_mesh_error("negative_edges.off", "OFF\n3 1 -1333355555\n" + triangle, "header claims -1333355555 edges");
  EXPECT_EQ(bsp::read_mesh(write("many_edges.off", "OFF\n3 1 1073741823\n" + triangle)).polygons.size(), 1u);
  const std::string found = "OFF\n#z\xff\xff\xffhF\n 1 0 \n1333355555EEEEEEEEEEendfacet";
  expect_mesh_error("fuzzer.off", found, "header claims 1333355555 edges");
}

TEST_F(FuzzFindings, PlyVertexCoordinateOfAnIntegerTypeOrAList) {
  const std::string header = "ply\nformat ascii 1.0\nelement vertex 3\n";
  const std::string rest = "property float y\nproperty float z\nelement face 1\n"
                           "property list uchar int vertex_indices\nend_header\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n";
  EXPECT_EQ(bsp::read_mesh(write("float.ply", header + "property float x\n" + rest)).polygons.size(), 1u);
  expect_mesh_error("int.ply", header + "property int32 x\n" + rest, "coordinate x is int32");
  expect_mesh_error("list.ply", header + "property list uchar float x\n" + rest, "coordinate x is a list");
}

// CGAL reads a halfedge element's source and target as uint32 and dereferences a null pointer when
// the first property of that name has another type (the mesh_reader fuzzer, after 915,981 runs).
TEST_F(FuzzFindings, PlyHalfedgeSourceOrTargetOfAnotherType) {
  const std::string mesh = "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
                           "property float z\nelement face 1\nproperty list uchar int vertex_indices\n";
  const std::string data = "end_header\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n0 1\n";
  const auto halfedge = [&](const std::string& source_type) {
    return mesh + "element halfedge 1\nproperty " + source_type + " source\nproperty uint target\n" + data;
  };
  EXPECT_EQ(bsp::read_mesh(write("uint.ply", halfedge("uint"))).polygons.size(), 1u);
  expect_mesh_error("float_source.ply", halfedge("float"), "PLY halfedge source is float");
  expect_mesh_error("list_source.ply", halfedge("list uchar uint"), "PLY halfedge source is a list");
}

// CGAL takes the format from line 2 whatever its words, so "element" there is no element, and a
// later property line indexed the last element of an empty list.
TEST_F(FuzzFindings, PlyElementOnTheFormatLineIsNoElement) {
  expect_mesh_error("format_line.ply", "ply\nformat ascii 1.0 element vertex 1\nformat x\nproperty float x\nend_header\n0\n",
                    "a PLY property comes before any element");
}

TEST_F(FuzzFindings, MinimalReportIsAcceptedAndCompared) {
  const auto path = write("ok.json", minimal_report().dump());
  const nlohmann::json report = bsp::results::read_report(path);
  EXPECT_FALSE(bsp::gate::compare_reports(report, report, {}).failed());
}

// compare_reports indexed a run's missing "validation", and aggregation (behind merge-reports) its
// missing id.scene, through a const json (undefined behaviour: AddressSanitizer saw a
// heap-use-after-free); read_report now names every field readers use.
TEST_F(FuzzFindings, RunWithoutAFieldTheReadersUseIsAnInputError) {
  for (const auto& [section, key] : std::vector<std::pair<std::string, std::string>>{
           {"", "validation"}, {"id", "n_polygons"}, {"id", "scene_params"}, {"id", "scene"}, {"id", "shape"},
           {"", "calibration_seconds"}, {"id", "kind"}, {"id", "command"}}) {
    nlohmann::json r = minimal_report();
    (section.empty() ? r["runs"][0] : r["runs"][0][section]).erase(key);
    EXPECT_THROW(bsp::results::read_report(write("no_" + key + ".json", r.dump())), bsp::InputError) << key;
  }
}

// Fields of the wrong type made nlohmann::json throw type_error out of read_report, merge and the gate.
TEST_F(FuzzFindings, ReportFieldsOfTheWrongTypeAreAnInputError) {
  nlohmann::json schema = minimal_report();
  schema["schema"] = 5;
  EXPECT_THROW(bsp::results::read_report(write("schema.json", schema.dump())), bsp::InputError);
  nlohmann::json label = minimal_report();
  label["runs"][0]["id"]["scene"] = 7;
  EXPECT_THROW(bsp::results::read_report(write("label.json", label.dump())), bsp::InputError);
  nlohmann::json violations = minimal_report();
  violations["runs"][0]["invariants"]["violations"] = "none";
  EXPECT_THROW(bsp::results::read_report(write("violations.json", violations.dump())), bsp::InputError);
}

// A face that turns straight back at one vertex (a spike) passed the convexity test, so a
// self-overlapping hexagon reached split as one polygon and its parts held more area than it had.
TEST_F(FuzzFindings, AFaceWithASpikeIsNotTakenAsConvex) {
  bsp::Polygon spiked;
  for (const bsp::Vec3& p : {bsp::Vec3{2, 2.25, 2.25}, bsp::Vec3{-4, -3, -3}, bsp::Vec3{2, -3.5, -3.5}, bsp::Vec3{0, 2, 2},
                             bsp::Vec3{-3.5, 2, 2}, bsp::Vec3{2.5, 2, 2}})
    spiked.verts.push_back({p, 0, 0});
  const double eps = 1e-8;
  EXPECT_FALSE(bsp::is_convex_planar(spiked, eps));
  std::vector<bsp::Polygon> pieces;
  bsp::SceneLoadStats stats;
  bsp::append_clean_polygon(std::move(spiked), eps, pieces, stats);
  for (const auto& piece : pieces) EXPECT_TRUE(bsp::is_convex_planar(piece, eps));
}

// A binary PLY whose last list holds exactly one byte more than the data has: the length check let
// it through by one byte (meant for ASCII's missing last separator), and the next record's read
// started past the end (std::out_of_range). The input is the fuzzer's, kept in the corpus.
TEST_F(FuzzFindings, ABinaryPlyListOneBytePastTheEndIsAnInputError) {
  std::ifstream in(std::string(BSPBENCH_SOURCE_DIR) + "/tests/fuzz/corpus/mesh_reader/crash-ply-binary-list-past-end",
                   std::ios::binary);
  const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  ASSERT_GT(bytes.size(), 1u);
  EXPECT_THROW(bsp::read_mesh(write("list.ply", bytes.substr(1))), bsp::InputError);
}

// A PLY ASCII value the stream cannot read ("p0" for an int) leaves CGAL's stream bad, and every
// later value, a list length among them, uninitialised: the mesh_reader fuzzer saw a 4.7 GB
// allocation for one face (its input is kept in the corpus). Each value must be one whole number
// in its type's range, as CGAL reads it (the one-byte types through a short).
TEST_F(FuzzFindings, PlyAsciiValueTheStreamCannotReadIsAnInputError) {
  const std::string head = "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
                           "property float z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n";
  const std::string vertices = "0 0 0\n1 0 0\n0 1 0\n";
  EXPECT_EQ(bsp::read_mesh(write("signs.ply", head + "+0 0 0\n1e0 0 0\n0 .1e1 0\n3 0 +1 2\n")).polygons.size(), 1u);
  expect_mesh_error("word_index.ply", head + vertices + "3 0 p1 2\n", "face 0 has 'p1', not a 32-bit integer");
  expect_mesh_error("word_coordinate.ply", head + "0 0 0\n1 0 0\n0 nan 0\n3 0 1 2\n", "vertex 2 has 'nan', not a real");
  expect_mesh_error("wide_length.ply", head + vertices + "70000 0 1 2\n", "face 0 has '70000', not a 16-bit integer");
  expect_mesh_error("two_signs.ply", head + vertices + "3 0 +-1 2\n", "face 0 has '+-1', not a 32-bit integer");
  std::ifstream in(std::string(BSPBENCH_SOURCE_DIR) + "/tests/fuzz/corpus/mesh_reader/oom-ply-ascii-unreadable-value",
                   std::ios::binary);
  const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  ASSERT_GT(bytes.size(), 1u);
  expect_mesh_error("found.ply", bytes.substr(1), "face 0 has 'p0', not a 32-bit integer");
}
