// CGAL's exact triangle-mesh intersection, timed: the yardstick for vericad's mesh mode
// (`vericad ssi A.stl B.stl`). Built by build.sh, run by run.py in this folder.
//
//   cgal_ssi A.stl B.stl [--repair] [--dump OUT.json]
//                             (STL binary or ASCII, OFF, OBJ, PLY: whatever CGAL's
//                              polygon-soup reader takes, chosen by extension)
//
// Prints one line of JSON:
//   {"polylines":P,"points":N,"closed":C,"faces_a":..,"faces_b":..,"read_ms":R,"intersection_ms":I,"cgal":"5.5.1"}
// read_ms covers reading both files and building both Surface_mesh; intersection_ms
// covers only CGAL::Polygon_mesh_processing::surface_intersection (kernel Epick: exact
// predicates, inexact constructions). --dump writes the polylines as JSON
// ([[[x,y,z],...],...], after the timing) for a point-by-point comparison. Exit 1 on
// unreadable input, 2 on bad arguments.
//
// The soups are turned into meshes as they are: run.py's height fields are valid,
// consistently oriented triangle meshes by construction. For other files pass --repair:
// a soup that is not a valid polygon mesh is then repaired and oriented first (checking
// that costs about as much as reading: 3.7 s and 290 MB more on 2 x 1M triangles).
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/IO/polygon_soup_io.h>
#include <CGAL/Polygon_mesh_processing/polygon_soup_to_polygon_mesh.h>
#include <CGAL/Polygon_mesh_processing/orient_polygon_soup.h>
#include <CGAL/Polygon_mesh_processing/repair_polygon_soup.h>
#include <CGAL/Polygon_mesh_processing/intersection.h>
#include <CGAL/version.h>

#include <chrono>
#include <cstdio>
#include <iostream>
#include <iterator>
#include <string>
#include <vector>

typedef CGAL::Exact_predicates_inexact_constructions_kernel K;
typedef K::Point_3 Point;
typedef CGAL::Surface_mesh<Point> Mesh;
namespace PMP = CGAL::Polygon_mesh_processing;

static bool read_mesh(const std::string& path, Mesh& mesh, bool repair) {
  std::vector<Point> points;
  std::vector<std::vector<std::size_t>> polygons;
  if (!CGAL::IO::read_polygon_soup(path, points, polygons) || polygons.empty()) {
    std::cerr << "cgal_ssi: cannot read a polygon soup from " << path << "\n";
    return false;
  }
  // STL repeats every vertex per facet; CGAL's reader merges identical points already.
  // With --repair, a soup that is not yet a valid polygon mesh is repaired (degenerate /
  // duplicate facets dropped) and oriented.
  if (repair && !PMP::is_polygon_soup_a_polygon_mesh(polygons)) {
    PMP::repair_polygon_soup(points, polygons);
    PMP::orient_polygon_soup(points, polygons);
  }
  PMP::polygon_soup_to_polygon_mesh(points, polygons, mesh);
  if (!CGAL::is_triangle_mesh(mesh)) {
    std::cerr << "cgal_ssi: " << path << " is not a triangle mesh\n";
    return false;
  }
  return true;
}

int main(int argc, char** argv) {
  const char* dump = nullptr;
  bool repair = false;
  std::vector<const char*> files;
  bool bad = false;
  for (int i = 1; i < argc; ++i) {
    std::string arg = argv[i];
    if (arg == "--repair") repair = true;
    else if (arg == "--dump" && i + 1 < argc) dump = argv[++i];
    else if (arg.rfind("--", 0) == 0) bad = true;
    else files.push_back(argv[i]);
  }
  if (bad || files.size() != 2) {
    std::cerr << "usage: cgal_ssi A.(stl|off|obj|ply) B.(stl|off|obj|ply) [--repair] [--dump OUT.json]\n";
    return 2;
  }
  typedef std::chrono::steady_clock Clock;
  auto ms = [](Clock::time_point a, Clock::time_point b) {
    return std::chrono::duration<double, std::milli>(b - a).count();
  };

  auto t0 = Clock::now();
  Mesh a, b;
  if (!read_mesh(files[0], a, repair) || !read_mesh(files[1], b, repair)) return 1;
  auto t1 = Clock::now();

  std::vector<std::vector<Point>> polylines;
  auto t2 = Clock::now();
  PMP::surface_intersection(a, b, std::back_inserter(polylines));
  auto t3 = Clock::now();

  std::size_t points = 0, closed = 0;
  for (const auto& p : polylines) {
    points += p.size();
    if (p.size() > 2 && p.front() == p.back()) ++closed;
  }
  std::printf("{\"polylines\":%zu,\"points\":%zu,\"closed\":%zu,\"faces_a\":%zu,\"faces_b\":%zu,"
              "\"read_ms\":%.3f,\"intersection_ms\":%.3f,\"cgal\":\"%s\"}\n",
              polylines.size(), points, closed, (std::size_t)num_faces(a), (std::size_t)num_faces(b),
              ms(t0, t1), ms(t2, t3), CGAL_STR(CGAL_VERSION));
  if (dump) {
    std::FILE* f = std::fopen(dump, "w");
    if (!f) {
      std::cerr << "cgal_ssi: cannot write " << dump << "\n";
      return 1;
    }
    std::fputc('[', f);
    for (std::size_t i = 0; i < polylines.size(); ++i) {
      std::fputs(i ? ",\n[" : "[", f);
      for (std::size_t j = 0; j < polylines[i].size(); ++j) {
        const Point& q = polylines[i][j];
        std::fprintf(f, "%s[%.17g,%.17g,%.17g]", j ? "," : "", q.x(), q.y(), q.z());
      }
      std::fputc(']', f);
    }
    std::fputs("]\n", f);
    std::fclose(f);
  }
  return 0;
}
