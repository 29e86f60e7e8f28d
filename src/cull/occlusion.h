#pragma once
// Occlusion culling by beam tracing [Naylor1992; Chrysanthou §6.1]: the scene tree is walked front
// to back inside a view frustum while an occlusion beam collects the directions that drawn
// fragments cover; what lies wholly inside the beam is hidden and skipped.
//
// Notation: the beam B is a BSP tree whose planes all pass through the eye and whose leaves are IN
// (every ray from the eye through that cell meets a drawn fragment) or OUT; it starts as one OUT
// leaf. A fragment later in a front-to-back order is never in front of an earlier one along any
// ray [Fuchs1980], so a fragment whose directions all lie in B is hidden. Each fragment of the walk
// is filtered down B and split by its planes: pieces reaching OUT leaves are visible, and each such
// leaf is replaced by the piece's own beam (the planes through the eye and the piece's edges, IN
// inside): the union of B with the fragment's shadow volume, which is Naylor's merge [Naylor1990]
// of B with a tree of one convex cell, as in shadow volume BSP trees [ChinFeiner1989]. A subtree
// whose bounding box (side data, never read by traversal) lies wholly in B is skipped, and the walk
// stops once B covers the view's near rectangle. Fragments are clipped to the view volume's near
// plane first: a renderer clips what lies before it, so that part neither shows nor hides.
//
// Conservative: a piece goes to a side of a beam plane only when it reaches beyond a band of
// kBeamBand × plane_eps on that side (to both, unsplit, when it lies within the band), and a split
// part too thin to keep is replaced by the whole piece. So a part of a fragment counted as covered
// lies behind a drawn fragment, or beside its edge by less than the band: at most band / sin(angle
// between the drawn fragment's plane and the edge's beam plane) from it in its plane, which is
// within the Embree check's slack of one plane_eps (validate/embree_scene.h, kInsideEps) down to the
// sine that check itself caps grazing at (1 / kMaxGrazingScale = 1e-3). A fragment seen edge-on (its
// plane within the band of the eye) is emitted and covers nothing. Edge planes are oriented by the
// fragment's winding as seen from the eye, never by a piece's centroid, which a sliver piece leaves
// on the wrong side of its own long edges.
#include <cstdint>
#include <span>
#include <vector>

#include "geometry/vec3.h"
#include "tree/traverse_culled.h"
#include "tree/tree.h"

namespace bsp {

// In plane_eps: far above the rounding of a plane through the eye and two vertices (~1e-16 of their
// distances, ~1e-7 plane_eps), and small enough for the grazing argument above. Half a plane_eps
// (an earlier value) let a ray 4e-9 beside a terrain fragment seen at a grazing angle count as
// covered where the proof, rightly, saw the fragment behind.
inline constexpr double kBeamBand = 1e-3;
// The sine between a piece's edge and the line of sight to it below which the edge gives no beam
// plane: the plane's direction, cross(p - eye, q - p), carries a relative error near 1e-16 / sine,
// which at ten scene diagonals from the eye must stay below the band (1e-12 diagonals). Such a
// piece covers nothing (OcclusionCounters::beams_refused): leaving the edge's plane out would widen
// its cone past the edge.
inline constexpr double kMinEdgeSine = 1e-3;
// The walk tests whether the beam covers the view after the first fragment it emits and then after
// every this many more: each test filters the near rectangle down the whole beam.
inline constexpr std::uint32_t kCoverTestInterval = 8;
// A subtree's box is filtered down the beam only when the subtree holds at least this many
// fragments: a box test costs up to three filters of a face down the whole beam. Measured on crystal's
// trees at 10^4, 8 metric views: testing every subtree took 0.32 s on city, 64 and up 0.23 s;
// architecture (interiors, where whole rooms hide) was fastest at 64 (0.092 s; never testing, 0.108 s),
// city and terrain 5-8% faster never testing.
inline constexpr std::uint64_t kMinSubtreeTest = 64;

struct OcclusionCounters {
  std::uint64_t nodes_visited = 0;       // scene nodes entered
  std::uint64_t subtrees_tested = 0;     // subtree boxes filtered down the beam
  std::uint64_t subtrees_culled = 0;     // of those, hidden: skipped with everything in them
  std::uint64_t fragments_tested = 0;    // fragments filtered down the beam
  std::uint64_t fragments_hidden = 0;    // of those, wholly inside it
  std::uint64_t fragments_clipped = 0;   // of those, wholly before the near plane (neither shown nor hiding)
  std::uint64_t fragments_emitted = 0;   // potentially visible, in the output
  std::uint64_t beam_merges = 0;         // OUT leaves replaced by a piece's beam
  std::uint64_t beam_nodes = 0;          // the beam's size at the end
  std::uint64_t beam_steps = 0;          // beam nodes passed while filtering (the culling's work)
  std::uint64_t beam_splits = 0;         // pieces cut in two by beam planes
  std::uint64_t beams_refused = 0;       // visible pieces too thin to give a beam (kMinEdgeSine)
  bool covered = false;                  // the walk stopped because the beam covered the view
};

class Occluder {
 public:
  // Computes each node's subtree bounding box, O(vertices) once per tree.
  explicit Occluder(const Tree& tree);
  // The potentially visible fragments inside `view`, front to back from view.eye.
  std::vector<std::uint32_t> visible(const Frustum& view, OcclusionCounters* counters = nullptr) const;

 private:
  const Tree& tree_;
  std::vector<Box> subtree_box_;  // per node, parallel to tree.nodes
  std::vector<std::uint64_t> subtree_fragments_;  // per node: fragments in its subtree
};

}  // namespace bsp
