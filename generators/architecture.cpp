// architecture: a game-level-like building. Each story is a g x g grid of cells whose columns and
// rows alternate between rooms (random widths) and corridors (narrow), separated by thick walls.
// Every interior wall has a door, every exterior wall a window; walls are built the way level
// editors build them: quads around the opening on both faces plus the reveal (jambs, head, sill)
// across the wall's thickness. Square pillars fill the wall corners so no two pieces cross; floors
// and ceilings are one quad per cell, and a gabled roof (two slanted quads, two gable triangles)
// covers every cell of the top story.
//
// What it shows: thousands of exactly coplanar polygons (all floors of a story share a plane, every
// wall face its wall line), polygons meeting along edges and T-junctions, both facing directions on
// shared planes (back-to-back gables), and an axis-aligned structure where the right cuts are free.
#include <algorithm>

#include "catalog.h"
#include "common/rng.h"
#include "shapes.h"

namespace bsp {

namespace {

// Dimensions in metres, typical of game levels.
constexpr double kStoryHeight = 3.0;
constexpr double kSlab = 0.25;       // floor slab: the ceiling sits this far below the next floor
constexpr double kWall = 0.2;        // wall (and pillar) thickness
constexpr double kRoomMin = 3.0, kRoomMax = 6.0;
constexpr double kCorridorMin = 1.4, kCorridorMax = 2.0;
constexpr double kPier = 0.15;       // least wall left on either side of an opening
constexpr double kDoorMin = 0.8, kDoorMax = 1.2, kDoorHeightMin = 2.0, kDoorHeightMax = 2.4;
constexpr double kWindowMin = 0.6, kWindowMax = 1.5, kSillMin = 0.8, kSillMax = 1.0;
constexpr double kWindowHeightMin = 1.0, kWindowHeightMax = 1.4;
constexpr double kRoofMin = 0.6, kRoofMax = 1.8;  // ridge height above the eaves

// Independent random streams per kind of item.
enum Stream : std::uint64_t { kColumns = 1, kRows, kWallsY, kWallsX, kRoofs };

const Vec3 kUp{0, 0, 1};

struct Layout {
  std::size_t g = 1, stories = 1;
  std::vector<double> xs, ys;  // grid lines, g + 1 each
  std::uint64_t seed = 0;

  double floor_z(std::size_t s) const { return static_cast<double>(s) * kStoryHeight; }
  double wall_height() const { return kStoryHeight - kSlab; }
};

// Even columns (rows) are rooms, odd ones corridors.
std::vector<double> grid_lines(std::size_t g, std::uint64_t stream) {
  std::vector<double> lines{0.0};
  for (std::size_t c = 0; c < g; ++c) {
    Rng rng(stream_seed(stream, c));
    const double w = c % 2 == 0 ? rng.uniform(kRoomMin, kRoomMax) : rng.uniform(kCorridorMin, kCorridorMax);
    lines.push_back(lines.back() + w);
  }
  return lines;
}

void floor_and_ceiling(const Layout& l, std::size_t s, std::size_t i, std::size_t j, std::vector<Polygon>& out) {
  const Vec3 lo{l.xs[i], l.ys[j], l.floor_z(s)};
  const Vec3 dx{l.xs[i + 1] - l.xs[i], 0, 0}, dy{0, l.ys[j + 1] - l.ys[j], 0};
  out.push_back(parallelogram(lo, dx, dy));
  out.push_back(flipped(parallelogram(lo + kUp * l.wall_height(), dx, dy)));
}

// A wall opening in wall coordinates: u along the wall from its start, v up from the floor.
struct Opening {
  double u0, u1, v0, v1;  // v0 == 0 for a door
};

Opening random_opening(Rng& rng, double length, bool door) {
  const double room = length - 2 * kPier;
  const double w = std::min(door ? rng.uniform(kDoorMin, kDoorMax) : rng.uniform(kWindowMin, kWindowMax), room);
  const double u0 = kPier + rng.uniform() * (room - w);
  if (door) return {u0, u0 + w, 0.0, rng.uniform(kDoorHeightMin, kDoorHeightMax)};
  const double sill = rng.uniform(kSillMin, kSillMax);
  return {u0, u0 + w, sill, sill + rng.uniform(kWindowHeightMin, kWindowHeightMax)};
}

// A wall of thickness kWall centred on the line start + a * u (u in [0, length]), with an opening:
// face pieces on both sides around the opening, then its reveal. A door (v0 == 0) makes 3 pieces a
// side plus 3 reveal quads (9); a window 4 a side plus 4 (12).
void wall(const Vec3& start, const Vec3& a, double length, double height, const Opening& o,
          std::vector<Polygon>& out) {
  const Vec3 nrm = cross(a, kUp);  // parallelogram(.., a, up) faces +nrm
  const Vec3 half = nrm * (0.5 * kWall), through = nrm * kWall;
  const bool door = o.v0 == 0.0;
  auto pieces = [&](const Vec3& face, bool front) {
    auto piece = [&](double ua, double ub, double va, double vb) {
      Polygon p = parallelogram(face + a * ua + kUp * va, a * (ub - ua), kUp * (vb - va));
      out.push_back(front ? std::move(p) : flipped(std::move(p)));
    };
    piece(0, o.u0, 0, height);
    piece(o.u1, length, 0, height);
    piece(o.u0, o.u1, o.v1, height);
    if (!door) piece(o.u0, o.u1, 0, o.v0);
  };
  pieces(start + half, true);
  pieces(start - half, false);
  const Vec3 back = start - half;
  const double w = o.u1 - o.u0, h = o.v1 - o.v0;
  out.push_back(parallelogram(back + a * o.u0 + kUp * o.v0, kUp * h, through));  // jamb facing +a
  out.push_back(parallelogram(back + a * o.u1 + kUp * o.v0, through, kUp * h));  // jamb facing -a
  out.push_back(parallelogram(back + a * o.u0 + kUp * o.v1, a * w, through));    // head facing down
  if (!door) out.push_back(parallelogram(back + a * o.u0 + kUp * o.v0, through, a * w));  // sill, up
}

// Wall segment `k` of grid line `line` on story s. along_y: the wall lies on x = xs[line] and runs
// between ys[k] and ys[k + 1]; otherwise on y = ys[line] between xs[k] and xs[k + 1]. The wall
// stops half a thickness short of each grid corner, where a pillar stands.
void wall_segment(const Layout& l, bool along_y, std::size_t s, std::size_t line, std::size_t k,
                  std::uint64_t index, std::vector<Polygon>& out) {
  const auto& cross_lines = along_y ? l.ys : l.xs;
  const double fixed = (along_y ? l.xs : l.ys)[line];
  const Vec3 a = along_y ? Vec3{0, 1, 0} : Vec3{1, 0, 0};
  const double begin = cross_lines[k] + 0.5 * kWall, length = cross_lines[k + 1] - cross_lines[k] - kWall;
  const Vec3 start = along_y ? Vec3{fixed, begin, l.floor_z(s)} : Vec3{begin, fixed, l.floor_z(s)};
  Rng rng(stream_seed(stream_seed(l.seed, along_y ? kWallsY : kWallsX), index));
  const bool exterior = line == 0 || line == l.g;
  wall(start, a, length, l.wall_height(), random_opening(rng, length, !exterior), out);
}

void pillar(const Layout& l, std::size_t s, std::size_t i, std::size_t j, std::vector<Polygon>& out) {
  const double r = 0.5 * kWall, h = l.wall_height();
  const Vec3 c{l.xs[i], l.ys[j], l.floor_z(s)};
  const Vec3 x{kWall, 0, 0}, y{0, kWall, 0}, up = kUp * h;
  out.push_back(parallelogram(c + Vec3{-r, -r, 0}, x, up));  // faces -y
  out.push_back(parallelogram(c + Vec3{r, -r, 0}, y, up));   // faces +x
  out.push_back(parallelogram(c + Vec3{r, r, 0}, x * -1, up));   // faces +y
  out.push_back(parallelogram(c + Vec3{-r, r, 0}, y * -1, up));  // faces -x
}

// Gabled roof over cell (i, j), ridge along x at mid y.
void roof(const Layout& l, std::size_t i, std::size_t j, std::vector<Polygon>& out) {
  Rng rng(stream_seed(stream_seed(l.seed, kRoofs), j * l.g + i));
  const double z = l.floor_z(l.stories), ridge = z + rng.uniform(kRoofMin, kRoofMax);
  const double x0 = l.xs[i], x1 = l.xs[i + 1], y0 = l.ys[j], y1 = l.ys[j + 1], ym = 0.5 * (y0 + y1);
  out.push_back(quad({x0, y0, z}, {x1, y0, z}, {x1, ym, ridge}, {x0, ym, ridge}));
  out.push_back(quad({x1, y1, z}, {x0, y1, z}, {x0, ym, ridge}, {x1, ym, ridge}));
  out.push_back(triangle({x0, y1, z}, {x0, y0, z}, {x0, ym, ridge}));
  out.push_back(triangle({x1, y0, z}, {x1, y1, z}, {x1, ym, ridge}));
}

std::size_t polygon_count(std::size_t g, std::size_t stories) {
  return stories * (24 * g * g + 38 * g + 4) + 4 * g * g;
}

std::vector<Polygon> make(const ParamSet& p) {
  Layout l;
  l.stories = static_cast<std::size_t>(p.integer("stories"));
  l.seed = seed_of(p);
  while (polygon_count(l.g + 1, l.stories) <= count_of(p)) ++l.g;
  l.xs = grid_lines(l.g, stream_seed(l.seed, kColumns));
  l.ys = grid_lines(l.g, stream_seed(l.seed, kRows));
  const std::size_t g = l.g, cells = g * g, walls = (g + 1) * g, corners = (g + 1) * (g + 1);
  const std::size_t per_story = cells + 2 * walls + corners;
  return generate_items(l.stories * per_story + cells, [&](std::size_t item, std::vector<Polygon>& out) {
    const std::size_t s = item / per_story;
    if (s == l.stories) return roof(l, (item - s * per_story) % g, (item - s * per_story) / g, out);
    std::size_t k = item % per_story;
    if (k < cells) return floor_and_ceiling(l, s, k % g, k / g, out);
    k -= cells;
    if (k < 2 * walls) {
      const bool along_y = k < walls;
      const std::size_t w = k % walls;
      return wall_segment(l, along_y, s, w / g, w % g, s * walls + w, out);
    }
    k -= 2 * walls;
    pillar(l, s, k % (g + 1), k / (g + 1), out);
  });
}

}  // namespace

GeneratorInfo architecture_generator() {
  return {"architecture",
          "game-level building: rooms and corridors with thick walls, doors, windows and gabled roofs; "
          "many exactly coplanar polygons",
          "stories * (24 g^2 + 38 g + 4) + 4 g^2 polygons, g the largest grid size (at least 1) keeping that "
          "within n; per story: 2 per cell (floor, ceiling), 9 per interior wall (2 g (g-1), with a door), "
          "12 per exterior wall (4 g, with a window), 4 per pillar ((g+1)^2); 4 per roof cell (g^2)",
          {n_param(5000, "largest number of polygons; the grid size g is chosen to stay within it"), seed_param(),
           {"stories", ParamSpec::Kind::Integer, "number of stories", 2, 1, 64, {}}},
          make,
          true};
}

}  // namespace bsp
