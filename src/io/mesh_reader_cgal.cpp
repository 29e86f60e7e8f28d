#include "io/mesh_reader_cgal.h"

#include <CGAL/IO/polygon_soup_io.h>
#include <CGAL/Simple_cartesian.h>

#include <exception>
#include <mutex>
#include <sstream>

namespace bsp {

namespace {

// std::cerr sent to `sink` while it lives, restored however the scope ends.
class CerrTo {
 public:
  explicit CerrTo(std::streambuf* sink) : old_(std::cerr.rdbuf(sink)) {}
  ~CerrTo() { std::cerr.rdbuf(old_); }
  CerrTo(const CerrTo&) = delete;
  CerrTo& operator=(const CerrTo&) = delete;

 private:
  std::streambuf* old_;
};

}  // namespace

bool read_polygon_soup_cgal(const std::string& path, PolygonSoup& soup, std::string& error) {
  using Point = CGAL::Simple_cartesian<double>::Point_3;
  std::vector<Point> points;
  std::vector<std::vector<std::size_t>> faces;
  bool ok = false;
  {
    // CGAL's readers report details on std::cerr; keep them out of our one-line errors. std::cerr
    // is one stream for the process, so its buffer is one reader's at a time: two sweep jobs
    // reading meshes at once restored each other's buffers, one already destroyed (a crash).
    static std::mutex cerr_swap;
    const std::lock_guard<std::mutex> lock(cerr_swap);
    std::ostringstream sink;
    const CerrTo quiet(sink.rdbuf());
    try {
      ok = CGAL::IO::read_polygon_soup(path, points, faces, CGAL::parameters::verbose(false));
    } catch (const std::exception& e) {
      error = e.what();
    }
  }
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
