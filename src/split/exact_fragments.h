#pragma once
// The fragments of an exact-kernel build: plane polygons (geometry/plane_polygon.h) whose every
// side is decided exactly, each with a rounded copy in a FragmentStore under the same id for what
// splitters estimate from geometry (areas, centroids, the points halving looks at). The copy
// never decides a side: a splitter that counts sides gets the exact counts (SideCounter reads
// SplitContext::exact), and the build partitions with classify() and split() here.
//
// A fragment is first tested whole, against a box in grid coordinates that contains its exact
// vertices (FilterBox): most fragments lie clear of a plane, as in the float kernel's bounding-sphere
// test (`boxes` counts those decided so). Otherwise each vertex is tested, cheapest way first:
//  - the filter on the vertex's cached cofactors (geometry/exact_predicates.h: VertexCofactors;
//    an input corner's are its grid coordinates and weight 1, exact);
//  - an input corner (a vertex made by two bounds of its input polygon, so a grid point): the
//    plane's value there in 128-bit integers, exact by grid_plane.h's bounds (`on_grid`);
//  - a vertex bound by the plane itself (a cut's vertex tested against the cut again, as merging
//    does): on it, by pooled index (`on_bound`);
//  - otherwise the 4x4 determinant in wide integers (`exact`).
// A fragment whose support is the plane, in either orientation, is coplanar without a test: pooled
// planes are canonical, so equal planes have equal indices.
//
// Ids and their reuse are the copy's (FragmentStore), so both stores agree on every id. Nothing is
// ever dropped: a split's parts have positive area by the plane polygons' invariants.
//
// Storage, as FragmentStore's: flat arrays, no heap allocation per fragment. Per id a 64-byte
// Record (box, pooled support, vertex run); per vertex slot its cofactors and 32-bit references to
// its bound plane and input corner; the input's planes are kept once, with their roundings, and a
// split's parts refer to them (and to the pooled cut) instead of copying planes. The copy's
// bounding spheres are not computed (no splitter tests sides on the copy).
#include <cstdint>
#include <span>
#include <utility>
#include <vector>

#include "geometry/grid_plane_pool.h"
#include "common/page_allocator.h"
#include "common/vector_path.h"
#include "geometry/plane_polygon.h"
#include "geometry/plane_polygon_set.h"
#include "split/fragment_store.h"

namespace bsp {

// How the side tests of a build were decided (best: all filtered).
struct ExactSideCounters {
  PredicateCounters predicates;  // filtered, and decided in wide integers
  std::uint64_t on_grid = 0;     // decided at an input corner in 128-bit integers
  std::uint64_t on_bound = 0;    // vertices on the plane because it bounds them (pooled index)
  std::uint64_t coplanar_by_index = 0;  // fragments found coplanar by their pooled support
  std::uint64_t boxes = 0;              // fragments decided whole by their box
};

class ExactFragments {
 public:
  // Whether each fragment has its rounded copy: a build's fragments do, for its splitters; a solid
  // space's sub-hyperplanes, which no splitter reads, do not (computing the copy and storing it
  // cost a solid's labels and merges more than a third of their time). Without copies the ids are
  // this store's own, reused last freed first.
  enum class Copies : std::uint8_t { Rounded, None };

  // Freed vertex runs of up to `reused_span` vertices are reused (FragmentStore::kReusedSpan by
  // default; a solid tree's sub-hyperplanes, clipped by every ancestor, reach dozens).
  explicit ExactFragments(GridPlanePool& planes, std::uint32_t reused_span = FragmentStore::kReusedSpan,
                          Copies copies = Copies::Rounded)
      : planes_(planes), reused_span_(reused_span), copies_(copies) {
    rounded_.reuse_spans_up_to(reused_span);
  }

  // Room for this many fragments and vertices (FragmentStore::reserve), of which `input_vertices`
  // given to add(): reserved pages cost nothing until written, and the arrays never copy what they
  // hold while the build stays below.
  void reserve(std::size_t fragments, std::size_t vertices, std::size_t input_fragments, std::size_t input_vertices);
  // Pools the polygon's support; `corners` says which of its vertices are grid points (input
  // corners), given in vertex order, or is empty when none is known.
  std::uint32_t add(const PlanePolygon& poly, std::span<const GridPoint> corners = {});
  // The polygon on pooled plane `support` bounded by pooled planes `bounds` (counter-clockwise,
  // each vertex defined): what solid trees make from planes alone. Refers to the pool, copies no plane.
  std::uint32_t add_pooled(std::uint32_t support, std::span<const std::uint32_t> bounds, std::uint32_t source = 0);
  void release(std::uint32_t id);
  // The fragment's plane polygon.
  PlanePolygon polygon(std::uint32_t id) const;
  // Appends the fragment to `out` by reference (its planes stay here until adopted from
  // release_input_planes() and the pool) and releases it.
  void take_into(std::uint32_t id, PlanePolygonSet& out);
  // The input's planes, which references with the top bit clear point to; the store reads them no
  // more (what is left of it is only released).
  PageVector<GridPlane> release_input_planes() { return std::move(own_); }

  std::uint32_t plane(std::uint32_t id) const { return rec_[id].support; }  // pooled support
  const FragmentStore& rounded() const { return rounded_; }  // empty with Copies::None
  // The vertices of the fragments not released.
  std::size_t vertices_live() const { return vertices_live_; }
  GridPlanePool& planes() const { return planes_; }

  // The fragment's side of pooled plane `plane`, exactly.
  Side classify(std::uint32_t id, std::uint32_t plane) const;
  // A box certainly holding the fragment's exact vertices (exact_predicates.h), unbounded when the
  // filter could not bound one of them.
  FilterBox box(std::uint32_t id) const;
  // Counts of ids on each side of each plane, added to out[j] for planes[j] (SideCounts).
  void count_sides(std::span<const std::uint32_t> ids, std::span<const std::uint32_t> planes,
                   std::span<SideCounts> out) const;
  // The vector instructions count_sides's box pass runs on (Widest unless a test asks for the other).
  void use_vector_path(VectorPath path) { vector_path_ = path; }
  // Splits a fragment classified Spanning by pooled plane `plane` and releases it (unless
  // keep_parent: a solid tree's sub-hyperplane stays its node's when merging cuts a copy); the parts
  // keep its support and source. Both parts exist (nothing is a sliver in the exact kernel).
  struct Parts {
    std::uint32_t front = FragmentStore::kNone, back = FragmentStore::kNone;
  };
  Parts split(std::uint32_t id, std::uint32_t plane, bool keep_parent = false);
  // The part of the fragment in front of pooled plane `plane` or on it: the fragment itself when
  // it lies there whole; FragmentStore::kNone when it lies behind; else the front part of a split,
  // made alone (the back part is never computed). The fragment is released unless returned or
  // keep_parent (split's).
  std::uint32_t clip(std::uint32_t id, std::uint32_t plane, bool keep_parent = false);

  const ExactSideCounters& counters() const { return counters_; }

  // What count_sides reads of a fragment, one cache line (64 bytes) in one array by id: its
  // FilterBox and its pooled support, so the box test of a node's fragments loads one line each;
  // where its vertices are fills the rest of the line.
  // An unbounded box has NaN half-widths: every comparison with NaN is false, so it decides nothing
  // in the vector test either, without a branch.
  struct Record {
    double centre[3] = {0, 0, 0};
    double half[3] = {0, 0, 0};
    std::uint32_t support = 0;  // pooled plane
    std::uint32_t first = 0;    // the fragment's first vertex slot (bound_, cof_, corner_)
    std::uint32_t count = 0;    // its vertices
    std::uint32_t source = 0;   // its input polygon
  };
  static_assert(sizeof(Record) == 64, "one cache line per fragment");

 private:
  // A plane a fragment refers to, in 32 bits: with the top bit clear, one of the input's planes as
  // loaded (a support or an edge plane, kept once in own_ with its rounding); with it set, a pooled
  // plane (a cut, in either orientation). Parts copy references, never planes.
  using PlaneRef = PlanePolygonSet::PlaneRef;
  static constexpr PlaneRef kPooled = PlanePolygonSet::kPooled;
  GridPlane plane_of(PlaneRef r) const { return (r & kPooled) ? planes_[r & ~kPooled] : own_[r]; }
  PlaneApprox approx_of(PlaneRef r) const { return (r & kPooled) ? planes_.approx(r & ~kPooled) : own_approx_[r]; }

  // Side of vertex i of fragment id of pooled plane `pooled` (`plane`, `approx`): +1, -1 or 0.
  int vertex_side(std::uint32_t id, std::size_t i, std::uint32_t pooled, const GridPlane& plane,
                  const PlaneApprox& approx) const;
  // Whether a vertex bound by plane reference r lies on pooled plane `pooled`: r is that pooled
  // plane, in either orientation.
  static bool on_pooled(PlaneRef r, std::uint32_t pooled) {
    return (r & kPooled) != 0 && PlanePool::coplanar(r & ~kPooled, pooled);
  }
  // Front/Back/Coplanar/Spanning from the fragment's vertices alone (no whole-fragment test),
  // stopping at the first vertex that makes it Spanning unless `sides` is given: then every
  // vertex's side is written there (+1, -1, 0), as split needs them.
  Side vertex_sides(std::uint32_t id, std::uint32_t plane, const PlaneApprox& approx, int* sides) const;
  void count_block(std::span<const std::uint32_t> ids, std::span<const std::uint32_t> planes,
                   std::span<SideCounts> out) const;
  // The vertex tests of fragment id against the planes[j] of the bits of `open`, counted into out[j].
  void count_vertices(std::uint32_t id, std::uint32_t open, std::span<const std::uint32_t> planes,
                      std::span<SideCounts> out) const;
  // Vertex slots for `count` vertices: a freed run of that length when there is one (as
  // FragmentStore reuses spans, in a fixed order), else new ones at the end of the arrays.
  std::uint32_t new_span(std::uint32_t count);
  void free_span(std::uint32_t first, std::uint32_t count);
  // Appends an input plane to own_; its reference.
  PlaneRef own(const GridPlane& p);
  // The rounded copy of the fragment whose vertex slots are [first, first + count).
  void rounded_polygon(PlaneRef support, std::uint32_t first, std::uint32_t count, std::uint32_t source,
                       Polygon& out) const;
  // One part of a split of the fragment whose slots start at `from`: the bounds at kept_ (the
  // parent's edge indices) then `cut`, the kept vertices copied, the two new ones computed.
  std::uint32_t add_part(PlaneRef support, std::uint32_t pooled, std::uint32_t source, std::uint32_t from, PlaneRef cut);
  // An id for a new fragment: its rounded copy's, or a free one of this store's. drop_id frees it.
  std::uint32_t new_id(PlaneRef support, std::uint32_t pooled, std::uint32_t source, std::uint32_t first,
                       std::uint32_t count);
  void drop_id(std::uint32_t id);
  // Registers the fragment whose bounds and vertices fill slots [first, first + count): its box,
  // its rounded copy (which gives the id), its record.
  std::uint32_t store(PlaneRef support, std::uint32_t pooled, std::uint32_t source, std::uint32_t first,
                      std::uint32_t count);

  GridPlanePool& planes_;
  std::uint32_t reused_span_;
  Copies copies_;
  FragmentStore rounded_;
  std::vector<std::uint32_t> free_ids_;  // with Copies::None
  std::size_t vertices_live_ = 0;
  // The input's planes as given (a support is not replaced by the pool's canonical multiple: the
  // vertices, cofactors and output are computed from the polygon's own planes), and their roundings.
  PageVector<GridPlane> own_;
  PageVector<PlaneApprox> own_approx_;
  PageVector<GridPoint> corners_;  // the input corners given to add()
  // By id.
  PageVector<Record> rec_;
  PageVector<PlaneRef> support_;
  // By vertex slot, each fragment's a run of rec_[id].count from rec_[id].first: no heap allocation
  // per fragment, and freed runs are reused. Bound i of the fragment is bound_[first + i].
  PageVector<PlaneRef> bound_;
  PageVector<VertexCofactors> cof_;
  PageVector<std::uint32_t> corner_;  // the vertex's index in corners_, or kNoCorner
  static constexpr std::uint32_t kNoCorner = 0xffffffffu;
  std::vector<std::vector<std::uint32_t>> free_spans_;  // by count: first slots of freed runs
  // Counts and scratch, not state: a store is used by one thread at a time.
  mutable ExactSideCounters counters_;
  VectorPath vector_path_ = VectorPath::Widest;
  std::vector<int> sides_;  // split's and clip's
  std::vector<std::uint32_t> kept_;
  std::vector<PlaneApprox> bounds_approx_;
  Polygon rounded_scratch_;
};

}  // namespace bsp
