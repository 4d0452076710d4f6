// CGAL 5.5 backend of peer_subdivide: Subdivision_method_3 on a Surface_mesh
// with Simple_cartesian<double> points, number_of_iterations(levels) in one call
// (for sqrt3 the boundary rule alternates within one call, see peer-rules.md).
#include "peer_common.hpp"

#include <CGAL/Polygon_mesh_processing/orient_polygon_soup.h>
#include <CGAL/Polygon_mesh_processing/polygon_soup_to_polygon_mesh.h>
#include <CGAL/Simple_cartesian.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/boost/graph/helpers.h>
#include <CGAL/subdivision_method_3.h>

#include <string>
#include <vector>

namespace peer {
namespace {

using K = CGAL::Simple_cartesian<double>;
using Point = K::Point_3;
using SM = CGAL::Surface_mesh<Point>;

}  // namespace

Outcome run_cgal(Scheme s, int levels, const Mesh& in, Mesh& out) {
  namespace PMP = CGAL::Polygon_mesh_processing;
  namespace SD = CGAL::Subdivision_method_3;

  std::vector<Point> pts;
  pts.reserve(in.nv());
  for (std::size_t v = 0; v < in.nv(); ++v)
    pts.emplace_back(in.xyz[3 * v], in.xyz[3 * v + 1], in.xyz[3 * v + 2]);
  std::vector<std::vector<std::size_t>> polys(in.nf());
  std::size_t k = 0;
  for (std::size_t f = 0; f < in.nf(); ++f) {
    polys[f].reserve(std::size_t(in.fsize[f]));
    for (int j = 0; j < in.fsize[f]; ++j) polys[f].push_back(std::size_t(in.fidx[k++]));
  }
  // CGAL's own verdict first, then the harness's manifold check as a net.
  if (!PMP::is_polygon_soup_a_polygon_mesh(polys))
    return Outcome::reject(
        "CGAL is_polygon_soup_a_polygon_mesh: not an oriented 2-manifold polygon mesh");
  std::string err;
  if (!validate_manifold_mesh(in, err)) return Outcome::reject(err);

  SM sm;
  PMP::polygon_soup_to_polygon_mesh(pts, polys, sm);
  if (sm.number_of_faces() != in.nf() || sm.number_of_vertices() != in.nv() ||
      !CGAL::is_valid_polygon_mesh(sm))
    return Outcome::reject("CGAL polygon_soup_to_polygon_mesh gave an invalid Surface_mesh");

  if (levels > 0) {
    const auto np = CGAL::parameters::number_of_iterations(levels);
    switch (s) {
      case Scheme::Loop:
        if (!CGAL::is_triangle_mesh(sm)) return Outcome::reject("CGAL Loop needs a triangle mesh");
        SD::Loop_subdivision(sm, np);
        break;
      case Scheme::CatmullClark:
        SD::CatmullClark_subdivision(sm, np);
        break;
      case Scheme::DooSabin:
        SD::DooSabin_subdivision(sm, np);
        break;
      case Scheme::Sqrt3:
        if (!CGAL::is_triangle_mesh(sm)) return Outcome::reject("CGAL Sqrt3 needs a triangle mesh");
        SD::Sqrt3_subdivision(sm, np);
        break;
      default:
        return Outcome::reject("internal: scheme not available in CGAL");
    }
  }

  out.clear();
  // Indices are dense (the hosts never remove elements), but map anyway.
  std::vector<int> idx(sm.num_vertices(), -1);
  int n = 0;
  for (SM::Vertex_index v : sm.vertices()) {
    const Point& p = sm.point(v);
    out.add_vertex(p.x(), p.y(), p.z());
    idx[std::size_t(v)] = n++;
  }
  for (SM::Face_index f : sm.faces()) {
    int c = 0;
    for (SM::Vertex_index v : CGAL::vertices_around_face(sm.halfedge(f), sm)) {
      out.fidx.push_back(idx[std::size_t(v)]);
      ++c;
    }
    out.fsize.push_back(c);
  }
  return Outcome::ok();
}

}  // namespace peer
