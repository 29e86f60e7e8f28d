#pragma once
// The fragments of a frozen tree in flat arrays: every vertex position of every fragment in one
// array of doubles, fragment i owning points[start[i], start[i + 1]), with its source polygon
// beside it. Texture coordinates, as floats, are stored only once some vertex has non-zero ones;
// until then they read as zero. A fragment costs 8 bytes plus 24 per vertex (32 with texture
// coordinates), instead of a heap vector of 40-byte vertices and its 32-byte header.
#include <cstdint>
#include <span>
#include <vector>

#include "common/page_allocator.h"
#include "geometry/polygon.h"

namespace bsp {

struct TexCoord {
  float u = 0, v = 0;
};

// One fragment, read in place. Valid until its array changes.
struct FragmentView {
  std::span<const Vec3> p;       // positions, counter-clockwise seen from the front of its plane
  std::span<const TexCoord> uv;  // parallel to p; empty when the array stores none
  std::uint32_t source = 0;      // the input polygon it is (a fragment of)

  std::size_t size() const { return p.size(); }
  Polygon polygon() const;  // a copy, for geometry code that takes a Polygon
  void copy_to(Polygon& out) const;  // the same into `out`, reusing its memory
};

class FragmentArray {
 public:
  FragmentArray() : start_{0} {}

  std::size_t size() const { return source_.size(); }
  bool empty() const { return source_.empty(); }
  std::size_t vertex_count() const { return points_.size(); }
  bool has_tex_coords() const { return !uv_.empty(); }

  FragmentView operator[](std::size_t i) const {
    const std::span<const TexCoord> uv =
        uv_.empty() ? std::span<const TexCoord>() : std::span<const TexCoord>(uv_).subspan(start_[i], start_[i + 1] - start_[i]);
    return {points(i), uv, source_[i]};
  }
  std::span<const Vec3> points(std::size_t i) const {
    return std::span<const Vec3>(points_).subspan(start_[i], start_[i + 1] - start_[i]);
  }

  void reserve(std::size_t fragments, std::size_t vertices);
  // Bulk packing, for writers that fill the fragments in any order (and on any thread): lays out
  // fragments with these vertex counts and sources, then write(i, f) fills fragment i, which must
  // have vertex_counts[i] vertices (texture coordinates missing from a view are zero). Replaces the
  // contents.
  void lay_out(std::span<const std::uint32_t> vertex_counts, std::span<const std::uint32_t> sources, bool tex_coords);
  void write(std::size_t i, const FragmentView& f);
  void push_back(const Polygon& poly);
  std::vector<Polygon> to_polygons() const;
  // The bytes stored (sizes, not capacities): positions, attributes and per-fragment records.
  std::size_t bytes() const;
  std::size_t position_bytes() const { return points_.size() * sizeof(Vec3); }
  std::size_t attribute_bytes() const { return uv_.size() * sizeof(TexCoord); }
  std::size_t record_bytes() const { return (start_.size() + source_.size()) * sizeof(std::uint32_t); }

  class Iterator {
   public:
    Iterator(const FragmentArray* a, std::size_t i) : a_(a), i_(i) {}
    FragmentView operator*() const { return (*a_)[i_]; }
    Iterator& operator++() {
      ++i_;
      return *this;
    }
    bool operator!=(const Iterator& o) const { return i_ != o.i_; }

   private:
    const FragmentArray* a_;
    std::size_t i_;
  };
  Iterator begin() const { return {this, 0}; }
  Iterator end() const { return {this, size()}; }

 private:
  void start_tex_coords();

  // Page-allocated: a million-fragment tree's arrays are mapped in huge pages and unmapped at once.
  PageVector<Vec3> points_;
  PageVector<TexCoord> uv_;          // empty, or parallel to points_
  PageVector<std::uint32_t> start_;  // size() + 1 offsets into points_
  PageVector<std::uint32_t> source_;
};

}  // namespace bsp
