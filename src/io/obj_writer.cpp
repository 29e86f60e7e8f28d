#include "io/obj_writer.h"

#include <algorithm>
#include <charconv>
#include <cstdint>
#include <vector>

namespace bsp {

namespace {

constexpr std::size_t kChunk = 4096;  // polygons per parallel chunk

void append_number(std::string& out, double x) {
  char buf[32];
  const auto end = std::to_chars(buf, buf + sizeof buf, x).ptr;
  out.push_back(' ');
  out.append(buf, end);
}

void append_index(std::string& out, std::uint64_t i) {
  char buf[24];
  const auto end = std::to_chars(buf, buf + sizeof buf, i).ptr;
  out.append(buf, end);
}

// `first` is the 1-based OBJ index of the chunk's first vertex.
std::string chunk_text(std::span<const Polygon> polys, std::uint64_t first) {
  std::string out;
  for (const auto& poly : polys) {
    for (const auto& v : poly.verts) {
      out += 'v';
      append_number(out, v.p.x);
      append_number(out, v.p.y);
      append_number(out, v.p.z);
      out += "\nvt";
      append_number(out, v.u);
      append_number(out, v.v);
      out += '\n';
    }
    out += 'f';
    for (std::size_t k = 0; k < poly.verts.size(); ++k) {
      out += ' ';
      append_index(out, first + k);
      out += '/';
      append_index(out, first + k);
    }
    out += '\n';
    first += poly.verts.size();
  }
  return out;
}

std::string comment_lines(std::string_view comment) {
  std::string out;
  std::size_t line_start = 0;
  while (line_start <= comment.size() && !comment.empty()) {
    const std::size_t end = std::min(comment.find('\n', line_start), comment.size());
    out += "# ";
    out += comment.substr(line_start, end - line_start);
    out += '\n';
    line_start = end + 1;
  }
  return out;
}

}  // namespace

std::string to_obj(std::span<const Polygon> polys, std::string_view comment) {
  const std::size_t chunks = (polys.size() + kChunk - 1) / kChunk;
  std::vector<std::uint64_t> first(chunks + 1, 1);
  for (std::size_t c = 0; c < chunks; ++c) {
    first[c + 1] = first[c];
    for (std::size_t i = c * kChunk; i < std::min(polys.size(), (c + 1) * kChunk); ++i)
      first[c + 1] += polys[i].verts.size();
  }
  std::vector<std::string> parts(chunks);
#pragma omp parallel for schedule(dynamic, 1)
  for (std::size_t c = 0; c < chunks; ++c)
    parts[c] = chunk_text(polys.subspan(c * kChunk, std::min(kChunk, polys.size() - c * kChunk)), first[c]);
  std::string out = comment_lines(comment);
  std::size_t total = out.size();
  for (const auto& p : parts) total += p.size();
  out.reserve(total);
  for (const auto& p : parts) out += p;
  return out;
}

std::string to_obj(const IndexedMesh& mesh, std::string_view comment) {
  std::string out = comment_lines(comment);
  for (const Vec3& v : mesh.vertices) {
    out += 'v';
    append_number(out, v.x);
    append_number(out, v.y);
    append_number(out, v.z);
    out += '\n';
  }
  for (std::size_t f = 0; f < mesh.face_count(); ++f) {
    out += 'f';
    for (std::uint32_t c = mesh.start[f]; c < mesh.start[f + 1]; ++c) {
      out += ' ';
      append_index(out, std::uint64_t{mesh.corners[c]} + 1);
    }
    out += '\n';
  }
  return out;
}

std::string to_off(const IndexedMesh& mesh, std::string_view comment) {
  std::string out = "OFF\n" + comment_lines(comment);
  append_index(out, mesh.vertices.size());
  out += ' ';
  append_index(out, mesh.face_count());
  out += " 0\n";
  for (const Vec3& v : mesh.vertices) {
    append_number(out, v.x);
    append_number(out, v.y);
    append_number(out, v.z);
    out += '\n';
  }
  for (std::size_t f = 0; f < mesh.face_count(); ++f) {
    append_index(out, mesh.start[f + 1] - mesh.start[f]);
    for (std::uint32_t c = mesh.start[f]; c < mesh.start[f + 1]; ++c) {
      out += ' ';
      append_index(out, mesh.corners[c]);
    }
    out += '\n';
  }
  return out;
}

}  // namespace bsp
