// doom-piece: a small 2D scene cut from a real level: the segs under one subtree of the nodes a
// Freedoom IWAD ships (built by ZenNode), a piece of n/2 to n segments (30 by default). Where the
// optimality gaps of heuristics are measured on real data: small enough for the optimal solver,
// shaped by a level designer rather than a random generator.
//
// The pieces: over the IWAD's maps in lump order, every subtree of the shipped nodes whose segs
// number between ceil(n/2) and n and whose parent's subtree has more than n (so no piece lies
// inside another); the seed picks one of them uniformly. Each seg becomes a segment from its v1 to
// its v2, its sector on the right as geometry/segment2.h wants; zero-length segs are left out.
#include <algorithm>
#include <array>
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "catalog.h"
#include "common/errors.h"
#include "common/rng.h"
#include "io/doom_iwads.h"
#include "io/doom_map.h"

namespace bsp {

namespace {

struct Piece {
  const VanillaNodes* nodes;  // owned by the caller's list of maps
  std::uint16_t root;         // a node index, or a subsector index with kSubsectorChild
};

// The segs under `root`, in tree order (front side first).
std::vector<std::uint16_t> segs_under(const VanillaNodes& nodes, std::uint16_t root) {
  std::vector<std::uint16_t> out, stack{root};
  std::vector<bool> seen(nodes.nodes.size(), false);
  while (!stack.empty()) {
    const std::uint16_t c = stack.back();
    stack.pop_back();
    if (c & kSubsectorChild) {
      const std::size_t s = c & ~kSubsectorChild;
      if (s >= nodes.subsectors.size()) continue;
      const Subsector& ss = nodes.subsectors[s];
      for (std::size_t i = ss.first; i < std::size_t{ss.first} + ss.count && i < nodes.segs.size(); ++i)
        out.push_back(static_cast<std::uint16_t>(i));
      continue;
    }
    if (c >= nodes.nodes.size() || seen[c]) continue;  // out of range, or a cycle
    seen[c] = true;
    for (int side = 1; side >= 0; --side) stack.push_back(nodes.nodes[c].child[side]);
  }
  return out;
}

// Each child's seg count, capped at `cap` (enough to tell a piece from a subtree too large), for
// every node, computed bottom-up in one pass: a node's count is its children's, a subsector's its
// own. Node records list children before parents in the vanilla layout; a child index not below
// its parent (a malformed lump, or a cycle) counts as `cap`.
std::vector<std::array<std::size_t, 2>> child_counts(const VanillaNodes& nodes, std::size_t cap) {
  std::vector<std::size_t> total(nodes.nodes.size(), cap);
  std::vector<std::array<std::size_t, 2>> out(nodes.nodes.size(), {cap, cap});
  for (std::size_t n = 0; n < nodes.nodes.size() && n < kSubsectorChild; ++n) {
    for (int side = 0; side < 2; ++side) {
      const std::uint16_t c = nodes.nodes[n].child[side];
      std::size_t count = cap;
      if (c & kSubsectorChild) {
        const std::size_t s = c & ~kSubsectorChild;
        if (s < nodes.subsectors.size()) count = std::min<std::size_t>(nodes.subsectors[s].count, cap);
      } else if (c < n) {
        count = total[c];
      }
      out[n][side] = count;
    }
    total[n] = std::min(cap, out[n][0] + out[n][1]);
  }
  return out;
}

// The topmost subtrees of one map's nodes holding min..max segs, in node order: the children that
// fit of every node whose own subtree holds more than max (a subtree within max lies inside one of
// those), and the root when the whole map fits.
void collect(const VanillaNodes& nodes, std::size_t min_segs, std::size_t max_segs, std::vector<Piece>& out) {
  const auto counts = child_counts(nodes, max_segs + 1);
  const auto fits = [&](std::size_t count) { return count >= min_segs && count <= max_segs; };
  for (std::size_t n = 0; n < counts.size(); ++n) {
    if (counts[n][0] + counts[n][1] <= max_segs) continue;
    for (int side = 0; side < 2; ++side)
      if (fits(counts[n][side])) out.push_back({&nodes, nodes.nodes[n].child[side]});
  }
  if (!counts.empty() && fits(counts.back()[0] + counts.back()[1]))
    out.push_back({&nodes, static_cast<std::uint16_t>(counts.size() - 1)});
}

std::vector<Polygon> make(const ParamSet& p) {
  const std::string iwad = p.choice("iwad") + ".wad";
  const auto max_segs = static_cast<std::size_t>(p.integer("n"));
  const std::size_t min_segs = (max_segs + 1) / 2;
  const Wad& wad = doom_wad(iwad);
  std::vector<VanillaNodes> maps;
  for (const std::string& name : map_names(wad)) {
    const DoomMap map = read_map(wad, name, doom_iwad_path(iwad));
    maps.push_back(read_vanilla_nodes(wad, map, doom_iwad_path(iwad)));
  }
  std::vector<Piece> pieces;
  for (const VanillaNodes& nodes : maps) collect(nodes, min_segs, max_segs, pieces);
  if (pieces.empty()) throw InputError(doom_iwad_path(iwad) + ": no subtree of its nodes holds the segs asked for");
  const Piece& piece = pieces[splitmix64(static_cast<std::uint64_t>(p.integer("seed"))) % pieces.size()];
  std::vector<Polygon> out;
  for (auto i : segs_under(*piece.nodes, piece.root)) {
    const Seg& s = piece.nodes->segs[i];
    const DoomVertex a = piece.nodes->vertices[s.v1], b = piece.nodes->vertices[s.v2];
    if (a.x == b.x && a.y == b.y) continue;
    out.push_back(Polygon{{Vertex{{double(a.x), double(a.y), 0}}, Vertex{{double(b.x), double(b.y), 0}}},
                          static_cast<std::uint32_t>(out.size())});
  }
  return out;
}

}  // namespace

GeneratorInfo doom_piece_generator() {
  return {"doom-piece",
          "2D: the segs under one subtree of the nodes a Freedoom IWAD ships, a small piece of a real level; where "
          "heuristics' gaps to the optimum are measured on real data",
          "the segs of the piece the seed picks: between ceil(n/2) and n (zero-length ones, if any, left out)",
          {{"n", ParamSpec::Kind::Integer, "most segs of a piece; the fewest are half as many", 30, 2, 1000, {}},
           seed_param(),
           {"iwad", ParamSpec::Kind::Choice, "the IWAD (Debian's freedoom package; BSPBENCH_DOOM_DIR to look elsewhere)",
            0, 0, 0, {"freedoom2", "freedoom1"}}},
          make,
          false,
          false,
          true};
}

}  // namespace bsp
