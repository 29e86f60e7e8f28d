#pragma once
// The only door to CGAL's readers; no CGAL type crosses it.
#include <array>
#include <cstddef>
#include <string>
#include <vector>

namespace bsp {

struct PolygonSoup {
  std::vector<std::array<double, 3>> points;
  std::vector<std::vector<std::size_t>> faces;
};

// CGAL::IO::read_polygon_soup; false with `error` set when CGAL rejects the file.
bool read_polygon_soup_cgal(const std::string& path, PolygonSoup& soup, std::string& error);

}  // namespace bsp
