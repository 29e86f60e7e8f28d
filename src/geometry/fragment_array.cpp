#include "geometry/fragment_array.h"

#include <algorithm>

namespace bsp {

Polygon FragmentView::polygon() const {
  Polygon out;
  copy_to(out);
  return out;
}

void FragmentView::copy_to(Polygon& out) const {
  out.verts.resize(p.size());
  for (std::size_t k = 0; k < p.size(); ++k) out.verts[k] = uv.empty() ? Vertex{p[k]} : Vertex{p[k], uv[k].u, uv[k].v};
  out.source = source;
}

void FragmentArray::reserve(std::size_t fragments, std::size_t vertices) {
  points_.reserve(vertices);
  start_.reserve(fragments + 1);
  source_.reserve(fragments);
}

void FragmentArray::lay_out(std::span<const std::uint32_t> vertex_counts, std::span<const std::uint32_t> sources,
                            bool tex_coords) {
  start_.assign(1, 0);
  start_.reserve(vertex_counts.size() + 1);
  for (auto k : vertex_counts) start_.push_back(start_.back() + k);
  source_.assign(sources.begin(), sources.end());
  points_.assign(start_.back(), Vec3{});
  uv_.assign(tex_coords ? start_.back() : 0, TexCoord{});
}

void FragmentArray::write(std::size_t i, const FragmentView& f) {
  std::copy(f.p.begin(), f.p.end(), points_.begin() + start_[i]);
  if (!uv_.empty()) std::copy(f.uv.begin(), f.uv.end(), uv_.begin() + start_[i]);
}

void FragmentArray::start_tex_coords() { uv_.assign(points_.size(), TexCoord{}); }

void FragmentArray::push_back(const Polygon& poly) {
  if (uv_.empty())
    for (const auto& v : poly.verts)
      if (v.u != 0 || v.v != 0) {
        start_tex_coords();
        break;
      }
  for (const auto& v : poly.verts) {
    points_.push_back(v.p);
    if (!uv_.empty()) uv_.push_back({static_cast<float>(v.u), static_cast<float>(v.v)});
  }
  start_.push_back(static_cast<std::uint32_t>(points_.size()));
  source_.push_back(poly.source);
}

std::vector<Polygon> FragmentArray::to_polygons() const {
  std::vector<Polygon> out;
  out.reserve(size());
  for (std::size_t i = 0; i < size(); ++i) out.push_back((*this)[i].polygon());
  return out;
}

std::size_t FragmentArray::bytes() const { return position_bytes() + attribute_bytes() + record_bytes(); }

}  // namespace bsp
