#include "io/mesh_reader_cgal.h"

#include <CGAL/IO/polygon_soup_io.h>
#include <CGAL/Simple_cartesian.h>

#include <exception>
#include <sstream>

namespace bsp {

bool read_polygon_soup_cgal(const std::string& path, PolygonSoup& soup, std::string& error) {
  using Point = CGAL::Simple_cartesian<double>::Point_3;
  std::vector<Point> points;
  std::vector<std::vector<std::size_t>> faces;
  // CGAL's readers report details on std::cerr; keep them out of our one-line errors.
  std::ostringstream sink;
  auto* old = std::cerr.rdbuf(sink.rdbuf());
  bool ok = false;
  try {
    ok = CGAL::IO::read_polygon_soup(path, points, faces, CGAL::parameters::verbose(false));
  } catch (const std::exception& e) {
    error = e.what();
  }
  std::cerr.rdbuf(old);
  if (!ok) {
    if (error.empty()) error = "CGAL could not parse it as a polygon soup";
    return false;
  }
  soup.points.reserve(points.size());
  for (const auto& p : points) soup.points.push_back({p.x(), p.y(), p.z()});
  soup.faces = std::move(faces);
  return true;
}

}  // namespace bsp
