// nlsubdiv_cgal.h: nlsubdiv's subdivision schemes for CGAL polygon meshes (Surface_mesh,
// Polyhedron_3, any MutableFaceGraph with a Point_3 vertex point map).
//
// Header-only, C++17, over include/nlsubdiv.h (link libnlsubdiv; CGAL 5.5 is header-only).
//
//   #include <nlsubdiv/cgal/nlsubdiv_cgal.h>
//   namespace SM3 = nlsubdiv::Subdivision_method_3;
//   try {
//     SM3::Mobius_Loop_subdivision(mesh, nlsubdiv::parameters::number_of_iterations(3).strict(true));
//   } catch (const SM3::Subdivision_error& e) {  // the mesh is unchanged
//     std::cerr << e.what() << "\n";
//   }
//
// The entry points are nlsubdiv::Subdivision_method_3::*_subdivision (one per scheme, linear
// and Mobius_*, and Differential_*), in the style of CGAL::Subdivision_method_3: a polygon
// mesh, CGAL named parameters (CGAL's own and nlsubdiv::parameters::strict, literal,
// linear_weight, vertex_linear_weight_map, crease_sharpness, corner_sharpness, crease_method, report,
// threads,
// vertex_curvature_scale_map, solver_max_iterations, solver_tolerance, dirmag_levels), no
// return value, nlsubdiv::cgal::Subdivision_error on failure. The lowercase functions of
// nlsubdiv::cgal (mobius_loop_subdivision, ...) are deprecated, kept for one version.
//
// Three layers (docs/integrations.md):
// * Mobius_loop_mask_3 and Mobius_butterfly_mask_3 (Star_mask_3): PTQMask_3s that evaluate
//   the star rules (nls_mobius_loop_star / nls_mobius_butterfly_star, nls_f4_hinted,
//   nls_f4) with the mesh's own connectivity. They run the paper's rules, equal to nls_mesh_subdivide with NLS_SUBDIVIDE_LITERAL (the
//   driver's default fold guard needs a pass over the whole mesh, which a per-star mask cannot
//   make); Mobius_butterfly_driver_mask_3 gives the guarded default for Butterfly;
// * Driver_mask_3 (aliases Mobius_catmull_clark_mask_3 and Mobius_kobbelt_mask_3 for PQQ,
//   Mobius_butterfly_driver_mask_3, Linear_butterfly_mask_3 and Linear_kobbelt_mask_3):
//   masks whose level is evaluated by the driver (nls_mesh_subdivide) on a flat copy of the
//   current level, each callback a lookup: for rules that need more than a star (Kobbelt's
//   virtual points) or whose face points depend on which corner a face starts at
//   (Catmull–Clark, Kobbelt: the mask starts every face of a refined level at its old-vertex
//   corner, as the driver's quad pattern does, so levels chain like the driver's);
// * free functions for every scheme, in CGAL's named-parameter style: mask + host where a
//   mask fits, otherwise the bulk path (flat copy -> nls_mesh_subdivide -> mesh rebuilt);
//   Spherelike_subdivision (bulk) and Differential_{Loop,Butterfly,DirMag}_subdivision (flat
//   copy -> one nls_differential_subdivide call for all levels -> mesh rebuilt).
//
// Masks compute the whole level when it is first touched and record any error in their
// Report (CGAL's callbacks return void; masks never throw). The free functions
// evaluate each level *before* the host changes the mesh, so a refused level leaves the mesh
// untouched; when a later level of a multi-level call fails, the mesh is restored from a copy
// made before the first level (copy-assignment of the PolygonMesh: the vertex point map must
// be the mesh's own, which is the default).
//
// Licence: part of nlsubdiv (MIT OR Apache-2.0); CGAL's headers are LGPL-3.0+/commercial.
#ifndef NLSUBDIV_CGAL_H
#define NLSUBDIV_CGAL_H

#include <CGAL/Named_function_parameters.h>
#include <CGAL/Subdivision_method_3/subdivision_hosts_3.h>
#include <CGAL/boost/graph/Euler_operations.h>
#include <CGAL/boost/graph/helpers.h>
#include <CGAL/boost/graph/iterator.h>
#include <CGAL/boost/graph/named_params_helper.h>

#include <cstdio>
#include <functional>
#include <memory>
#include <stdexcept>
#include <string>
#include <unordered_map>
#include <vector>

#include "../common/nlsubdiv_flat.hh"
#include "../common/nlsubdiv_pool.hh"
#include "nlsubdiv.h"

namespace nlsubdiv {

/// nlsubdiv's own named-parameter tags (CGAL 5.5's scheme: one enum type per parameter, its
/// one value the query tag for CGAL::parameters::get_parameter). The functions that set them
/// are in nlsubdiv::parameters (below).
namespace internal_np {
enum strict_t { strict };
enum literal_t { literal };
enum linear_weight_t { linear_weight };
enum crease_sharpness_t { crease_sharpness };
enum corner_sharpness_t { corner_sharpness };
enum crease_method_t { crease_method };
enum report_t { report };
enum vertex_curvature_scale_map_t { vertex_curvature_scale_map };
enum edge_sharpness_map_t { edge_sharpness_map };
enum vertex_sharpness_map_t { vertex_sharpness_map };
enum vertex_linear_weight_map_t { vertex_linear_weight_map };
enum solver_max_iterations_t { solver_max_iterations };
enum solver_tolerance_t { solver_tolerance };
enum dirmag_levels_t { dirmag_levels };
enum threads_t { threads };
}  // namespace internal_np

namespace cgal {

/// Options of the masks and functions.
struct Options {
  /// Fallbacks become NLS_STATUS_FALLBACK_IN_STRICT_MODE, and the input is refused for what
  /// the kernel accepts by policy but is most likely a mistake (nlsubdiv::flat::strict_check).
  bool strict = false;
  /// Sharp features: the sharpness given to the edges of the named parameter
  /// `edge_is_constrained_map` (OpenSubdiv's scale: 10 or more infinitely sharp) and to the
  /// vertices of `vertex_is_constrained_map` (corners).
  double crease_sharpness = 10.0;
  double corner_sharpness = 10.0;
  /// NLS_CREASE_UNIFORM or NLS_CREASE_CHAIKIN.
  uint32_t crease_method = NLS_CREASE_UNIFORM;
  /// Möbius schemes: NLS_SUBDIVIDE_LITERAL (the paper's rules without the driver's fold
  /// guard). The star-rule masks are always literal.
  bool literal = false;
  /// Möbius schemes: nls_subdivide_options::linear_weight, the weight of the linear result in
  /// the Möbius–linear spectrum (seed 000 §7.2): 0 Möbius, 1 linear, bit for bit. The star-rule
  /// masks evaluate weight 0 only.
  double linear_weight = 0.0;
  /// Threads of the kernel's passes (nls_subdivide_options::executor), the calling thread
  /// included: 1 the calling thread only, 0 the hardware's thread count. The result is the
  /// same bits for every count. The star-rule masks and the differential functions run on the
  /// calling thread.
  unsigned threads = 1;
  /// The pool of `threads` threads, started on first use and shared by the copies of these
  /// options (a mask evaluates every level with the same pool).
  std::shared_ptr<nlsubdiv::ThreadPool> pool;
};

/// Options of the differential functions (nls_differential_options; seed 001 §3): the
/// reconstruction's iteration cap (reaching it is NLS_STATUS_NOT_CONVERGED, mesh unchanged),
/// its relative residual tolerance, and for DirMag the number of DirMag levels (at least 1).
struct DifferentialOptions {
  uint32_t max_iterations = 100;
  double tolerance = 1e-10;
  uint32_t dirmag_levels = 1;
  bool strict = false;  ///< the strict input checks (nlsubdiv::flat::strict_check) first
};

/// What a call did: `status` (NLS_STATUS_OK on success), the element it names (a face or
/// vertex of the level's flat copy, or an output vertex; NLS_NO_ELEMENT), the 1-based level,
/// the fallbacks (elements that took the documented linear rule), and the path taken.
struct Report {
  nls_status status = NLS_STATUS_OK;
  uint32_t element = NLS_NO_ELEMENT;
  uint32_t level = 0;
  uint32_t fallbacks = 0;
  const char* path = "";  ///< "star rules", "driver mask", "bulk" or "differential"
  /// Differential schemes only: the reconstruction's iterations and relative residual
  /// (nls_differential_report; also set on NLS_STATUS_NOT_CONVERGED).
  uint32_t iterations = 0;
  double residual = 0.0;
  bool ok() const { return status == NLS_STATUS_OK; }
  std::string message() const {
    if (ok()) return "ok";
    char buf[64];
    std::snprintf(buf, sizeof buf, "level %u: ", level);
    std::string m = std::string(buf) + nls_status_str(status);
    if (element != NLS_NO_ELEMENT) {
      std::snprintf(buf, sizeof buf, " (%s %u)", nlsubdiv::flat::element_kind(status), element);
      m += buf;
    }
    return m;
  }
};

using FlatMesh = nlsubdiv::flat::FlatMesh;

namespace detail {

using P3 = std::array<double, 3>;
inline bool finite3(const P3& p) { return std::isfinite(p[0]) && std::isfinite(p[1]) && std::isfinite(p[2]); }
inline P3 nan3() { return {NAN, NAN, NAN}; }
inline P3 add(const P3& a, const P3& b) { return {a[0] + b[0], a[1] + b[1], a[2] + b[2]}; }
inline P3 scale(const P3& a, double s) { return {a[0] * s, a[1] * s, a[2] * s}; }

inline uint64_t edge_key(uint32_t a, uint32_t b) {
  return (static_cast<uint64_t>(std::min(a, b)) << 32) | std::max(a, b);
}

/// A contiguous numbering of the current level and its flat copy. Vertices and faces in
/// iteration order; each face from `start[f]` (corners[i] = target of the i-th half-edge
/// from it): the face's own half-edge on the first level, the half-edge into its corner of
/// the previous level (vertex index < nv_prev) on refined levels when there is one, as the
/// driver's quad pattern starts its faces.
template <class PM>
struct Level {
  typedef typename boost::graph_traits<PM>::vertex_descriptor vertex_descriptor;
  typedef typename boost::graph_traits<PM>::halfedge_descriptor halfedge_descriptor;
  typedef typename boost::graph_traits<PM>::face_descriptor face_descriptor;
  std::unordered_map<vertex_descriptor, uint32_t> vid;
  std::vector<vertex_descriptor> verts;
  std::unordered_map<face_descriptor, uint32_t> fid;
  std::vector<face_descriptor> faces;
  std::vector<halfedge_descriptor> start;
  FlatMesh flat;

  template <class VPM>
  void build(const PM& pm, VPM vpm, std::size_t nv_prev) {
    vid.clear();
    verts.clear();
    fid.clear();
    faces.clear();
    start.clear();
    flat.positions.clear();
    flat.offsets.assign(1, 0);
    flat.indices.clear();
    for (auto v : CGAL::vertices(pm)) {
      vid.emplace(v, static_cast<uint32_t>(verts.size()));
      verts.push_back(v);
      const auto& p = get(vpm, v);
      flat.positions.push_back(CGAL::to_double(p.x()));
      flat.positions.push_back(CGAL::to_double(p.y()));
      flat.positions.push_back(CGAL::to_double(p.z()));
    }
    for (auto f : CGAL::faces(pm)) {
      fid.emplace(f, static_cast<uint32_t>(faces.size()));
      faces.push_back(f);
      halfedge_descriptor h0 = halfedge(f, pm);
      if (nv_prev != SIZE_MAX)
        for (auto h : CGAL::halfedges_around_face(halfedge(f, pm), pm))
          if (vid.at(target(h, pm)) < nv_prev) {
            h0 = h;
            break;
          }
      start.push_back(h0);
      for (auto h : CGAL::halfedges_around_face(h0, pm)) flat.indices.push_back(vid.at(target(h, pm)));
      flat.offsets.push_back(static_cast<uint32_t>(flat.indices.size()));
    }
  }
  P3 pos(vertex_descriptor v) const {
    const uint32_t i = vid.at(v);
    return {flat.positions[3 * i], flat.positions[3 * i + 1], flat.positions[3 * i + 2]};
  }
};

template <class Point>
Point to_point(const P3& p) {
  return Point(p[0], p[1], p[2]);
}

/// State shared by the copies of a mask (CGAL's hosts take masks by value): the level last
/// evaluated, its results and the report.
template <class PM>
struct MaskState {
  typedef typename boost::graph_traits<PM>::vertex_descriptor vertex_descriptor;
  typedef typename boost::graph_traits<PM>::face_descriptor face_descriptor;
  Level<PM> level;
  std::size_t evaluated_nv = SIZE_MAX;  // vertex count of the level evaluated
  std::size_t nv_prev = SIZE_MAX;       // vertex count of the level before it (face starts)
  uint32_t level_no = 0;
  bool failed = false;
  Options opts;
  Report report;
  std::vector<P3> vertex_pt;                    // by vertex index
  std::unordered_map<uint64_t, P3> edge_pt;     // by (min, max) vertex pair
  std::vector<P3> face_pt;                      // by face index (quad schemes)

  bool fail(nls_status s, uint32_t el) {
    failed = true;
    if (report.ok()) {
      report.status = s;
      report.element = el;
      report.level = level_no;
    }
    return false;
  }
};

/// The executor of `o`: NULL for one thread, otherwise its pool's (started here on first use).
inline const nls_executor* executor_of(Options& o) {
  if (o.threads != 1 && !o.pool) o.pool = std::make_shared<nlsubdiv::ThreadPool>(o.threads);
  return o.pool ? o.pool->executor() : nullptr;
}

/// Evaluates the level of `st` (its flat copy) with the driver and fills the lookup tables
/// (old vertices, edge points by (min, max) pair, face points of the quad schemes).
template <class PM>
bool fill_from_driver(MaskState<PM>& st, uint32_t scheme, uint32_t flags) {
  const FlatMesh& in = st.level.flat;
  uint32_t el = NLS_NO_ELEMENT, fallbacks = 0;
  FlatMesh out;
  nls_status s =
      nlsubdiv::flat::run_levels(scheme, flags, in, 1, out, el, fallbacks, nullptr, st.opts.linear_weight, nullptr,
                                 executor_of(st.opts));
  if (s != NLS_STATUS_OK) return st.fail(s, el);
  st.report.fallbacks += fallbacks;
  const std::size_t n = in.vertex_count();
  std::vector<uint64_t> keys;
  for (std::size_t f = 0; f + 1 < in.offsets.size(); ++f)
    for (uint32_t c = in.offsets[f]; c < in.offsets[f + 1]; ++c) {
      const uint32_t a = in.indices[c], b = in.indices[c + 1 < in.offsets[f + 1] ? c + 1 : in.offsets[f]];
      keys.push_back(edge_key(a, b));
    }
  std::sort(keys.begin(), keys.end());
  keys.erase(std::unique(keys.begin(), keys.end()), keys.end());
  auto P = [&](std::size_t i) { return P3{out.positions[3 * i], out.positions[3 * i + 1], out.positions[3 * i + 2]}; };
  st.vertex_pt.assign(n, nan3());
  for (std::size_t i = 0; i < n; ++i) st.vertex_pt[i] = P(i);
  st.edge_pt.clear();
  for (std::size_t e = 0; e < keys.size(); ++e) st.edge_pt.emplace(keys[e], P(n + e));
  st.face_pt.clear();
  if (scheme == NLS_SCHEME_CATMULL_CLARK || scheme == NLS_SCHEME_KOBBELT) {
    st.face_pt.resize(in.face_count());
    for (std::size_t f = 0; f < in.face_count(); ++f) st.face_pt[f] = P(n + keys.size() + f);
  }
  return true;
}

}  // namespace detail

// ---------------------------------------------------------------------------------------
// Driver masks: the level evaluated by nls_mesh_subdivide, callbacks are lookups.
// ---------------------------------------------------------------------------------------

/// A PTQMask_3 (Scheme Loop or Modified Butterfly) or PQQMask_3 (Catmull–Clark, Kobbelt)
/// whose level is computed by the driver on a flat copy of the mesh: the result of a
/// host step equals one nls_mesh_subdivide level (order-independently; the driver's rounding
/// where vertex numbering enters, e.g. the orientation of an edge blend).
template <class PolygonMesh, uint32_t Scheme, uint32_t Flags,
          class VertexPointMap = typename boost::property_map<PolygonMesh, CGAL::vertex_point_t>::type>
class Driver_mask_3 {
 public:
  static constexpr uint32_t scheme = Scheme;
  static constexpr uint32_t flags = Flags;
  typedef PolygonMesh Mesh;
  typedef typename boost::graph_traits<Mesh>::vertex_descriptor vertex_descriptor;
  typedef typename boost::graph_traits<Mesh>::halfedge_descriptor halfedge_descriptor;
  typedef typename boost::graph_traits<Mesh>::face_descriptor face_descriptor;
  typedef typename boost::property_traits<VertexPointMap>::value_type Point;

  Driver_mask_3(Mesh* pmesh, VertexPointMap vpm, Options opts = Options())
      : pmesh_(pmesh), vpm_(vpm), st_(std::make_shared<detail::MaskState<Mesh>>()) {
    st_->opts = opts;
  }

  /// Evaluates the current level now (the callbacks do it on first use); false on error.
  bool evaluate() { return ensure(); }
  /// The report of the levels evaluated so far (the first error is kept).
  const Report& report() const { return st_->report; }
  /// Sets the vertex count of the level before the current one (its vertices start the faces
  /// of the current level; the free functions do this).
  void set_previous_vertex_count(std::size_t n) { st_->nv_prev = n; }

  void face_node(face_descriptor f, Point& pt) {
    ensure();
    pt = detail::to_point<Point>(pick(st_->face_pt, st_->level.fid.at(f), centroid(f)));
  }
  void edge_node(halfedge_descriptor h, Point& pt) {
    ensure();
    pt = detail::to_point<Point>(edge_point(h));
  }
  void vertex_node(vertex_descriptor v, Point& pt) {
    ensure();
    pt = detail::to_point<Point>(pick(st_->vertex_pt, st_->level.vid.at(v), st_->level.pos(v)));
  }
  void border_node(halfedge_descriptor h, Point& ept, Point& vpt) {
    ensure();
    ept = detail::to_point<Point>(edge_point(h));
    vertex_descriptor t = target(h, *pmesh_);
    vpt = detail::to_point<Point>(pick(st_->vertex_pt, st_->level.vid.at(t), st_->level.pos(t)));
  }

 private:
  Mesh* pmesh_;
  VertexPointMap vpm_;
  std::shared_ptr<detail::MaskState<Mesh>> st_;

  static detail::P3 pick(const std::vector<detail::P3>& v, uint32_t i, const detail::P3& dflt) {
    return i < v.size() && detail::finite3(v[i]) ? v[i] : dflt;
  }
  detail::P3 centroid(face_descriptor f) const {
    detail::P3 s{0, 0, 0};
    double n = 0;
    for (auto h : CGAL::halfedges_around_face(halfedge(f, *pmesh_), *pmesh_)) {
      s = detail::add(s, st_->level.pos(target(h, *pmesh_)));
      n += 1;
    }
    return detail::scale(s, 1.0 / n);
  }
  detail::P3 edge_point(halfedge_descriptor h) const {
    const uint32_t a = st_->level.vid.at(source(h, *pmesh_)), b = st_->level.vid.at(target(h, *pmesh_));
    auto it = st_->edge_pt.find(detail::edge_key(a, b));
    if (it != st_->edge_pt.end() && detail::finite3(it->second)) return it->second;
    return detail::scale(detail::add(st_->level.pos(source(h, *pmesh_)), st_->level.pos(target(h, *pmesh_))), 0.5);
  }

  bool ensure() {
    detail::MaskState<Mesh>& st = *st_;
    const std::size_t nv = num_vertices(*pmesh_);
    if (st.evaluated_nv == nv) return !st.failed;
    if (st.evaluated_nv != SIZE_MAX) st.nv_prev = st.evaluated_nv;  // the host's next step
    st.evaluated_nv = nv;
    st.failed = false;
    ++st.level_no;
    st.vertex_pt.clear();
    st.edge_pt.clear();
    st.face_pt.clear();
    st.level.build(*pmesh_, vpm_, st.nv_prev);
    const FlatMesh& in = st.level.flat;
    const uint32_t fl = Flags | (st.opts.strict ? NLS_SUBDIVIDE_STRICT : 0u) |
                        ((Flags & NLS_SUBDIVIDE_MOBIUS) && st.opts.literal ? NLS_SUBDIVIDE_LITERAL : 0u);
    uint32_t el = NLS_NO_ELEMENT;
    nls_status s = NLS_STATUS_OK;
    if (st.opts.strict && st.level_no == 1) {
      s = nlsubdiv::flat::validate(Scheme, fl, in, el);
      if (s == NLS_STATUS_OK) s = nlsubdiv::flat::strict_check(in, el);
      if (s != NLS_STATUS_OK) return st.fail(s, el);
    }
    st.report.path = "driver mask";
    return detail::fill_from_driver(st, Scheme, fl);
  }
};

// ---------------------------------------------------------------------------------------
// Mobius_loop_mask_3: the Möbius Loop star rules with CGAL's connectivity.
// ---------------------------------------------------------------------------------------

/// PTQMask_3 of canonical Möbius Loop or Modified Butterfly (seed 000 §4) from the star
/// rules with CGAL's connectivity: per vertex star nls_mobius_loop_star or
/// nls_mobius_butterfly_star (ring counter-clockwise from the driver's first spoke),
/// interior edges nls_f4_hinted(a, e_a, e_b, b, apex) with a the smaller index (or the one
/// candidate), boundary loops by the Möbius curve rules (nls_f4). Loop's linear fallbacks are
/// evaluated here (counted, or an error in strict mode); a Butterfly fallback reads the 2-ring
/// linear stencils, so that level is taken from the driver on the same flat copy instead.
template <class PolygonMesh, uint32_t Scheme,
          class VertexPointMap = typename boost::property_map<PolygonMesh, CGAL::vertex_point_t>::type>
class Star_mask_3 {
 public:
  static constexpr uint32_t scheme = Scheme;
  static constexpr uint32_t flags = NLS_SUBDIVIDE_MOBIUS;
  typedef PolygonMesh Mesh;
  typedef typename boost::graph_traits<Mesh>::vertex_descriptor vertex_descriptor;
  typedef typename boost::graph_traits<Mesh>::halfedge_descriptor halfedge_descriptor;
  typedef typename boost::graph_traits<Mesh>::face_descriptor face_descriptor;
  typedef typename boost::property_traits<VertexPointMap>::value_type Point;

  Star_mask_3(Mesh* pmesh, VertexPointMap vpm, Options opts = Options())
      : pmesh_(pmesh), vpm_(vpm), st_(std::make_shared<detail::MaskState<Mesh>>()) {
    st_->opts = opts;
  }
  bool evaluate() { return ensure(); }
  const Report& report() const { return st_->report; }
  void set_previous_vertex_count(std::size_t n) { st_->nv_prev = n; }

  void edge_node(halfedge_descriptor h, Point& pt) {
    ensure();
    pt = detail::to_point<Point>(edge_point(h));
  }
  void vertex_node(vertex_descriptor v, Point& pt) {
    ensure();
    pt = detail::to_point<Point>(vertex_point(v));
  }
  void border_node(halfedge_descriptor h, Point& ept, Point& vpt) {
    ensure();
    ept = detail::to_point<Point>(edge_point(h));
    vpt = detail::to_point<Point>(vertex_point(target(h, *pmesh_)));
  }

 private:
  Mesh* pmesh_;
  VertexPointMap vpm_;
  std::shared_ptr<detail::MaskState<Mesh>> st_;
  std::unordered_map<uint64_t, detail::P3> cand_;  // (v << 32 | u): candidate of edge v-u from v's star
  bool need_driver_ = false;                        // Butterfly: a fallback in this level

  const Mesh& pm() const { return *pmesh_; }
  uint32_t id(vertex_descriptor v) const { return st_->level.vid.at(v); }
  detail::P3 pos(vertex_descriptor v) const { return st_->level.pos(v); }
  detail::P3 vertex_point(vertex_descriptor v) const {
    const uint32_t i = id(v);
    return i < st_->vertex_pt.size() && detail::finite3(st_->vertex_pt[i]) ? st_->vertex_pt[i] : pos(v);
  }
  detail::P3 edge_point(halfedge_descriptor h) const {
    auto it = st_->edge_pt.find(detail::edge_key(id(source(h, pm())), id(target(h, pm()))));
    if (it != st_->edge_pt.end() && detail::finite3(it->second)) return it->second;
    return detail::scale(detail::add(pos(source(h, pm())), pos(target(h, pm()))), 0.5);
  }

  /// The corner index (flat copy) of the outgoing half-edge h of v: face offset + position
  /// of v in the face's corner list.
  uint32_t corner(halfedge_descriptor h) const {
    const FlatMesh& fl = st_->level.flat;
    const uint32_t f = st_->level.fid.at(face(h, pm())), v = id(source(h, pm()));
    for (uint32_t c = fl.offsets[f]; c < fl.offsets[f + 1]; ++c)
      if (fl.indices[c] == v) return c;
    return UINT32_MAX;
  }

  /// The driver's star: spokes counter-clockwise from the face-side outgoing boundary
  /// half-edge (boundary) or the outgoing half-edge of lowest corner index (interior); the
  /// closing spoke of a boundary star is `in` (b1 -> v).
  void star(vertex_descriptor v, std::vector<halfedge_descriptor>& spokes, std::vector<vertex_descriptor>& ring,
            halfedge_descriptor& in, bool& boundary) const {
    spokes.clear();
    ring.clear();
    boundary = false;
    if (halfedge(v, pm()) == boost::graph_traits<Mesh>::null_halfedge()) return;
    halfedge_descriptor h0 = boost::graph_traits<Mesh>::null_halfedge();
    uint32_t best = UINT32_MAX;
    for (auto h : CGAL::halfedges_around_source(v, pm())) {
      if (is_border(h, pm())) continue;
      if (is_border(opposite(h, pm()), pm())) {
        h0 = h;
        boundary = true;
        break;
      }
      const uint32_t c = corner(h);
      if (c < best) best = c, h0 = h;
    }
    if (h0 == boost::graph_traits<Mesh>::null_halfedge()) return;
    halfedge_descriptor h = h0;
    std::size_t guard = 0;
    do {
      spokes.push_back(h);
      ring.push_back(target(h, pm()));
      halfedge_descriptor p = prev(h, pm()), o = opposite(p, pm());
      if (is_border(o, pm())) {
        in = p;
        ring.push_back(source(p, pm()));
        break;
      }
      h = o;
    } while (h != h0 && ++guard < 4096);
  }

  bool fallback(std::size_t k) {
    if (st_->opts.strict) return st_->fail(NLS_STATUS_FALLBACK_IN_STRICT_MODE, static_cast<uint32_t>(k));
    if (Scheme == NLS_SCHEME_MODIFIED_BUTTERFLY)
      need_driver_ = true;  // the driver counts it
    else
      ++st_->report.fallbacks;
    return true;
  }

  bool ensure() {
    detail::MaskState<Mesh>& st = *st_;
    const std::size_t nv = num_vertices(pm());
    if (st.evaluated_nv == nv) return !st.failed;
    if (st.evaluated_nv != SIZE_MAX) st.nv_prev = st.evaluated_nv;
    st.evaluated_nv = nv;
    st.failed = false;
    ++st.level_no;
    st.vertex_pt.assign(nv, detail::nan3());
    st.edge_pt.clear();
    cand_.clear();
    st.report.path = "star rules";
    st.level.build(pm(), vpm_, st.nv_prev);
    const uint32_t fl = NLS_SUBDIVIDE_MOBIUS | (st.opts.strict ? NLS_SUBDIVIDE_STRICT : 0u);
    uint32_t el = NLS_NO_ELEMENT;
    nls_status s = nlsubdiv::flat::validate(Scheme, fl, st.level.flat, el);
    if (s == NLS_STATUS_OK && st.opts.strict && st.level_no == 1) s = nlsubdiv::flat::strict_check(st.level.flat, el);
    if (s != NLS_STATUS_OK) return st.fail(s, el);
    need_driver_ = false;
    if (!(vertices() && edges())) return false;
    if (Scheme != NLS_SCHEME_MODIFIED_BUTTERFLY && !boundary_vertices()) return false;
    if (need_driver_) return detail::fill_from_driver(st, Scheme, fl);
    return finite();
  }

  bool vertices() {
    std::vector<halfedge_descriptor> spokes;
    std::vector<vertex_descriptor> ring;
    std::vector<double> xyz, ec;
    halfedge_descriptor in;
    bool boundary = false;
    std::vector<uint32_t> irregular;
    // Butterfly: which vertices are interior with valence != 6 (the singular rings).
    std::vector<char> singular;
    if (Scheme == NLS_SCHEME_MODIFIED_BUTTERFLY) {
      singular.assign(st_->level.verts.size(), 0);
      for (vertex_descriptor v : st_->level.verts) {
        star(v, spokes, ring, in, boundary);
        singular[id(v)] = (!spokes.empty() && !boundary && ring.size() != 6) ? 1 : 0;
      }
    }
    for (vertex_descriptor v : st_->level.verts) {
      const uint32_t vi = id(v);
      star(v, spokes, ring, in, boundary);
      if (spokes.empty()) {  // isolated: carried through
        st_->vertex_pt[vi] = pos(v);
        continue;
      }
      const std::size_t n = ring.size();
      detail::P3 vp = detail::nan3();
      const bool ear = boundary && spokes.size() == 1;  // one face: the driver gives it no form
      if (!ear) {
        xyz.clear();
        for (auto u : ring) {
          detail::P3 p = pos(u);
          xyz.insert(xyz.end(), p.begin(), p.end());
        }
        ec.assign(3 * n, NAN);
        const detail::P3 pv = pos(v);
        nls_status s;
        if (Scheme == NLS_SCHEME_MODIFIED_BUTTERFLY) {
          irregular.assign(n, 0);
          for (std::size_t j = 0; j < n; ++j) irregular[j] = singular[id(ring[j])] ? 1u : 0u;
          const nls_star_view star = flat::star_of(pv.data(), xyz.data(), n, !boundary);
          s = nls_mobius_butterfly_star(&star, irregular.data(), ec.data());
        } else {
          const nls_star_view star = flat::star_of(pv.data(), xyz.data(), n, !boundary);
          s = nls_mobius_loop_star(&star, vp.data(), ec.data());
        }
        if (s == NLS_STATUS_OK) {
          for (std::size_t j = 0; j < spokes.size(); ++j)
            cand_[(static_cast<uint64_t>(vi) << 32) | id(ring[j])] = {ec[3 * j], ec[3 * j + 1], ec[3 * j + 2]};
        } else {
          vp = detail::nan3();
        }
      }
      if (Scheme == NLS_SCHEME_MODIFIED_BUTTERFLY) {  // interpolating
        st_->vertex_pt[vi] = pos(v);
        continue;
      }
      if (!boundary) {
        if (!detail::finite3(vp)) {
          if (!fallback(vi)) return false;
          double a = 0.375;
          if (n != 6) {
            const double c = 0.375 + 0.25 * std::cos(2.0 * 3.14159265358979323846 / static_cast<double>(n));
            a = 0.625 - c * c;
          }
          detail::P3 sum{0, 0, 0};
          for (auto u : ring) sum = detail::add(sum, pos(u));
          vp = detail::add(detail::scale(pos(v), 1.0 - a), detail::scale(sum, a / static_cast<double>(n)));
        }
        st_->vertex_pt[vi] = vp;
      }
    }
    return true;
  }

  detail::P3 cand(uint32_t v, uint32_t u) const {
    auto it = cand_.find((static_cast<uint64_t>(v) << 32) | u);
    return it == cand_.end() ? detail::nan3() : it->second;
  }

  bool edges() {
    const std::size_t nv = st_->level.verts.size();
    std::size_t rank = 0;  // output index for strict-mode reports only (edge iteration order)
    for (auto e : CGAL::edges(pm())) {
      halfedge_descriptor h = halfedge(e, pm());
      const std::size_t k = nv + rank++;
      if (is_border(e, pm())) {
        if (is_border(h, pm())) h = opposite(h, pm());
        halfedge_descriptor hb = opposite(h, pm());
        const detail::P3 p0 = pos(target(next(hb, pm()), pm())), a = pos(source(h, pm())), b = pos(target(h, pm())),
                         p3 = pos(source(prev(hb, pm()), pm()));
        detail::P3 q;
        if (nls_f4(p0.data(), a.data(), b.data(), p3.data(), q.data()) != NLS_STATUS_OK) {
          if (!fallback(k)) return false;
          q = detail::scale(detail::add(a, b), 0.5);
        }
        st_->edge_pt[detail::edge_key(id(source(h, pm())), id(target(h, pm())))] = q;
        continue;
      }
      if (id(source(h, pm())) > id(target(h, pm()))) h = opposite(h, pm());
      halfedge_descriptor t = opposite(h, pm());
      const uint32_t ia = id(source(h, pm())), ib = id(target(h, pm()));
      const detail::P3 a = pos(source(h, pm())), b = pos(target(h, pm()));
      const detail::P3 ca = cand(ia, ib), cb = cand(ib, ia);
      const detail::P3 hint = pos(target(next(h, pm()), pm()));
      detail::P3 q = detail::nan3();
      bool have = false;
      if (detail::finite3(ca) && detail::finite3(cb))
        have = nls_f4_hinted(a.data(), ca.data(), cb.data(), b.data(), hint.data(), q.data()) == NLS_STATUS_OK;
      else if (detail::finite3(ca))
        q = ca, have = true;
      else if (detail::finite3(cb))
        q = cb, have = true;
      if (!(have && detail::finite3(q))) {
        if (!fallback(k)) return false;
        const detail::P3 c = pos(target(next(h, pm()), pm())), d = pos(target(next(t, pm()), pm()));
        q = detail::add(detail::scale(detail::add(a, b), 0.375), detail::scale(detail::add(c, d), 0.125));
      }
      st_->edge_pt[detail::edge_key(ia, ib)] = q;
    }
    return true;
  }

  bool boundary_vertices() {
    std::vector<halfedge_descriptor> spokes;
    std::vector<vertex_descriptor> ring;
    halfedge_descriptor in;
    bool boundary = false;
    for (vertex_descriptor v : st_->level.verts) {
      star(v, spokes, ring, in, boundary);
      if (spokes.empty() || !boundary) continue;
      const uint32_t vi = id(v);
      const halfedge_descriptor out_h = spokes.front();
      const detail::P3 b0 = pos(target(out_h, pm())), b1 = pos(source(in, pm()));
      const detail::P3 e_out = st_->edge_pt.at(detail::edge_key(vi, id(target(out_h, pm()))));
      const detail::P3 e_in = st_->edge_pt.at(detail::edge_key(vi, id(source(in, pm()))));
      detail::P3 q;
      if (nls_f4(b1.data(), e_in.data(), e_out.data(), b0.data(), q.data()) != NLS_STATUS_OK) {
        if (!fallback(vi)) return false;
        q = detail::add(detail::scale(pos(v), 0.75), detail::scale(detail::add(b0, b1), 0.125));
      }
      st_->vertex_pt[vi] = q;
    }
    return true;
  }

  bool finite() {
    for (std::size_t i = 0; i < st_->vertex_pt.size(); ++i)
      if (!detail::finite3(st_->vertex_pt[i])) return st_->fail(NLS_STATUS_NUMERICAL_FAILURE, static_cast<uint32_t>(i));
    for (const auto& e : st_->edge_pt)
      if (!detail::finite3(e.second)) return st_->fail(NLS_STATUS_NUMERICAL_FAILURE, NLS_NO_ELEMENT);
    return true;
  }
};

template <class PM, class VPM = typename boost::property_map<PM, CGAL::vertex_point_t>::type>
using Mobius_loop_mask_3 = Star_mask_3<PM, NLS_SCHEME_LOOP, VPM>;
template <class PM, class VPM = typename boost::property_map<PM, CGAL::vertex_point_t>::type>
using Mobius_butterfly_mask_3 = Star_mask_3<PM, NLS_SCHEME_MODIFIED_BUTTERFLY, VPM>;
template <class PM, class VPM = typename boost::property_map<PM, CGAL::vertex_point_t>::type>
using Mobius_butterfly_driver_mask_3 = Driver_mask_3<PM, NLS_SCHEME_MODIFIED_BUTTERFLY, NLS_SUBDIVIDE_MOBIUS, VPM>;
template <class PM, class VPM = typename boost::property_map<PM, CGAL::vertex_point_t>::type>
using Mobius_catmull_clark_mask_3 = Driver_mask_3<PM, NLS_SCHEME_CATMULL_CLARK, NLS_SUBDIVIDE_MOBIUS, VPM>;
template <class PM, class VPM = typename boost::property_map<PM, CGAL::vertex_point_t>::type>
using Mobius_kobbelt_mask_3 = Driver_mask_3<PM, NLS_SCHEME_KOBBELT, NLS_SUBDIVIDE_MOBIUS, VPM>;
template <class PM, class VPM = typename boost::property_map<PM, CGAL::vertex_point_t>::type>
using Linear_butterfly_mask_3 = Driver_mask_3<PM, NLS_SCHEME_MODIFIED_BUTTERFLY, 0, VPM>;
template <class PM, class VPM = typename boost::property_map<PM, CGAL::vertex_point_t>::type>
using Linear_kobbelt_mask_3 = Driver_mask_3<PM, NLS_SCHEME_KOBBELT, 0, VPM>;

// ---------------------------------------------------------------------------------------
// Free functions.
// ---------------------------------------------------------------------------------------

namespace detail {

template <class PM, class NP>
unsigned int iterations(const NP& np) {
  return CGAL::parameters::choose_parameter(CGAL::parameters::get_parameter(np, CGAL::internal_np::number_of_iterations), 1);
}

/// Replaces `pm` by `out` (old vertices first, in order; the mesh's internal point map
/// receives the positions). On failure (add_face refuses a face, which the driver's output
/// cannot cause) the mesh is restored and false returned.
template <class PM, class Vpm>
bool rebuild(PM& pm, const FlatMesh& out) {
  typedef typename boost::property_traits<Vpm>::value_type Point;
  typedef typename boost::graph_traits<PM>::vertex_descriptor vertex_descriptor;
  PM backup(pm);
  CGAL::clear(pm);
  auto ppm = get(CGAL::vertex_point, pm);
  std::vector<vertex_descriptor> vs;
  vs.reserve(out.vertex_count());
  for (std::size_t i = 0; i < out.vertex_count(); ++i) {
    vertex_descriptor v = add_vertex(pm);
    put(ppm, v, Point(out.positions[3 * i], out.positions[3 * i + 1], out.positions[3 * i + 2]));
    vs.push_back(v);
  }
  std::vector<vertex_descriptor> corners;
  for (std::size_t fi = 0; fi + 1 < out.offsets.size(); ++fi) {
    corners.clear();
    for (uint32_t c = out.offsets[fi]; c < out.offsets[fi + 1]; ++c) corners.push_back(vs[out.indices[c]]);
    if (CGAL::Euler::add_face(corners, pm) == boost::graph_traits<PM>::null_face()) {
      pm = backup;
      return false;
    }
  }
  return true;
}

/// Sharp-feature tags from the named parameters `edge_is_constrained_map` (edges -> bool:
/// creases of `opts.crease_sharpness`, e.g. the output of
/// CGAL::Polygon_mesh_processing::detect_sharp_edges), `vertex_is_constrained_map`
/// (vertices -> bool: corners of `opts.corner_sharpness`) and nlsubdiv's
/// `edge_sharpness_map` / `vertex_sharpness_map` (-> double: every non-zero value tags its
/// element with that sharpness, and wins over the flag), numbered as `lv` numbers the
/// vertices. Without any of them, no tags.
template <class PM, class NP>
nlsubdiv::flat::FlatTags tags_of(const PM& pm, const NP& np, const Level<PM>& lv, const Options& opts) {
  nlsubdiv::flat::FlatTags t;
  t.method = opts.crease_method;
  constexpr bool ecm_given = !CGAL::parameters::is_default_parameter<NP, CGAL::internal_np::edge_is_constrained_t>::value;
  constexpr bool esm_given = !CGAL::parameters::is_default_parameter<NP, nlsubdiv::internal_np::edge_sharpness_map_t>::value;
  constexpr bool vcm_given = !CGAL::parameters::is_default_parameter<NP, CGAL::internal_np::vertex_is_constrained_t>::value;
  constexpr bool vsm_given = !CGAL::parameters::is_default_parameter<NP, nlsubdiv::internal_np::vertex_sharpness_map_t>::value;
  if constexpr (ecm_given || esm_given) {
    for (auto e : CGAL::edges(pm)) {
      double s = 0.0;
      if constexpr (esm_given) s = get(CGAL::parameters::get_parameter(np, nlsubdiv::internal_np::edge_sharpness_map), e);
      if constexpr (ecm_given)
        if (s == 0.0 && get(CGAL::parameters::get_parameter(np, CGAL::internal_np::edge_is_constrained), e)) s = opts.crease_sharpness;
      if (s == 0.0) continue;  // smooth (NaN is not 0: the kernel refuses it)
      auto h = halfedge(e, pm);
      t.crease_vertices.push_back(lv.vid.at(source(h, pm)));
      t.crease_vertices.push_back(lv.vid.at(target(h, pm)));
      t.crease_sharpness.push_back(s);
    }
  }
  if constexpr (vcm_given || vsm_given) {
    for (auto v : CGAL::vertices(pm)) {
      double s = 0.0;
      if constexpr (vsm_given) s = get(CGAL::parameters::get_parameter(np, nlsubdiv::internal_np::vertex_sharpness_map), v);
      if constexpr (vcm_given)
        if (s == 0.0 && get(CGAL::parameters::get_parameter(np, CGAL::internal_np::vertex_is_constrained), v)) s = opts.corner_sharpness;
      if (s == 0.0) continue;
      t.corner_vertices.push_back(lv.vid.at(v));
      t.corner_sharpness.push_back(s);
    }
  }
  return t;
}

/// The bulk path: flat copy -> nls_mesh_subdivide -> the mesh rebuilt (old vertices
/// first, in order; the mesh's internal point map receives the positions). With sharp
/// features ([`tags_of`]) the tagged calls (Loop, Catmull–Clark, Modified Butterfly and
/// Kobbelt, linear or Möbius; any other scheme is NLS_STATUS_TAGS_NOT_SUPPORTED, mesh
/// unchanged).
template <class PM, class NP>
Report bulk(PM& pm, uint32_t scheme, uint32_t flags, const NP& np, Options opts) {
  typedef typename CGAL::GetVertexPointMap<PM, NP>::type Vpm;
  Vpm vpm = CGAL::parameters::choose_parameter(CGAL::parameters::get_parameter(np, CGAL::internal_np::vertex_point),
                                               get_property_map(CGAL::vertex_point, pm));
  Report r;
  r.path = "bulk";
  Level<PM> lv;
  lv.build(pm, vpm, SIZE_MAX);
  const uint32_t f = flags | (opts.strict ? NLS_SUBDIVIDE_STRICT : 0u) |
                     ((flags & NLS_SUBDIVIDE_MOBIUS) && opts.literal ? NLS_SUBDIVIDE_LITERAL : 0u);
  uint32_t el = NLS_NO_ELEMENT, fallbacks = 0;
  nls_status s = NLS_STATUS_OK;
  if (opts.strict) {
    s = nlsubdiv::flat::validate(scheme, f, lv.flat, el);
    if (s == NLS_STATUS_OK) s = nlsubdiv::flat::strict_check(lv.flat, el);
  }
  FlatMesh out;
  const nlsubdiv::flat::FlatTags tags = tags_of(pm, np, lv, opts);
  const nls_tags tv = tags.view();
  // Per-vertex spectrum weights (vertex_linear_weight_map), in the flat copy's vertex order.
  std::vector<double> weights;
  if constexpr (!CGAL::parameters::is_default_parameter<NP, nlsubdiv::internal_np::vertex_linear_weight_map_t>::value) {
    auto wm = CGAL::parameters::get_parameter(np, nlsubdiv::internal_np::vertex_linear_weight_map);
    if (flags & NLS_SUBDIVIDE_MOBIUS)
      for (auto v : lv.verts) weights.push_back(static_cast<double>(get(wm, v)));
  }
  if (s == NLS_STATUS_OK)
    s = nlsubdiv::flat::run_levels(scheme, f, lv.flat, iterations<PM>(np), out, el, fallbacks, tags.empty() ? nullptr : &tv,
                                   (flags & NLS_SUBDIVIDE_MOBIUS) ? opts.linear_weight : 0.0,
                                   weights.empty() ? nullptr : weights.data(), executor_of(opts));
  if (s != NLS_STATUS_OK) {
    r.status = s;
    r.element = el;
    r.level = 1;
    return r;
  }
  r.fallbacks = fallbacks;
  if (!rebuild<PM, Vpm>(pm, out)) {
    r.status = NLS_STATUS_NON_MANIFOLD_EDGE;  // cannot happen for the driver's output
    r.level = iterations<PM>(np);
  }
  return r;
}

/// The differential path: flat copy -> one nls_differential_subdivide call with levels =
/// number_of_iterations (the reconstruction is global: k levels are one solve) -> rebuilt.
template <class PM, class NP>
Report differential(PM& pm, uint32_t stencil, const NP& np, const DifferentialOptions& dopts, bool strict_folds = false) {
  typedef typename CGAL::GetVertexPointMap<PM, NP>::type Vpm;
  Vpm vpm = CGAL::parameters::choose_parameter(CGAL::parameters::get_parameter(np, CGAL::internal_np::vertex_point),
                                               get_property_map(CGAL::vertex_point, pm));
  Report r;
  r.path = "differential";
  Level<PM> lv;
  lv.build(pm, vpm, SIZE_MAX);
  if (!tags_of(pm, np, lv, Options()).empty()) {
    // Differential-space subdivision takes no sharp features.
    r.status = NLS_STATUS_TAGS_NOT_SUPPORTED;
    r.level = 1;
    return r;
  }
  nls_differential_options o{};
  nls_differential_default_options(&o);
  o.scheme = stencil;
  o.levels = iterations<PM>(np);
  o.dirmag_levels = stencil == NLS_DIFFERENTIAL_DIRMAG ? dopts.dirmag_levels : 0u;
  o.max_iterations = dopts.max_iterations;
  o.tolerance = dopts.tolerance;
  o.strict = strict_folds ? 1u : 0u;
  // §4.4 editing: the named parameters vertex_curvature_scale_map (vertex -> double) and
  // CGAL's vertex_normal_map (vertex -> vector with x(), y(), z()), read in the flat copy's
  // vertex order.
  std::vector<double> curvature, normals;
  if constexpr (!CGAL::parameters::is_default_parameter<NP, nlsubdiv::internal_np::vertex_curvature_scale_map_t>::value) {
    auto cm = CGAL::parameters::get_parameter(np, nlsubdiv::internal_np::vertex_curvature_scale_map);
    for (auto v : lv.verts) curvature.push_back(static_cast<double>(get(cm, v)));
    o.curvature_scale = curvature.data();
  }
  if constexpr (!CGAL::parameters::is_default_parameter<NP, CGAL::internal_np::vertex_normal_map_t>::value) {
    auto nm = CGAL::parameters::get_parameter(np, CGAL::internal_np::vertex_normal_map);
    for (auto v : lv.verts) {
      const auto n = get(nm, v);
      normals.push_back(CGAL::to_double(n.x()));
      normals.push_back(CGAL::to_double(n.y()));
      normals.push_back(CGAL::to_double(n.z()));
    }
    o.normals = normals.data();
  }
  uint32_t el = NLS_NO_ELEMENT;
  nls_status s = NLS_STATUS_OK;
  if (dopts.strict) {
    s = nlsubdiv::flat::validate(NLS_SCHEME_LOOP, 0, lv.flat, el);
    if (s == NLS_STATUS_OK) s = nlsubdiv::flat::strict_check(lv.flat, el);
  }
  FlatMesh out;
  nls_differential_report rep{};
  if (s == NLS_STATUS_OK) s = nlsubdiv::flat::run_differential(o, lv.flat, out, el, rep);
  r.iterations = rep.iterations;
  r.residual = rep.relative_residual;
  if (s != NLS_STATUS_OK) {
    r.status = s;
    r.element = el;
    r.level = o.levels;
    return r;
  }
  if (!rebuild<PM, Vpm>(pm, out)) {
    r.status = NLS_STATUS_NON_MANIFOLD_EDGE;
    r.level = o.levels;
  }
  return r;
}

/// `levels` host steps with a mask of type Mask built per level; each level evaluated before
/// the host touches the mesh; restore from a copy if a later level fails.
template <class Mask, bool Quad, class PM, class NP>
Report with_mask(PM& pm, const NP& np, Options opts) {
  typedef typename CGAL::GetVertexPointMap<PM, NP>::type Vpm;
  Vpm vpm = CGAL::parameters::choose_parameter(CGAL::parameters::get_parameter(np, CGAL::internal_np::vertex_point),
                                               get_property_map(CGAL::vertex_point, pm));
  const unsigned int levels = iterations<PM>(np);
  Report total;
  {
    // The star rules have no sharp features: a mesh with tags takes the bulk path, whose
    // tagged calls subdivide the creases with the Möbius curve rules.
    Level<PM> lv;
    lv.build(pm, vpm, SIZE_MAX);
    if (!tags_of(pm, np, lv, opts).empty()) return bulk(pm, Mask::scheme, Mask::flags, np, opts);
  }
  // CGAL's hosts assert CGAL::is_valid_polygon_mesh after each step (it refuses isolated
  // vertices, which the kernel carries through): such meshes take the bulk path, which
  // gives the driver's result, so the answer does not depend on the path.
  if (!CGAL::is_valid_polygon_mesh(pm)) return bulk(pm, Mask::scheme, Mask::flags, np, opts);
  PM backup(pm);
  std::size_t nv_prev = SIZE_MAX;
  for (unsigned int k = 0; k < levels; ++k) {
    Mask mask(&pm, vpm, opts);
    mask.set_previous_vertex_count(nv_prev);
    const std::size_t nv = num_vertices(pm);
    const bool ok = mask.evaluate();
    Report r = mask.report();
    total.fallbacks += r.fallbacks;
    total.path = r.path;
    if (!ok) {
      total.status = r.status;
      total.element = r.element;
      total.level = k + 1;
      if (k > 0) pm = backup;
      return total;
    }
    try {
      if constexpr (Quad)
        CGAL::Subdivision_method_3::PQQ(pm, mask, CGAL::parameters::vertex_point_map(vpm).number_of_iterations(1));
      else
        CGAL::Subdivision_method_3::PTQ(pm, mask, CGAL::parameters::vertex_point_map(vpm).number_of_iterations(1));
    } catch (const std::exception&) {  // a CGAL precondition/postcondition of the host
      pm = backup;
      total.status = NLS_STATUS_INVALID_ARGUMENT;
      total.level = k + 1;
      return total;
    }
    nv_prev = nv;
  }
  return total;
}

}  // namespace detail

namespace detail {

template <class PM, class NP>
using Vpm_t = typename CGAL::GetVertexPointMap<PM, NP>::type;

/// The path of a scheme: the star-rule masks in CGAL's PTQ host for literal Möbius Loop and
/// Modified Butterfly at weight 0, the driver mask in CGAL's PQQ host for Möbius Kobbelt,
/// the bulk path otherwise.
template <class PM, class NP>
Report run_scheme(PM& pm, uint32_t scheme, uint32_t flags, const NP& np, const Options& opts) {
  const bool mobius = (flags & NLS_SUBDIVIDE_MOBIUS) != 0;
  // Per-vertex weights are carried level to level inside one driver call: the bulk path.
  if constexpr (!CGAL::parameters::is_default_parameter<NP, nlsubdiv::internal_np::vertex_linear_weight_map_t>::value)
    if (mobius) return bulk(pm, scheme, flags, np, opts);
  if (mobius && opts.literal && opts.linear_weight == 0.0) {
    if (scheme == NLS_SCHEME_LOOP) return with_mask<Mobius_loop_mask_3<PM, Vpm_t<PM, NP>>, false>(pm, np, opts);
    if (scheme == NLS_SCHEME_MODIFIED_BUTTERFLY)
      return with_mask<Mobius_butterfly_mask_3<PM, Vpm_t<PM, NP>>, false>(pm, np, opts);
  }
  if (mobius && scheme == NLS_SCHEME_KOBBELT) return with_mask<Mobius_kobbelt_mask_3<PM, Vpm_t<PM, NP>>, true>(pm, np, opts);
  return bulk(pm, scheme, flags, np, opts);
}

/// The deprecated Möbius Loop and Butterfly functions evaluated the star rules (literal).
inline Options literal_of(Options o) {
  o.literal = true;
  return o;
}

}  // namespace detail

// ---------------------------------------------------------------------------------------
// Deprecated names (kept for one version): nlsubdiv::Subdivision_method_3 (below) has the
// CGAL-style entry points. Each of these equals its new name bit for bit (the Möbius Loop
// and Butterfly ones: the new name with nlsubdiv::parameters::literal(true)) and returns the
// Report instead of throwing.
// ---------------------------------------------------------------------------------------

/// Deprecated: Subdivision_method_3::Mobius_Loop_subdivision with literal(true).
template <class PolygonMesh, class NamedParameters = CGAL::parameters::Default_named_parameters>
Report mobius_loop_subdivision(PolygonMesh& pm, const NamedParameters& np = CGAL::parameters::default_values(), Options opts = {}) {
  return detail::run_scheme(pm, NLS_SCHEME_LOOP, NLS_SUBDIVIDE_MOBIUS, np, detail::literal_of(opts));
}
/// Deprecated: Subdivision_method_3::Mobius_Butterfly_subdivision with literal(true).
template <class PolygonMesh, class NamedParameters = CGAL::parameters::Default_named_parameters>
Report mobius_butterfly_subdivision(PolygonMesh& pm, const NamedParameters& np = CGAL::parameters::default_values(), Options opts = {}) {
  return detail::run_scheme(pm, NLS_SCHEME_MODIFIED_BUTTERFLY, NLS_SUBDIVIDE_MOBIUS, np, detail::literal_of(opts));
}
/// Deprecated: Subdivision_method_3::Mobius_CatmullClark_subdivision.
template <class PolygonMesh, class NamedParameters = CGAL::parameters::Default_named_parameters>
Report mobius_catmull_clark_subdivision(PolygonMesh& pm, const NamedParameters& np = CGAL::parameters::default_values(), Options opts = {}) {
  return detail::run_scheme(pm, NLS_SCHEME_CATMULL_CLARK, NLS_SUBDIVIDE_MOBIUS, np, opts);
}
/// Deprecated: Subdivision_method_3::Mobius_Kobbelt_subdivision.
template <class PolygonMesh, class NamedParameters = CGAL::parameters::Default_named_parameters>
Report mobius_kobbelt_subdivision(PolygonMesh& pm, const NamedParameters& np = CGAL::parameters::default_values(), Options opts = {}) {
  return detail::run_scheme(pm, NLS_SCHEME_KOBBELT, NLS_SUBDIVIDE_MOBIUS, np, opts);
}
/// Deprecated: Subdivision_method_3::Mobius_DooSabin_subdivision.
template <class PolygonMesh, class NamedParameters = CGAL::parameters::Default_named_parameters>
Report mobius_doo_sabin_subdivision(PolygonMesh& pm, const NamedParameters& np = CGAL::parameters::default_values(), Options opts = {}) {
  return detail::run_scheme(pm, NLS_SCHEME_DOO_SABIN, NLS_SUBDIVIDE_MOBIUS, np, opts);
}
/// Deprecated: Subdivision_method_3::Mobius_Simplest_subdivision.
template <class PolygonMesh, class NamedParameters = CGAL::parameters::Default_named_parameters>
Report mobius_simplest_subdivision(PolygonMesh& pm, const NamedParameters& np = CGAL::parameters::default_values(), Options opts = {}) {
  return detail::run_scheme(pm, NLS_SCHEME_SIMPLEST, NLS_SUBDIVIDE_MOBIUS, np, opts);
}
/// Deprecated: Subdivision_method_3::Mobius_Dual_subdivision.
template <class PolygonMesh, class NamedParameters = CGAL::parameters::Default_named_parameters>
Report mobius_dual_subdivision(PolygonMesh& pm, const NamedParameters& np = CGAL::parameters::default_values(), Options opts = {}) {
  return detail::run_scheme(pm, NLS_SCHEME_DUAL, NLS_SUBDIVIDE_MOBIUS, np, opts);
}
/// Deprecated: Subdivision_method_3::Mobius_VertexInsertion_subdivision.
template <class PolygonMesh, class NamedParameters = CGAL::parameters::Default_named_parameters>
Report mobius_vertex_insertion_subdivision(PolygonMesh& pm, const NamedParameters& np = CGAL::parameters::default_values(),
                                           Options opts = {}) {
  return detail::run_scheme(pm, NLS_SCHEME_VERTEX_INSERTION, NLS_SUBDIVIDE_MOBIUS, np, opts);
}
/// Deprecated: Subdivision_method_3::Mobius_DualTruncation_subdivision.
template <class PolygonMesh, class NamedParameters = CGAL::parameters::Default_named_parameters>
Report mobius_dual_truncation_subdivision(PolygonMesh& pm, const NamedParameters& np = CGAL::parameters::default_values(),
                                          Options opts = {}) {
  return detail::run_scheme(pm, NLS_SCHEME_DUAL_TRUNCATION, NLS_SUBDIVIDE_MOBIUS, np, opts);
}
/// Deprecated: Subdivision_method_3::Loop_subdivision.
template <class PolygonMesh, class NamedParameters = CGAL::parameters::Default_named_parameters>
Report loop_subdivision(PolygonMesh& pm, const NamedParameters& np = CGAL::parameters::default_values(), Options opts = {}) {
  return detail::run_scheme(pm, NLS_SCHEME_LOOP, 0, np, opts);
}
/// Deprecated: Subdivision_method_3::CatmullClark_subdivision.
template <class PolygonMesh, class NamedParameters = CGAL::parameters::Default_named_parameters>
Report catmull_clark_subdivision(PolygonMesh& pm, const NamedParameters& np = CGAL::parameters::default_values(), Options opts = {}) {
  return detail::run_scheme(pm, NLS_SCHEME_CATMULL_CLARK, 0, np, opts);
}
/// Deprecated: Subdivision_method_3::Butterfly_subdivision.
template <class PolygonMesh, class NamedParameters = CGAL::parameters::Default_named_parameters>
Report butterfly_subdivision(PolygonMesh& pm, const NamedParameters& np = CGAL::parameters::default_values(), Options opts = {}) {
  return detail::run_scheme(pm, NLS_SCHEME_MODIFIED_BUTTERFLY, 0, np, opts);
}
/// Deprecated: Subdivision_method_3::Kobbelt_subdivision.
template <class PolygonMesh, class NamedParameters = CGAL::parameters::Default_named_parameters>
Report kobbelt_subdivision(PolygonMesh& pm, const NamedParameters& np = CGAL::parameters::default_values(), Options opts = {}) {
  return detail::run_scheme(pm, NLS_SCHEME_KOBBELT, 0, np, opts);
}
/// Deprecated: Subdivision_method_3::DooSabin_subdivision.
template <class PolygonMesh, class NamedParameters = CGAL::parameters::Default_named_parameters>
Report doo_sabin_subdivision(PolygonMesh& pm, const NamedParameters& np = CGAL::parameters::default_values(), Options opts = {}) {
  return detail::run_scheme(pm, NLS_SCHEME_DOO_SABIN, 0, np, opts);
}
/// Deprecated: Subdivision_method_3::Simplest_subdivision.
template <class PolygonMesh, class NamedParameters = CGAL::parameters::Default_named_parameters>
Report simplest_subdivision(PolygonMesh& pm, const NamedParameters& np = CGAL::parameters::default_values(), Options opts = {}) {
  return detail::run_scheme(pm, NLS_SCHEME_SIMPLEST, 0, np, opts);
}
/// Deprecated: Subdivision_method_3::Dual_subdivision.
template <class PolygonMesh, class NamedParameters = CGAL::parameters::Default_named_parameters>
Report dual_subdivision(PolygonMesh& pm, const NamedParameters& np = CGAL::parameters::default_values(), Options opts = {}) {
  return detail::run_scheme(pm, NLS_SCHEME_DUAL, 0, np, opts);
}
/// Deprecated: Subdivision_method_3::VertexInsertion_subdivision.
template <class PolygonMesh, class NamedParameters = CGAL::parameters::Default_named_parameters>
Report vertex_insertion_subdivision(PolygonMesh& pm, const NamedParameters& np = CGAL::parameters::default_values(), Options opts = {}) {
  return detail::run_scheme(pm, NLS_SCHEME_VERTEX_INSERTION, 0, np, opts);
}
/// Deprecated: Subdivision_method_3::DualTruncation_subdivision.
template <class PolygonMesh, class NamedParameters = CGAL::parameters::Default_named_parameters>
Report dual_truncation_subdivision(PolygonMesh& pm, const NamedParameters& np = CGAL::parameters::default_values(), Options opts = {}) {
  return detail::run_scheme(pm, NLS_SCHEME_DUAL_TRUNCATION, 0, np, opts);
}
/// Deprecated: Subdivision_method_3::Spherelike_subdivision. Spherelike interpolating
/// subdivision (seed 003 §3; any polygons -> quads; no Möbius form; bulk path). Coincident
/// points or a spike: NLS_STATUS_DEGENERATE_GEOMETRY, mesh unchanged.
template <class PolygonMesh, class NamedParameters = CGAL::parameters::Default_named_parameters>
Report spherelike_subdivision(PolygonMesh& pm, const NamedParameters& np = CGAL::parameters::default_values(), Options opts = {}) {
  return detail::run_scheme(pm, NLS_SCHEME_SPHERELIKE, 0, np, opts);
}

/// Deprecated: Subdivision_method_3::Differential_Loop_subdivision. Differential-space
/// subdivision (seed 001 §3; triangle meshes; number_of_iterations = levels, reconstructed
/// ONCE for all levels: not the same as repeated 1-level calls). The Report carries the
/// solver's iterations and residual. Non-triangles: NLS_STATUS_UNSUPPORTED_FACE_TYPE;
/// max_iterations reached: NLS_STATUS_NOT_CONVERGED; the mesh is unchanged on every error.
template <class PolygonMesh, class NamedParameters = CGAL::parameters::Default_named_parameters>
Report differential_loop_subdivision(PolygonMesh& pm, const NamedParameters& np = CGAL::parameters::default_values(),
                                     DifferentialOptions dopts = {}) {
  return detail::differential(pm, NLS_DIFFERENTIAL_LOOP, np, dopts);
}
/// Deprecated: Subdivision_method_3::Differential_Butterfly_subdivision.
template <class PolygonMesh, class NamedParameters = CGAL::parameters::Default_named_parameters>
Report differential_butterfly_subdivision(PolygonMesh& pm, const NamedParameters& np = CGAL::parameters::default_values(),
                                          DifferentialOptions dopts = {}) {
  return detail::differential(pm, NLS_DIFFERENTIAL_BUTTERFLY, np, dopts);
}
/// Deprecated: Subdivision_method_3::Differential_DirMag_subdivision (DirMag, seed 001 §3.4:
/// DifferentialOptions::dirmag_levels levels of DirMag, then Butterfly).
template <class PolygonMesh, class NamedParameters = CGAL::parameters::Default_named_parameters>
Report differential_dirmag_subdivision(PolygonMesh& pm, const NamedParameters& np = CGAL::parameters::default_values(),
                                       DifferentialOptions dopts = {}) {
  return detail::differential(pm, NLS_DIFFERENTIAL_DIRMAG, np, dopts);
}

/// Any scheme (NLS_SCHEME_*) with flags (NLS_SUBDIVIDE_MOBIUS or 0) through the bulk path.
template <class PolygonMesh, class NamedParameters = CGAL::parameters::Default_named_parameters>
Report subdivide(PolygonMesh& pm, uint32_t scheme, uint32_t flags, const NamedParameters& np = CGAL::parameters::default_values(),
                 Options opts = {}) {
  return detail::bulk(pm, scheme, flags, np, opts);
}

/// The error of the CGAL-style functions (nlsubdiv::Subdivision_method_3): thrown after the
/// mesh has been left exactly as it was (strong guarantee), carrying the whole Report.
/// what() is Report::message(), e.g. "level 1: the scheme does not accept this face type
/// (face 3)".
class Subdivision_error : public std::runtime_error {
 public:
  explicit Subdivision_error(const Report& r) : std::runtime_error(r.message()), report_(r) {}
  nls_status status() const { return report_.status; }
  uint32_t element() const { return report_.element; }
  uint32_t level() const { return report_.level; }
  const Report& report() const { return report_; }

 private:
  Report report_;
};

}  // namespace cgal

// ---------------------------------------------------------------------------------------
// Named parameters: CGAL's, chainable with nlsubdiv's own.
// ---------------------------------------------------------------------------------------

/// A CGAL named-parameter pack (it is a CGAL::Named_function_parameters, so CGAL and the
/// functions below read it with CGAL::parameters::get_parameter) whose chaining functions
/// also offer nlsubdiv's parameters: nlsubdiv::parameters::number_of_iterations(2).strict(true)
/// or nlsubdiv::parameters::strict(true).vertex_point_map(vpm). CGAL 5.5's own packs
/// (CGAL::parameters::...) are accepted too; they chain CGAL's parameters only.
template <typename T, typename Tag, typename Base = CGAL::internal_np::No_property>
struct Named_function_parameters : CGAL::Named_function_parameters<T, Tag, Base> {
  typedef CGAL::Named_function_parameters<T, Tag, Base> cgal_np;
  typedef Named_function_parameters<T, Tag, Base> self;
  Named_function_parameters() : cgal_np() {}
  Named_function_parameters(const T& v) : cgal_np(v) {}
  Named_function_parameters(const T& v, const Base& b) : cgal_np(v, b) {}

  // CGAL's parameters, each returning this class so that nlsubdiv's can follow.
#define CGAL_add_named_parameter(X, Y, Z)                                   \
  template <typename K>                                                     \
  Named_function_parameters<K, CGAL::internal_np::X, self> Z(const K& k) const { \
    return Named_function_parameters<K, CGAL::internal_np::X, self>(k, *this);   \
  }
#include <CGAL/STL_Extension/internal/parameters_interface.h>
#undef CGAL_add_named_parameter

  /// See nlsubdiv::parameters::strict.
  Named_function_parameters<bool, internal_np::strict_t, self> strict(bool on) const { return {on, *this}; }
  /// See nlsubdiv::parameters::literal.
  Named_function_parameters<bool, internal_np::literal_t, self> literal(bool on) const { return {on, *this}; }
  /// See nlsubdiv::parameters::linear_weight.
  Named_function_parameters<double, internal_np::linear_weight_t, self> linear_weight(double u) const { return {u, *this}; }
  /// See nlsubdiv::parameters::crease_sharpness.
  Named_function_parameters<double, internal_np::crease_sharpness_t, self> crease_sharpness(double s) const { return {s, *this}; }
  /// See nlsubdiv::parameters::corner_sharpness.
  Named_function_parameters<double, internal_np::corner_sharpness_t, self> corner_sharpness(double s) const { return {s, *this}; }
  /// See nlsubdiv::parameters::crease_method.
  Named_function_parameters<uint32_t, internal_np::crease_method_t, self> crease_method(uint32_t m) const { return {m, *this}; }
  /// See nlsubdiv::parameters::report.
  Named_function_parameters<std::reference_wrapper<cgal::Report>, internal_np::report_t, self> report(cgal::Report& r) const {
    return {std::ref(r), *this};
  }
  /// See nlsubdiv::parameters::vertex_curvature_scale_map.
  template <typename Map>
  Named_function_parameters<Map, internal_np::vertex_curvature_scale_map_t, self> vertex_curvature_scale_map(const Map& m) const {
    return {m, *this};
  }
  /// See nlsubdiv::parameters::edge_sharpness_map.
  template <typename Map>
  Named_function_parameters<Map, internal_np::edge_sharpness_map_t, self> edge_sharpness_map(const Map& m) const {
    return {m, *this};
  }
  /// See nlsubdiv::parameters::vertex_sharpness_map.
  template <typename Map>
  Named_function_parameters<Map, internal_np::vertex_sharpness_map_t, self> vertex_sharpness_map(const Map& m) const {
    return {m, *this};
  }
  /// See nlsubdiv::parameters::vertex_linear_weight_map.
  template <typename Map>
  Named_function_parameters<Map, internal_np::vertex_linear_weight_map_t, self> vertex_linear_weight_map(const Map& m) const {
    return {m, *this};
  }
  /// See nlsubdiv::parameters::solver_max_iterations.
  Named_function_parameters<uint32_t, internal_np::solver_max_iterations_t, self> solver_max_iterations(uint32_t n) const {
    return {n, *this};
  }
  /// See nlsubdiv::parameters::solver_tolerance.
  Named_function_parameters<double, internal_np::solver_tolerance_t, self> solver_tolerance(double t) const { return {t, *this}; }
  /// See nlsubdiv::parameters::dirmag_levels.
  Named_function_parameters<uint32_t, internal_np::dirmag_levels_t, self> dirmag_levels(uint32_t n) const { return {n, *this}; }
  /// See nlsubdiv::parameters::threads.
  Named_function_parameters<unsigned, internal_np::threads_t, self> threads(unsigned n) const { return {n, *this}; }
};

namespace parameters {

/// No parameter (the defaults), chainable with nlsubdiv's parameters.
inline Named_function_parameters<bool, CGAL::internal_np::all_default_t> default_values() { return {}; }

// CGAL's parameters as free functions starting an nlsubdiv pack.
#define CGAL_add_named_parameter(X, Y, Z)                       \
  template <typename K>                                         \
  Named_function_parameters<K, CGAL::internal_np::X> Z(const K& p) { \
    return Named_function_parameters<K, CGAL::internal_np::X>(p);    \
  }
#include <CGAL/STL_Extension/internal/parameters_interface.h>
#undef CGAL_add_named_parameter

/// Strict mode (default false): a fallback (an element that would take the documented linear
/// rule) is NLS_STATUS_FALLBACK_IN_STRICT_MODE, and the input is refused for what the kernel
/// accepts by policy but is most likely a mistake (nlsubdiv::flat::strict_check). Differential
/// schemes: the strict input checks, and with edits a folded output is
/// NLS_STATUS_FOLDED_SURFACE (nls_differential_options::strict).
inline Named_function_parameters<bool, internal_np::strict_t> strict(bool on) { return {on}; }
/// Möbius schemes (default false): the paper's rules without the driver's fold guard
/// (NLS_SUBDIVIDE_LITERAL).
inline Named_function_parameters<bool, internal_np::literal_t> literal(bool on) { return {on}; }
/// Möbius schemes (default 0): the weight u of the linear result in the Möbius–linear spectrum
/// (seed 000 §7.2), each level (1 − u) · Möbius + u · linear; 0 is the Möbius result and 1
/// the linear one, bit for bit. NaN or outside [0, 1]: NLS_STATUS_INVALID_ARGUMENT.
inline Named_function_parameters<double, internal_np::linear_weight_t> linear_weight(double u) { return {u}; }
/// Sharpness (default 10, OpenSubdiv's scale: 10 or more infinitely sharp) of the edges of
/// CGAL's edge_is_constrained_map.
inline Named_function_parameters<double, internal_np::crease_sharpness_t> crease_sharpness(double s) { return {s}; }
/// Sharpness (default 10) of the corners of CGAL's vertex_is_constrained_map.
inline Named_function_parameters<double, internal_np::corner_sharpness_t> corner_sharpness(double s) { return {s}; }
/// NLS_CREASE_UNIFORM (default) or NLS_CREASE_CHAIKIN.
inline Named_function_parameters<uint32_t, internal_np::crease_method_t> crease_method(uint32_t m) { return {m}; }
/// Output: receives the call's Report (status, element, level, fallbacks, path, solver
/// iterations and residual) on success and, before the exception, on failure.
inline Named_function_parameters<std::reference_wrapper<cgal::Report>, internal_np::report_t> report(cgal::Report& r) {
  return {std::ref(r)};
}
/// Differential schemes (§4.4 editing): a readable property map vertex -> double, the factor
/// on each control vertex's mean curvature (1 keeps it). Target normals: CGAL's
/// vertex_normal_map (vertex -> vector with x(), y(), z(); a zero vector keeps the vertex's
/// own normal).
template <typename Map>
Named_function_parameters<Map, internal_np::vertex_curvature_scale_map_t> vertex_curvature_scale_map(const Map& m) {
  return {m};
}
/// Sharp features: a readable property map edge -> double, the sharpness of every edge
/// whose value is not 0 (OpenSubdiv's scale: 10 or more infinitely sharp, below it
/// semi-sharp); a value wins over edge_is_constrained_map's uniform crease_sharpness for
/// its edge. NaN, negative or infinite values are NLS_STATUS_INVALID_SHARPNESS, mesh
/// unchanged.
template <typename Map>
Named_function_parameters<Map, internal_np::edge_sharpness_map_t> edge_sharpness_map(const Map& m) {
  return {m};
}
/// Sharp features: a readable property map vertex -> double, the corner sharpness of every
/// vertex whose value is not 0 (wins over vertex_is_constrained_map's corner_sharpness).
template <typename Map>
Named_function_parameters<Map, internal_np::vertex_sharpness_map_t> vertex_sharpness_map(const Map& m) {
  return {m};
}
/// Möbius schemes: a readable property map vertex -> double, the weight u of the linear
/// result at each vertex (nls_subdivide_options::linear_weights; the convention of
/// linear_weight, which it replaces). Each output vertex of each level takes a weight carried
/// from its parents (an old vertex its own, an edge point the mean of its ends, a face point
/// the mean of its corners, a Doo–Sabin corner point its vertex's) and is
/// (1 − u) · Möbius + u · linear; equal values everywhere are linear_weight of that value,
/// bit for bit. Always the bulk path. NaN or outside [0, 1]: NLS_STATUS_INVALID_ARGUMENT
/// naming the vertex (its index in the mesh's vertex order), mesh unchanged. The linear
/// schemes ignore it.
template <typename Map>
Named_function_parameters<Map, internal_np::vertex_linear_weight_map_t> vertex_linear_weight_map(const Map& m) {
  return {m};
}
/// Differential schemes: the reconstruction's iteration cap (default 100; reaching it is
/// NLS_STATUS_NOT_CONVERGED).
inline Named_function_parameters<uint32_t, internal_np::solver_max_iterations_t> solver_max_iterations(uint32_t n) { return {n}; }
/// Differential schemes: the relative residual to reach (default 1e-10).
inline Named_function_parameters<double, internal_np::solver_tolerance_t> solver_tolerance(double t) { return {t}; }
/// DirMag: the first this many levels use DirMag (default 1).
inline Named_function_parameters<uint32_t, internal_np::dirmag_levels_t> dirmag_levels(uint32_t n) { return {n}; }
/// Threads of the kernel's passes (default 1: the calling thread only; 0: the hardware's
/// thread count), through nlsubdiv::ThreadPool (nlsubdiv_pool.hh), started once per call and
/// shared by its levels. The result, the fallbacks and the errors are the same bits for every
/// count. The star-rule masks (Mobius_loop_mask_3, Mobius_butterfly_mask_3) and the
/// differential functions run on the calling thread.
inline Named_function_parameters<unsigned, internal_np::threads_t> threads(unsigned n) { return {n}; }

}  // namespace parameters

namespace cgal {
namespace detail {

template <class NP, class Tag, class D>
D param_or(const NP& np, Tag tag, D dflt) {
  return static_cast<D>(CGAL::parameters::choose_parameter(CGAL::parameters::get_parameter(np, tag), dflt));
}

/// Options from the named parameters.
template <class NP>
Options options_of(const NP& np) {
  Options o;
  o.strict = param_or(np, nlsubdiv::internal_np::strict, o.strict);
  o.literal = param_or(np, nlsubdiv::internal_np::literal, o.literal);
  o.linear_weight = param_or(np, nlsubdiv::internal_np::linear_weight, o.linear_weight);
  o.crease_sharpness = param_or(np, nlsubdiv::internal_np::crease_sharpness, o.crease_sharpness);
  o.corner_sharpness = param_or(np, nlsubdiv::internal_np::corner_sharpness, o.corner_sharpness);
  o.crease_method = param_or(np, nlsubdiv::internal_np::crease_method, o.crease_method);
  o.threads = param_or(np, nlsubdiv::internal_np::threads, o.threads);
  return o;
}

template <class NP>
DifferentialOptions differential_options_of(const NP& np) {
  DifferentialOptions d;
  d.strict = param_or(np, nlsubdiv::internal_np::strict, d.strict);
  d.max_iterations = param_or(np, nlsubdiv::internal_np::solver_max_iterations, d.max_iterations);
  d.tolerance = param_or(np, nlsubdiv::internal_np::solver_tolerance, d.tolerance);
  d.dirmag_levels = param_or(np, nlsubdiv::internal_np::dirmag_levels, d.dirmag_levels);
  return d;
}

/// The report to the named parameter `report`, then the exception on failure.
template <class NP>
void finish(const Report& r, const NP& np) {
  if constexpr (!CGAL::parameters::is_default_parameter<NP, nlsubdiv::internal_np::report_t>::value)
    CGAL::parameters::get_parameter_reference(np, nlsubdiv::internal_np::report) = r;
  if (!r.ok()) throw Subdivision_error(r);
}

template <class PM, class NP>
void scheme(PM& pm, uint32_t scheme, uint32_t flags, const NP& np) {
  finish(run_scheme(pm, scheme, flags, np, options_of(np)), np);
}

template <class PM, class NP>
void differential_scheme(PM& pm, uint32_t stencil, const NP& np) {
  const DifferentialOptions d = differential_options_of(np);
  finish(differential(pm, stencil, np, d, d.strict), np);
}

}  // namespace detail
}  // namespace cgal

/// CGAL-style entry points, like CGAL::Subdivision_method_3::Loop_subdivision: a polygon
/// mesh (Surface_mesh, Polyhedron_3, any MutableFaceGraph), CGAL named parameters (CGAL's
/// number_of_iterations, default 1, vertex_point_map, edge_is_constrained_map,
/// vertex_is_constrained_map, vertex_normal_map; nlsubdiv's from nlsubdiv::parameters), no
/// return value. An error throws nlsubdiv::Subdivision_method_3::Subdivision_error (status,
/// element, level, the Report; what() the message) with the mesh exactly as it was; the
/// named parameter report(r) receives the Report in every case.
namespace Subdivision_method_3 {

using Subdivision_error = cgal::Subdivision_error;
using Report = cgal::Report;

/// Möbius Loop (seed 000 §4; triangles). The driver's fold guard by default (bulk path);
/// with literal(true) and linear_weight 0 the star rules in CGAL's PTQ host (Mobius_loop_mask_3).
template <class PolygonMesh, class NamedParameters = CGAL::parameters::Default_named_parameters>
void Mobius_Loop_subdivision(PolygonMesh& pmesh, const NamedParameters& np = CGAL::parameters::default_values()) {
  cgal::detail::scheme(pmesh, NLS_SCHEME_LOOP, NLS_SUBDIVIDE_MOBIUS, np);
}
/// Möbius Modified Butterfly (triangles, interpolating); paths as Mobius_Loop_subdivision.
template <class PolygonMesh, class NamedParameters = CGAL::parameters::Default_named_parameters>
void Mobius_Butterfly_subdivision(PolygonMesh& pmesh, const NamedParameters& np = CGAL::parameters::default_values()) {
  cgal::detail::scheme(pmesh, NLS_SCHEME_MODIFIED_BUTTERFLY, NLS_SUBDIVIDE_MOBIUS, np);
}
/// Möbius Catmull–Clark (any polygons -> quads; bulk path, all levels in one driver call).
template <class PolygonMesh, class NamedParameters = CGAL::parameters::Default_named_parameters>
void Mobius_CatmullClark_subdivision(PolygonMesh& pmesh, const NamedParameters& np = CGAL::parameters::default_values()) {
  cgal::detail::scheme(pmesh, NLS_SCHEME_CATMULL_CLARK, NLS_SUBDIVIDE_MOBIUS, np);
}
/// Möbius Kobbelt (quads, interpolating; CGAL's PQQ host with Mobius_kobbelt_mask_3).
template <class PolygonMesh, class NamedParameters = CGAL::parameters::Default_named_parameters>
void Mobius_Kobbelt_subdivision(PolygonMesh& pmesh, const NamedParameters& np = CGAL::parameters::default_values()) {
  cgal::detail::scheme(pmesh, NLS_SCHEME_KOBBELT, NLS_SUBDIVIDE_MOBIUS, np);
}
/// Möbius Doo–Sabin (dual; bulk path).
template <class PolygonMesh, class NamedParameters = CGAL::parameters::Default_named_parameters>
void Mobius_DooSabin_subdivision(PolygonMesh& pmesh, const NamedParameters& np = CGAL::parameters::default_values()) {
  cgal::detail::scheme(pmesh, NLS_SCHEME_DOO_SABIN, NLS_SUBDIVIDE_MOBIUS, np);
}
/// Möbius simplest (Peters–Reif; bulk path).
template <class PolygonMesh, class NamedParameters = CGAL::parameters::Default_named_parameters>
void Mobius_Simplest_subdivision(PolygonMesh& pmesh, const NamedParameters& np = CGAL::parameters::default_values()) {
  cgal::detail::scheme(pmesh, NLS_SCHEME_SIMPLEST, NLS_SUBDIVIDE_MOBIUS, np);
}
/// Möbius dual scheme (bulk path).
template <class PolygonMesh, class NamedParameters = CGAL::parameters::Default_named_parameters>
void Mobius_Dual_subdivision(PolygonMesh& pmesh, const NamedParameters& np = CGAL::parameters::default_values()) {
  cgal::detail::scheme(pmesh, NLS_SCHEME_DUAL, NLS_SUBDIVIDE_MOBIUS, np);
}
/// Möbius vertex insertion (bulk path).
template <class PolygonMesh, class NamedParameters = CGAL::parameters::Default_named_parameters>
void Mobius_VertexInsertion_subdivision(PolygonMesh& pmesh, const NamedParameters& np = CGAL::parameters::default_values()) {
  cgal::detail::scheme(pmesh, NLS_SCHEME_VERTEX_INSERTION, NLS_SUBDIVIDE_MOBIUS, np);
}
/// Möbius dual truncation (bulk path).
template <class PolygonMesh, class NamedParameters = CGAL::parameters::Default_named_parameters>
void Mobius_DualTruncation_subdivision(PolygonMesh& pmesh, const NamedParameters& np = CGAL::parameters::default_values()) {
  cgal::detail::scheme(pmesh, NLS_SCHEME_DUAL_TRUNCATION, NLS_SUBDIVIDE_MOBIUS, np);
}
/// Linear Loop (the driver's boundary rules; sharp features through edge_is_constrained_map
/// and vertex_is_constrained_map).
template <class PolygonMesh, class NamedParameters = CGAL::parameters::Default_named_parameters>
void Loop_subdivision(PolygonMesh& pmesh, const NamedParameters& np = CGAL::parameters::default_values()) {
  cgal::detail::scheme(pmesh, NLS_SCHEME_LOOP, 0, np);
}
/// Linear Catmull–Clark (sharp features as Loop_subdivision).
template <class PolygonMesh, class NamedParameters = CGAL::parameters::Default_named_parameters>
void CatmullClark_subdivision(PolygonMesh& pmesh, const NamedParameters& np = CGAL::parameters::default_values()) {
  cgal::detail::scheme(pmesh, NLS_SCHEME_CATMULL_CLARK, 0, np);
}
/// Linear Modified Butterfly.
template <class PolygonMesh, class NamedParameters = CGAL::parameters::Default_named_parameters>
void Butterfly_subdivision(PolygonMesh& pmesh, const NamedParameters& np = CGAL::parameters::default_values()) {
  cgal::detail::scheme(pmesh, NLS_SCHEME_MODIFIED_BUTTERFLY, 0, np);
}
/// Linear Kobbelt.
template <class PolygonMesh, class NamedParameters = CGAL::parameters::Default_named_parameters>
void Kobbelt_subdivision(PolygonMesh& pmesh, const NamedParameters& np = CGAL::parameters::default_values()) {
  cgal::detail::scheme(pmesh, NLS_SCHEME_KOBBELT, 0, np);
}
/// Linear Doo–Sabin.
template <class PolygonMesh, class NamedParameters = CGAL::parameters::Default_named_parameters>
void DooSabin_subdivision(PolygonMesh& pmesh, const NamedParameters& np = CGAL::parameters::default_values()) {
  cgal::detail::scheme(pmesh, NLS_SCHEME_DOO_SABIN, 0, np);
}
/// Linear simplest scheme.
template <class PolygonMesh, class NamedParameters = CGAL::parameters::Default_named_parameters>
void Simplest_subdivision(PolygonMesh& pmesh, const NamedParameters& np = CGAL::parameters::default_values()) {
  cgal::detail::scheme(pmesh, NLS_SCHEME_SIMPLEST, 0, np);
}
/// Linear dual scheme.
template <class PolygonMesh, class NamedParameters = CGAL::parameters::Default_named_parameters>
void Dual_subdivision(PolygonMesh& pmesh, const NamedParameters& np = CGAL::parameters::default_values()) {
  cgal::detail::scheme(pmesh, NLS_SCHEME_DUAL, 0, np);
}
/// Linear vertex insertion.
template <class PolygonMesh, class NamedParameters = CGAL::parameters::Default_named_parameters>
void VertexInsertion_subdivision(PolygonMesh& pmesh, const NamedParameters& np = CGAL::parameters::default_values()) {
  cgal::detail::scheme(pmesh, NLS_SCHEME_VERTEX_INSERTION, 0, np);
}
/// Linear dual truncation.
template <class PolygonMesh, class NamedParameters = CGAL::parameters::Default_named_parameters>
void DualTruncation_subdivision(PolygonMesh& pmesh, const NamedParameters& np = CGAL::parameters::default_values()) {
  cgal::detail::scheme(pmesh, NLS_SCHEME_DUAL_TRUNCATION, 0, np);
}
/// Spherelike interpolating subdivision (seed 003 §3; any polygons -> quads; no Möbius form).
/// Coincident points or a spike: NLS_STATUS_DEGENERATE_GEOMETRY.
template <class PolygonMesh, class NamedParameters = CGAL::parameters::Default_named_parameters>
void Spherelike_subdivision(PolygonMesh& pmesh, const NamedParameters& np = CGAL::parameters::default_values()) {
  cgal::detail::scheme(pmesh, NLS_SCHEME_SPHERELIKE, 0, np);
}
/// Differential-space subdivision with the Loop stencil (seed 001 §3; triangles):
/// number_of_iterations levels reconstructed once (one solve, not k solves of one level);
/// solver_max_iterations, solver_tolerance; §4.4 edits through vertex_curvature_scale_map and
/// vertex_normal_map; strict(true) adds the strict input checks and makes a folded edited
/// output NLS_STATUS_FOLDED_SURFACE. The Report has the solver's iterations and residual.
template <class PolygonMesh, class NamedParameters = CGAL::parameters::Default_named_parameters>
void Differential_Loop_subdivision(PolygonMesh& pmesh, const NamedParameters& np = CGAL::parameters::default_values()) {
  cgal::detail::differential_scheme(pmesh, NLS_DIFFERENTIAL_LOOP, np);
}
/// Differential-space subdivision with the Butterfly stencil (as Differential_Loop_subdivision).
template <class PolygonMesh, class NamedParameters = CGAL::parameters::Default_named_parameters>
void Differential_Butterfly_subdivision(PolygonMesh& pmesh, const NamedParameters& np = CGAL::parameters::default_values()) {
  cgal::detail::differential_scheme(pmesh, NLS_DIFFERENTIAL_BUTTERFLY, np);
}
/// DirMag (seed 001 §3.4): dirmag_levels levels of DirMag (default 1), then Butterfly.
template <class PolygonMesh, class NamedParameters = CGAL::parameters::Default_named_parameters>
void Differential_DirMag_subdivision(PolygonMesh& pmesh, const NamedParameters& np = CGAL::parameters::default_values()) {
  cgal::detail::differential_scheme(pmesh, NLS_DIFFERENTIAL_DIRMAG, np);
}

}  // namespace Subdivision_method_3
}  // namespace nlsubdiv

#endif  // NLSUBDIV_CGAL_H
