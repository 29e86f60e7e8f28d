// Bad input cannot exhaust the machine: crafted files of about 100 bytes whose headers, faces or
// lists claim far more than they hold, in every format, run through the real bspbench binary with
// its address space capped at 1 GB and its CPU time at 20 s. Each must end with exit code 2, one
// stderr line naming the file and the claim, no output, and a peak resident set far below what the
// claim would take. Well-formed binary PLY and STL files, whose records the checks walk, still read.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <string>

#include "cli_runner.h"
#include "io/mesh_reader.h"

namespace fs = std::filesystem;

namespace {

constexpr rlim_t kAddressSpace = rlim_t{1} << 30;
constexpr rlim_t kCpuSeconds = 20;
constexpr long kMaxRssKb = 200 * 1024;  // the 100 MB goal with room for sanitizer builds

std::string le32(std::uint32_t v) {
  std::string s(4, '\0');
  for (int b = 0; b < 4; ++b) s[b] = static_cast<char>((v >> (8 * b)) & 0xff);
  return s;
}

const std::string kPlyVertexHeader =
    "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n";
const std::string kTriangleLines = "0 0 0\n1 0 0\n0 1 0\n";

class MeshClaims : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = bsp::testing::fresh_test_dir("bspbench_claims");
    fs::create_directories(dir_ / "out");
  }
  void TearDown() override { fs::remove_all(dir_); }

  fs::path write(const std::string& name, const std::string& content) const {
    std::ofstream(dir_ / name, std::ios::binary) << content;
    return dir_ / name;
  }

  // `order` on the file: exit 2, one line naming the file and containing `problem`, nothing
  // written, and little memory and time spent.
  void expect_rejected(const fs::path& file, const std::string& problem) const {
    SCOPED_TRACE(file.filename().string() + " (" + std::to_string(fs::file_size(file)) + " bytes)");
    ASSERT_LE(fs::file_size(file), 200u) << "the point is a small file";
    const auto r = bsp::testing::run_bspbench_limited(
        "order --input " + file.string() + " --heuristic first --eye 0.5,0.5,4 --out " + (dir_ / "out" / "run").string(),
        dir_, kAddressSpace, kCpuSeconds);
    EXPECT_EQ(r.result.code, 2) << r.result.err;
    EXPECT_EQ(std::count(r.result.err.begin(), r.result.err.end(), '\n'), 1) << r.result.err;
    EXPECT_NE(r.result.err.find(file.string()), std::string::npos) << r.result.err;
    EXPECT_NE(r.result.err.find(problem), std::string::npos) << r.result.err;
    EXPECT_TRUE(r.result.out.empty()) << r.result.out;
    EXPECT_TRUE(fs::is_empty(dir_ / "out")) << "output written for a rejected file";
    EXPECT_LT(r.max_rss_kb, kMaxRssKb);
  }

  fs::path dir_;
};

}  // namespace

TEST_F(MeshClaims, OffHeaderCountsBeyondTheFileAreRejected) {
  expect_rejected(write("faces.off", "OFF\n3 1000000000 0\n" + kTriangleLines + "3 0 1 2\n"),
                  "header claims 3 vertices and 1000000000 faces but the file has only 45 bytes");
  expect_rejected(write("vertices.off", "OFF\n2000000000 1 0\n" + kTriangleLines + "3 0 1 2\n"),
                  "header claims 2000000000 vertices and 1 faces");
  expect_rejected(write("negative.off", "OFF\n3 -1 0\n" + kTriangleLines), "negative number");
}

TEST_F(MeshClaims, OffFaceLongerThanItsLineIsRejected) {
  expect_rejected(write("long_face.off", "OFF\n3 1 0\n" + kTriangleLines + "1000000000 0 1 2\n"),
                  "face 0 claims 1000000000 vertices but its line lists 3");
  expect_rejected(write("nan_face.off", "OFF\n3 1 0\n" + kTriangleLines + "nan 0 1 2\n"),
                  "face 0 does not start with its number of vertices");
}

TEST_F(MeshClaims, BinaryOffIsRejectedByName) {
  expect_rejected(write("binary.off", "OFF BINARY\n" + std::string(12, '\x7f')), "binary OFF is not supported");
}

TEST_F(MeshClaims, PlyElementCountsBeyondTheFileAreRejected) {
  expect_rejected(write("vertices.ply", "ply\nformat ascii 1.0\nelement vertex 1000000000\nproperty float x\n"
                                        "property float y\nproperty float z\nend_header\n" + kTriangleLines),
                  "header claims 1000000000 vertex records");
  expect_rejected(write("faces.ply", kPlyVertexHeader + "element face 4000000000\n"
                                     "property list uchar int vertex_indices\nend_header\n" + kTriangleLines),
                  "header claims 4000000000 face records");
  expect_rejected(write("negative.ply", "ply\nformat ascii 1.0\nelement vertex -3\nproperty float x\nend_header\n"),
                  "element vertex has count '-3', not a count");
}

TEST_F(MeshClaims, PlyListsLongerThanTheFileAreRejected) {
  expect_rejected(write("ascii_list.ply", kPlyVertexHeader + "element face 1\nproperty list int int vertex_indices\n"
                                          "end_header\n" + kTriangleLines + "2000000000 0 1 2\n"),
                  "face 0 has a list of 2000000000 entries");
  const std::string binary_header =
      "ply\nformat binary_little_endian 1.0\nelement face 1\nproperty list uint int vertex_indices\nend_header\n";
  expect_rejected(write("binary_list.ply", binary_header + le32(0xffffffffu) + le32(0) + le32(1)),
                  "face 0 has a list of 4294967295 entries");
  expect_rejected(write("negative_list.ply", binary_header.substr(0, binary_header.find("uint")) +
                                                 "int int vertex_indices\nend_header\n" + le32(0xfffffffeu)),
                  "face 0 has a list of negative length");
}

TEST_F(MeshClaims, PlyWithoutHeaderEndOrWithDataEndingAtAListLengthIsRejected) {
  // CGAL reads on without end_header, sizes a list by a length read past the end of the data
  // (garbage), and indexes the last element for a property before any element.
  expect_rejected(write("no_end.ply", "ply\nformat ascii 1.0\nelement vertex 1000000000\nproperty float x\n"),
                  "the PLY header has no end_header line");
  expect_rejected(write("property_first.ply", "ply\nformat ascii 1.0\nproperty float x\nelement vertex 1\nend_header\n0\n"),
                  "a PLY property comes before any element");
  expect_rejected(write("truncated.ply", "ply\nformat binary_little_endian 1.0\nelement face 2\n"
                                         "property list uchar int vertex_indices\nend_header\n\3" +
                                             le32(0) + le32(1) + le32(2)),
                  "the data ends inside face 1 (the header claims 2)");
}

TEST_F(MeshClaims, BinaryStlTriangleCountBeyondTheFileIsRejected) {
  expect_rejected(write("triangles.stl", std::string(80, ' ') + le32(0xffffffffu) + std::string(16, '\0')),
                  "binary STL header claims 4294967295 triangles");
}

TEST_F(MeshClaims, ObjFaceIndicesOutOfRangeAreRejected) {
  const std::string v = "v 0 0 0\nv 1 0 0\nv 0 1 0\n";
  expect_rejected(write("huge.obj", v + "f 1 2 99999999999999999999\n"), "line 4: face index 99999999999999999999 is too large");
  expect_rejected(write("beyond_int.obj", v + "f 1 2 3000000000\n"), "face index 3000000000 is too large");
  expect_rejected(write("past_end.obj", v + "f 1 2 9\n"), "line 4: face index 9 but the file has only 3 vertices");
  expect_rejected(write("zero.obj", v + "f 0 1 2\n"), "face index 0 (OBJ counts vertices from 1)");
  expect_rejected(write("relative.obj", "v 0 0 0\nv 1 0 0\nf -1 -2 -3\nv 0 1 0\n"),
                  "line 3: face index -3 reaches back past the first vertex (2 so far)");
  expect_rejected(write("min_int.obj", v + "f 1 2 -2147483648\n"), "face index -2147483648 is too large");
}

TEST_F(MeshClaims, WellFormedBinaryPlyAndStlStillRead) {
  std::string floats;
  for (float f : {0.f, 0.f, 0.f, 1.f, 0.f, 0.f, 0.f, 1.f, 0.f}) floats.append(reinterpret_cast<const char*>(&f), 4);
  const fs::path ply = write("tri.ply", "ply\nformat binary_little_endian 1.0\nelement vertex 3\nproperty float x\n"
                                        "property float y\nproperty float z\nelement face 1\n"
                                        "property list uchar int vertex_indices\nend_header\n" +
                                            floats + std::string(1, '\3') + le32(0) + le32(1) + le32(2));
  EXPECT_EQ(bsp::read_mesh(ply.string()).polygons.size(), 1u);
  const std::string normal(12, '\0'), attribute(2, '\0');
  const fs::path stl = write("tri.stl", std::string(80, ' ') + le32(1) + normal + floats + attribute);
  EXPECT_EQ(bsp::read_mesh(stl.string()).polygons.size(), 1u);
}
