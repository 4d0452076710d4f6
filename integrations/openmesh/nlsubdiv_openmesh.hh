// nlsubdiv_openmesh.hh: nlsubdiv's subdivision schemes as OpenMesh uniform subdividers.
//
// Header-only, C++17, over the C ABI of include/nlsubdiv.h (link libnlsubdiv and
// OpenMeshCore). Used exactly like OpenMesh's own LoopT:
//
//   #include <nlsubdiv/openmesh/nlsubdiv_openmesh.hh>
//   nlsubdiv::openmesh::MobiusLoopT<Mesh> sd;
//   sd.attach(mesh); if (!sd(3)) std::puts(sd.message()); sd.detach();
//   // or in one call: sd(mesh, 3);
//
// Two kinds of classes (docs/integrations.md):
// * tier 1, MobiusLoopT, MobiusButterflyT and MobiusCatmullClarkT: the rules are evaluated
//   at each vertex star with OpenMesh's own connectivity (circulators over the half-edges),
//   through the tier-1 exports nls_mobius_loop_star / nls_mobius_butterfly_star /
//   nls_mobius_catmull_clark_star, nls_f4_hinted, nls_f4 and nls_face_point_with_ids; the new connectivity is written in the driver's layout, so the result
//   equals nls_mesh_subdivide with NLS_SUBDIVIDE_LITERAL on the same mesh (bit for bit where
//   the stars start at the driver's spokes, which this header arranges). These are the
//   paper's rules: the driver's default fold guard needs a pass over the whole mesh (each
//   star's trust from its neighbours' candidates), so for the guarded default use the bulk
//   classes (MobiusLoopBulkT, MobiusButterflyBulkT, MobiusCatmullClarkBulkT);
// * bulk, every scheme (BulkSubdividerT and the aliases MobiusKobbeltT, MobiusDooSabinT,
//   LinearLoopT, SpherelikeT, ...): the mesh is copied to flat arrays, subdivided with
//   nls_mesh_subdivide (any number of levels) and the connectivity rebuilt;
// * differential (DifferentialT and DifferentialLoopT / ButterflyT / DirMagT, triangles):
//   one nls_differential_subdivide call for all k levels of sd(k), the connectivity rebuilt.
//
// In both, the mesh is validated (nls_mesh_plan: manifold, oriented, finite, face
// types of the scheme) before anything is computed, and on any error the mesh is left exactly
// as it was: operator() returns false and status(), element() and message() say why. Nothing
// aborts the host and nothing throws (except std::bad_alloc from the host's own containers).
//
// Connectivity: the old vertices keep their handles (and their properties); edges and faces
// are rebuilt in the driver's order (OpenMesh's own subdividers split them instead). The
// properties of your own (not OpenMesh's built-in "f:", "e:" ones) are carried over where
// the subdivision keeps an element (detail::inherit_properties): a child face of face f
// takes f's face properties, a child edge of edge e (a half of it) e's edge properties,
// other new faces and edges hold the type's default value; half-edge properties and the
// built-in ones (normals, colours, status, feature flags) start from the default. The dual
// schemes (Doo–Sabin, Simplest, Dual) reset vertex properties to the default (their
// vertices are new points). docs/integrations.md lists it per scheme. Vertices of the mesh
// must not be marked deleted (call
// garbage_collection() first). Use a mesh with double points (OpenMesh::DefaultTraitsDouble):
// float points round every level.
//
// OpenMesh's two interfaces both work: `Sd sd; sd(mesh, n)`, and `Sd sd(mesh); sd(n)` (the
// (mesh&) constructor attaches in the derived class, once the object exists: the base one
// would call the pure prepare() too early), and the destructor detaches first (the base
// destructor would call the pure cleanup()). A mesh with float points is refused at compile
// time (a static_assert): float points would round every level.
//
// Licence: this header is part of nlsubdiv (MIT OR Apache-2.0); it contains no OpenMesh code.
#ifndef NLSUBDIV_OPENMESH_HH
#define NLSUBDIV_OPENMESH_HH

#include <OpenMesh/Tools/Subdivider/Uniform/SubdividerT.hh>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <string>
#include <utility>
#include <type_traits>
#include <memory>
#include <unordered_map>
#include <vector>

#include "nlsubdiv.h"
#include "../common/nlsubdiv_flat.hh"
#include "../common/nlsubdiv_pool.hh"

namespace nlsubdiv {
namespace openmesh {

using FlatMesh = nlsubdiv::flat::FlatMesh;

namespace detail {

using P3 = std::array<double, 3>;

inline bool finite3(const P3& p) { return std::isfinite(p[0]) && std::isfinite(p[1]) && std::isfinite(p[2]); }
inline P3 nan3() { return {NAN, NAN, NAN}; }
inline P3 add(const P3& a, const P3& b) { return {a[0] + b[0], a[1] + b[1], a[2] + b[2]}; }
inline P3 scale(const P3& a, double s) { return {a[0] * s, a[1] * s, a[2] * s}; }
inline P3 lin2(double wa, const P3& a, double wb, const P3& b) { return add(scale(a, wa), scale(b, wb)); }
inline P3 sum(const std::vector<P3>& v) {
  P3 s{0.0, 0.0, 0.0};
  for (const P3& p : v) s = add(s, p);
  return s;
}
inline P3 centroid(const std::vector<P3>& v) { return scale(sum(v), 1.0 / static_cast<double>(v.size())); }
inline P3 midpoint(const P3& a, const P3& b) { return scale(add(a, b), 0.5); }
/// The crease rule 3/4 v + 1/8 (b0 + b1), the driver's boundary fallback.
inline P3 crease(const P3& v, const P3& b0, const P3& b1) { return lin2(0.75, v, 0.125, add(b0, b1)); }

template <class Mesh>
P3 point(const Mesh& m, typename Mesh::VertexHandle v) {
  const auto& p = m.point(v);
  return {static_cast<double>(p[0]), static_cast<double>(p[1]), static_cast<double>(p[2])};
}

/// The mesh as flat arrays: vertices by index, faces by index, each face from the start of
/// its half-edge (`from_vertex(halfedge_handle(f))`). Fails (INVALID_ARGUMENT) when the mesh
/// holds deleted elements.
template <class Mesh>
nls_status export_flat(const Mesh& m, FlatMesh& out) {
  if (m.has_vertex_status() || m.has_face_status()) {
    for (auto v : m.all_vertices())
      if (m.has_vertex_status() && m.status(v).deleted()) return NLS_STATUS_INVALID_ARGUMENT;
    for (auto f : m.all_faces())
      if (m.has_face_status() && m.status(f).deleted()) return NLS_STATUS_INVALID_ARGUMENT;
  }
  out.positions.clear();
  out.offsets.assign(1, 0);
  out.indices.clear();
  out.positions.reserve(3 * m.n_vertices());
  for (auto v : m.all_vertices()) {
    P3 p = point(m, v);
    out.positions.insert(out.positions.end(), p.begin(), p.end());
  }
  out.indices.reserve(m.n_halfedges());
  for (auto f : m.all_faces()) {
    auto h0 = m.halfedge_handle(f), h = h0;
    std::size_t guard = 0;
    do {
      out.indices.push_back(static_cast<uint32_t>(m.from_vertex_handle(h).idx()));
      h = m.next_halfedge_handle(h);
    } while (h != h0 && ++guard < m.n_halfedges());
    out.offsets.push_back(static_cast<uint32_t>(out.indices.size()));
  }
  return NLS_STATUS_OK;
}

using nlsubdiv::flat::validate;

using nlsubdiv::flat::strict_check;

/// Replaces the connectivity of `m` by `flat` (the driver's output layout). The first
/// `m.n_vertices()` vertices of `flat` are the old vertices (same handles, new positions);
/// the others are appended. `flat` is a valid manifold mesh (the driver's output), so
/// add_face cannot fail; returns false if it does anyway (then the mesh is incomplete: the
/// callers restore their backup).
template <class Mesh>
bool rebuild(Mesh& m, const FlatMesh& flat) {
  using Point = typename Mesh::Point;
  using Scalar = typename Point::value_type;
  const std::size_t nv_old = m.n_vertices();
  if (flat.vertex_count() < nv_old) return false;
  m.request_vertex_status();
  m.request_edge_status();
  m.request_halfedge_status();
  m.request_face_status();
  for (auto f : m.faces()) m.delete_face(f, false);
  m.garbage_collection();
  bool ok = m.n_vertices() == nv_old && m.n_faces() == 0;
  auto pt = [&](std::size_t i) {
    return Point(static_cast<Scalar>(flat.positions[3 * i]), static_cast<Scalar>(flat.positions[3 * i + 1]),
                 static_cast<Scalar>(flat.positions[3 * i + 2]));
  };
  for (std::size_t i = 0; i < nv_old && ok; ++i) m.set_point(m.vertex_handle(static_cast<int>(i)), pt(i));
  for (std::size_t i = nv_old; i < flat.vertex_count() && ok; ++i) m.add_vertex(pt(i));
  std::vector<typename Mesh::VertexHandle> corners;
  for (std::size_t f = 0; f + 1 < flat.offsets.size() && ok; ++f) {
    corners.clear();
    for (uint32_t c = flat.offsets[f]; c < flat.offsets[f + 1]; ++c)
      corners.push_back(m.vertex_handle(static_cast<int>(flat.indices[c])));
    // add_face makes the face's half-edge the one into corners[0]: rotate by one so the
    // face starts (from_vertex of its half-edge) at corners[0], the driver's first corner.
    auto fh = m.add_face(corners);
    if (!fh.is_valid()) {
      ok = false;
      break;
    }
    auto h = m.halfedge_handle(fh);
    std::size_t guard = 0;
    while (m.from_vertex_handle(h) != corners[0] && ++guard <= corners.size()) h = m.next_halfedge_handle(h);
    m.set_halfedge_handle(fh, h);
  }
  m.release_face_status();
  m.release_halfedge_status();
  m.release_edge_status();
  m.release_vertex_status();
  return ok;
}

/// Whether `m` has properties of its own (not OpenMesh's built-in "v:", "e:", "f:" ones) on
/// elements of kind `prefix`.
template <class It>
bool has_user_props(It b, It e, const char* prefix) {
  for (; b != e; ++b)
    if (*b && (*b)->name().compare(0, 2, prefix) != 0) return true;
  return false;
}

inline uint64_t edge_key(uint32_t a, uint32_t b) { return (static_cast<uint64_t>(std::min(a, b)) << 32) | std::max(a, b); }

/// The sorted (min, max) keys of the edges of `f` (the driver's edge order).
inline std::vector<uint64_t> edge_keys(const FlatMesh& f) {
  std::vector<uint64_t> keys;
  keys.reserve(f.indices.size());
  for (std::size_t i = 0; i + 1 < f.offsets.size(); ++i)
    for (uint32_t c = f.offsets[i]; c < f.offsets[i + 1]; ++c)
      keys.push_back(edge_key(f.indices[c], f.indices[c + 1 < f.offsets[i + 1] ? c + 1 : f.offsets[i]]));
  std::sort(keys.begin(), keys.end());
  keys.erase(std::unique(keys.begin(), keys.end()), keys.end());
  return keys;
}

/// The face containing corner `h` of `f` (-1 if none).
inline long face_of_corner(const FlatMesh& f, uint64_t h) {
  auto it = std::upper_bound(f.offsets.begin(), f.offsets.end(), h);
  if (it == f.offsets.begin() || it == f.offsets.end()) return -1;
  return static_cast<long>(it - f.offsets.begin()) - 1;
}

/// The input face of each output face after `levels` levels of `scheme` on `in` (the driver's
/// output order, docs/mesh-and-linear-schemes.md), -1 where an output face lies in no one input
/// face: Loop and Modified Butterfly: face g of level k comes from face g / 4 of level k − 1;
/// the quad schemes (Catmull–Clark, Kobbelt, Spherelike) and vertex insertion: output face h
/// is corner h of the level before (corners of a refined level: 4 or 3 per face); Doo–Sabin
/// and Simplest: the first faces are the input faces shrunk (face g < F is face g's); Dual and
/// dual truncation: none.
inline std::vector<long> face_parents(uint32_t scheme, const FlatMesh& in, uint32_t levels, std::size_t nf_out) {
  std::vector<long> parent(nf_out, -1);
  const std::size_t nf_in = in.face_count();
  for (std::size_t g = 0; g < nf_out; ++g) {
    if (levels == 0) {
      parent[g] = g < nf_in ? static_cast<long>(g) : -1;
      continue;
    }
    uint64_t h = g;
    switch (scheme) {
      case NLS_SCHEME_LOOP:
      case NLS_SCHEME_MODIFIED_BUTTERFLY:
        for (uint32_t k = 0; k < levels; ++k) h /= 4;
        parent[g] = h < nf_in ? static_cast<long>(h) : -1;
        break;
      case NLS_SCHEME_CATMULL_CLARK:
      case NLS_SCHEME_KOBBELT:
      case NLS_SCHEME_SPHERELIKE:
        for (uint32_t k = 1; k < levels; ++k) h /= 4;
        parent[g] = face_of_corner(in, h);
        break;
      case NLS_SCHEME_VERTEX_INSERTION:
        for (uint32_t k = 1; k < levels; ++k) h /= 3;
        parent[g] = face_of_corner(in, h);
        break;
      case NLS_SCHEME_DOO_SABIN:
      case NLS_SCHEME_SIMPLEST:
        parent[g] = g < nf_in ? static_cast<long>(g) : -1;
        break;
      default:
        break;
    }
  }
  return parent;
}

/// The input edge (its index in `m_old`) of each edge of the output, by the output's (min, max)
/// vertex pair: Loop, Modified Butterfly and the quad schemes split every edge (a, b) of a
/// level at its edge point (vertex count of the level + the edge's rank in (min, max) order)
/// into (a, e) and (e, b), level by level (the connectivity of the intermediate levels from
/// the linear driver, one level per call); vertex insertion keeps the input edges whole; the
/// other schemes have no edge that lies on one input edge.
template <class Mesh>
std::unordered_map<uint64_t, int> edge_origins(const Mesh& m_old, uint32_t scheme, const FlatMesh& in, uint32_t levels) {
  std::unordered_map<uint64_t, int> origin;
  for (auto e : m_old.edges()) {
    auto h = m_old.halfedge_handle(e, 0);
    origin[edge_key(static_cast<uint32_t>(m_old.from_vertex_handle(h).idx()), static_cast<uint32_t>(m_old.to_vertex_handle(h).idx()))] =
        e.idx();
  }
  const bool splits = scheme == NLS_SCHEME_LOOP || scheme == NLS_SCHEME_MODIFIED_BUTTERFLY || scheme == NLS_SCHEME_CATMULL_CLARK ||
                      scheme == NLS_SCHEME_KOBBELT || scheme == NLS_SCHEME_SPHERELIKE;
  if (levels == 0 || scheme == NLS_SCHEME_VERTEX_INSERTION) return origin;
  if (!splits) return {};
  FlatMesh cur = in, next;
  for (uint32_t k = 0; k < levels; ++k) {
    const std::vector<uint64_t> keys = edge_keys(cur);
    const uint64_t nv = cur.vertex_count();
    std::unordered_map<uint64_t, int> child;
    for (std::size_t r = 0; r < keys.size(); ++r) {
      auto it = origin.find(keys[r]);
      if (it == origin.end()) continue;
      const uint32_t a = static_cast<uint32_t>(keys[r] >> 32), b = static_cast<uint32_t>(keys[r] & 0xffffffffu);
      const uint32_t ep = static_cast<uint32_t>(nv + r);
      child[edge_key(a, ep)] = it->second;
      child[edge_key(ep, b)] = it->second;
    }
    origin.swap(child);
    if (k + 1 < levels) {
      uint32_t el = 0, fb = 0;
      if (nlsubdiv::flat::run_levels(scheme, 0, cur, 1, next, el, fb) != NLS_STATUS_OK) return {};
      std::swap(cur, next);
    }
  }
  return origin;
}

/// Rearranges the property `old_p` (of the old elements) into the new elements: new element j
/// takes old element parent[j]'s value, or the type's default where parent[j] < 0; returns
/// the new property object (same type, name and persistence), or null.
inline OpenMesh::BaseProperty* inherited(const OpenMesh::BaseProperty& old_p, const std::vector<long>& parent) {
  OpenMesh::BaseProperty* c = old_p.clone();
  const std::size_t n_old = c->n_elements(), n_new = parent.size();
  c->resize(n_old + n_new);
  for (std::size_t j = 0; j < n_new; ++j)
    if (parent[j] >= 0 && static_cast<std::size_t>(parent[j]) < n_old) c->copy(static_cast<std::size_t>(parent[j]), n_old + j);
  for (std::size_t j = 0; j < n_new; ++j) c->swap(j, n_old + j);
  c->resize(n_new);
  return c;
}

/// Puts into `m` (new connectivity) the face and edge properties of `m_old` (the mesh before
/// `levels` levels of `scheme` on `in`, its flat copy) that the children inherit: a child face
/// of face f takes f's values, a child edge of edge e takes e's values (face_parents,
/// edge_origins); the other faces and edges hold the property type's default value.
/// OpenMesh's built-in properties ("f:", "e:" names: normals, colours, status, ...) are not
/// inherited. Dual schemes (Doo–Sabin, Simplest, Dual), whose output vertices are not the
/// input vertices, reset the vertex properties of their own to the default value.
template <class Mesh>
void inherit_properties(Mesh& m, const Mesh& m_old, uint32_t scheme, const FlatMesh& in, uint32_t levels) {
  if (has_user_props(m.fprops_begin(), m.fprops_end(), "f:")) {
    const std::vector<long> parent = face_parents(scheme, in, levels, m.n_faces());
    auto it = m.fprops_begin();
    auto old = m_old.fprops_begin();
    // Same positions: the properties of `m` are those of `m_old` (rebuild may append and
    // release a status property after them).
    for (; it != m.fprops_end() && old != m_old.fprops_end(); ++it, ++old) {
      if (!*it || !*old || (*it)->name().compare(0, 2, "f:") == 0 || (*it)->name() != (*old)->name()) continue;
      OpenMesh::BaseProperty* c = inherited(**old, parent);
      delete *it;
      *it = c;
    }
  }
  if (has_user_props(m.eprops_begin(), m.eprops_end(), "e:")) {
    const std::unordered_map<uint64_t, int> origin = edge_origins(m_old, scheme, in, levels);
    std::vector<long> parent(m.n_edges(), -1);
    for (auto e : m.edges()) {
      auto h = m.halfedge_handle(e, 0);
      auto f = origin.find(edge_key(static_cast<uint32_t>(m.from_vertex_handle(h).idx()), static_cast<uint32_t>(m.to_vertex_handle(h).idx())));
      if (f != origin.end()) parent[static_cast<std::size_t>(e.idx())] = f->second;
    }
    auto it = m.eprops_begin();
    auto old = m_old.eprops_begin();
    // Same positions: the properties of `m` are those of `m_old` (rebuild may append and
    // release a status property after them).
    for (; it != m.eprops_end() && old != m_old.eprops_end(); ++it, ++old) {
      if (!*it || !*old || (*it)->name().compare(0, 2, "e:") == 0 || (*it)->name() != (*old)->name()) continue;
      OpenMesh::BaseProperty* c = inherited(**old, parent);
      delete *it;
      *it = c;
    }
  }
  if (levels > 0 && (scheme == NLS_SCHEME_DOO_SABIN || scheme == NLS_SCHEME_SIMPLEST || scheme == NLS_SCHEME_DUAL))
    for (auto it = m.vprops_begin(); it != m.vprops_end(); ++it)
      if (*it && (*it)->name().compare(0, 2, "v:") != 0) {
        (*it)->clear();
        (*it)->resize(m.n_vertices());
      }
}

}  // namespace detail

/// What the last call did: status (NLS_STATUS_OK on success), the element the status names
/// (a face, vertex or output vertex of the level being computed, or NLS_NO_ELEMENT), the
/// level (1-based) at which it arose, and the fallback count (elements that took the
/// documented linear rule of the Möbius schemes; with set_strict(true) a fallback is the error
/// NLS_STATUS_FALLBACK_IN_STRICT_MODE instead).
struct Outcome {
  nls_status status = NLS_STATUS_OK;
  uint32_t element = NLS_NO_ELEMENT;
  uint32_t level = 0;
  uint32_t fallbacks = 0;
};

/// Common base of the nlsubdiv subdividers: the status accessors and the transactional
/// level loop. `subdivide` validates, runs `levels` levels through `level_()` (tier 1) or
/// one bulk call, and restores the mesh on failure.
template <typename MeshType, typename RealType = double>
class SubdividerBaseT : public OpenMesh::Subdivider::Uniform::SubdividerT<MeshType, RealType> {
 public:
  typedef OpenMesh::Subdivider::Uniform::SubdividerT<MeshType, RealType> parent_t;
  typedef MeshType mesh_t;
  typedef RealType real_t;

  static_assert(std::is_same<typename std::remove_cv<typename MeshType::Point::value_type>::type, double>::value,
                "nlsubdiv subdividers need double points (OpenMesh::DefaultTraitsDouble, or a Point of Vec3d): "
                "float points would round every level");

  // No (mesh_t&) constructor here: the base one would call prepare() before this object
  // exists. The derived classes have one that attaches once they are built.
  SubdividerBaseT() = default;

  /// Strict mode: fallbacks become NLS_STATUS_FALLBACK_IN_STRICT_MODE, and the input is also
  /// refused for what the kernel accepts by policy but is most likely a mistake
  /// (detail::strict_check: unreferenced vertices, duplicated vertices, zero-area faces). The
  /// mesh is then left unchanged.
  void set_strict(bool strict) { strict_ = strict; }
  bool strict() const { return strict_; }

  nls_status status() const { return out_.status; }
  uint32_t element() const { return out_.element; }
  uint32_t level() const { return out_.level; }
  uint32_t fallbacks() const { return out_.fallbacks; }
  const Outcome& outcome() const { return out_; }
  /// "ok", or the status text with the element and level, e.g.
  /// "level 1: the scheme does not accept this face type (element 3)".
  const char* message() const { return msg_.c_str(); }

 protected:
  bool prepare(mesh_t&) override { return true; }  // no properties: per-level arrays only
  bool cleanup(mesh_t&) override { return true; }

  bool fail(nls_status s, uint32_t element, uint32_t level) {
    out_.status = s;
    out_.element = element;
    out_.level = level;
    char buf[64];
    std::snprintf(buf, sizeof buf, "level %u: ", level);
    msg_ = std::string(buf) + nls_status_str(s);
    if (element != NLS_NO_ELEMENT) {
      std::snprintf(buf, sizeof buf, " (%s %u)", nlsubdiv::flat::element_kind(s), element);
      msg_ += buf;
    }
    return false;
  }
  void reset() {
    out_ = Outcome();
    msg_ = "ok";
  }

  Outcome out_;
  std::string msg_ = "ok";
  bool strict_ = false;
};

// ---------------------------------------------------------------------------------------
// Bulk path: every scheme, through nls_mesh_subdivide.
// ---------------------------------------------------------------------------------------

/// `levels` levels of `Scheme` (NLS_SCHEME_*) with `Flags` (NLS_SUBDIVIDE_MOBIUS or 0) in one
/// nls_mesh_subdivide call on a flat copy of the mesh, then the connectivity is
/// rebuilt in the driver's layout: the result is the driver's, bit for bit (modulo the point
/// type). With update_points = false the old vertices keep their positions at every level.
///
/// Sharp features: with set_feature_creases(true), the mesh's feature edges
/// (`status(eh).feature()`, OpenMesh's own flag for sharp edges) are crease tags of the given
/// sharpness and its feature vertices corners (linear Loop and Catmull–Clark with
/// OpenSubdiv's rules, linear Modified Butterfly and Kobbelt with their 4-point crease rule,
/// the Möbius versions of these four with the Möbius curve rules along the creases; any
/// other scheme fails with NLS_STATUS_TAGS_NOT_SUPPORTED when the mesh has a feature). With
/// set_sharpness_properties, per-edge and per-vertex sharpness values from OpenMesh
/// properties tag their elements too (semi-sharp creases with their own values). The tags are carried level by
/// level inside the one call, so update_points = false (one call per level) is refused with
/// NLS_STATUS_INVALID_ARGUMENT when there is a feature. The output carries no feature flags.
template <typename MeshType, uint32_t Scheme, uint32_t Flags, typename RealType = double>
class BulkSubdividerT : public SubdividerBaseT<MeshType, RealType> {
 public:
  typedef SubdividerBaseT<MeshType, RealType> base_t;
  typedef MeshType mesh_t;
  BulkSubdividerT() = default;
  /// OpenMesh's interface 1: attached to `m`, then `sd(n)`.
  explicit BulkSubdividerT(mesh_t& m) { this->attach(m); }
  ~BulkSubdividerT() override { this->detach(); }

  /// Feature edges as creases of `sharpness` (OpenSubdiv's scale: 10 or more is infinitely
  /// sharp, below it semi-sharp) and feature vertices as corners of `corner_sharpness`.
  void set_feature_creases(bool on, double sharpness = 10.0, double corner_sharpness = 10.0) {
    features_ = on;
    crease_sharpness_ = sharpness;
    corner_sharpness_ = corner_sharpness;
  }
  /// Per-element sharpness from OpenMesh properties (OpenSubdiv's scale): every edge whose
  /// `edge_sharpness` value is not 0 is a crease of that sharpness and every vertex whose
  /// `vertex_sharpness` value is not 0 a corner, whether or not feature creases are on; a
  /// value wins over the feature flag's uniform sharpness for its element. NaN, negative or
  /// infinite values reach the kernel, which refuses them (NLS_STATUS_INVALID_SHARPNESS,
  /// mesh unchanged). A default-constructed (invalid) handle is not read.
  void set_sharpness_properties(OpenMesh::EPropHandleT<double> edge_sharpness,
                                OpenMesh::VPropHandleT<double> vertex_sharpness = OpenMesh::VPropHandleT<double>()) {
    edge_sharpness_ = edge_sharpness;
    vertex_sharpness_ = vertex_sharpness;
  }
  /// NLS_CREASE_UNIFORM (the default) or NLS_CREASE_CHAIKIN.
  void set_crease_method(uint32_t method) { crease_method_ = method; }
  /// Möbius classes (Flags with NLS_SUBDIVIDE_MOBIUS): the weight u of the linear result in
  /// the Möbius–linear spectrum (seed 000 §7.2, nls_subdivide_options::linear_weight): each
  /// level is (1 − u) · Möbius + u · linear; 0 (the default) is the Möbius result and 1 the
  /// linear one, bit for bit. NaN or outside [0, 1]: NLS_STATUS_INVALID_ARGUMENT, mesh
  /// unchanged. The linear classes ignore it.
  void set_linear_weight(double u) { linear_weight_ = u; }
  double linear_weight() const { return linear_weight_; }
  /// Threads of the kernel's passes, the calling thread included: 1 (the default) runs on the
  /// calling thread only, 0 takes the hardware's thread count. The subdivider starts a pool
  /// (nlsubdiv::ThreadPool, nlsubdiv_pool.hh) here, once, and every later call reuses it.
  /// The result, the fallbacks and the errors are the same bits for every thread count.
  void set_threads(unsigned n) {
    if (n == 1) {
      pool_.reset();
      return;
    }
    pool_ = std::make_shared<nlsubdiv::ThreadPool>(n);
  }
  unsigned threads() const { return pool_ ? pool_->threads() : 1u; }
  /// Möbius classes: the weight u of the linear result per vertex from an OpenMesh property
  /// (nls_subdivide_options::linear_weights; the convention of set_linear_weight, which it
  /// replaces): each output vertex of each level takes a weight carried from its parents (an
  /// old vertex its own, an edge point the mean of its ends, a face point the mean of its
  /// corners, a Doo–Sabin corner point its vertex's) and is (1 − u) · Möbius + u · linear.
  /// Equal values everywhere are set_linear_weight of that value, bit for bit. A value NaN
  /// or outside [0, 1] is NLS_STATUS_INVALID_ARGUMENT naming the vertex (element = its
  /// index), mesh unchanged. The weights live inside one call, so update_points = false (one
  /// call per level) is refused with NLS_STATUS_INVALID_ARGUMENT. A default-constructed
  /// (invalid) handle is not read (the global weight); the linear classes ignore it.
  void set_linear_weight_property(OpenMesh::VPropHandleT<double> linear_weights) { linear_weights_ = linear_weights; }

  const char* name() const override {
    static const char* const names[] = {"Loop", "Catmull-Clark", "Modified Butterfly", "Kobbelt", "Doo-Sabin",
                                        "Simplest", "Dual", "Vertex insertion", "Dual truncation", "Spherelike"};
    static const std::string n = std::string((Flags & NLS_SUBDIVIDE_MOBIUS) ? "Uniform nlsubdiv Moebius " : "Uniform nlsubdiv ") +
                                 (Scheme < 10 ? names[Scheme] : "?");
    return n.c_str();
  }

 protected:
  bool subdivide(mesh_t& m, size_t n, const bool update_points = true) override {
    this->reset();
    if (n > NLS_MAX_LEVELS) return this->fail(NLS_STATUS_INVALID_ARGUMENT, NLS_NO_ELEMENT, 0);
    FlatMesh in;
    nls_status s = detail::export_flat(m, in);
    if (s != NLS_STATUS_OK) return this->fail(s, NLS_NO_ELEMENT, 0);
    const uint32_t flags = Flags | (this->strict_ ? NLS_SUBDIVIDE_STRICT : 0u);
    const std::size_t nv_old = in.vertex_count();
    if (this->strict_) {
      uint32_t el = NLS_NO_ELEMENT;
      // The kernel's own validation first (its statuses win), then the strict input checks.
      s = detail::validate(Scheme, flags, in, el);
      if (s == NLS_STATUS_OK) s = detail::strict_check(in, el);
      if (s != NLS_STATUS_OK) return this->fail(s, el, 1);
    }
    tags_ = nlsubdiv::flat::FlatTags();
    tags_.method = crease_method_;
    if (features_ || edge_sharpness_.is_valid() || vertex_sharpness_.is_valid()) feature_tags(m, tags_);
    if (!tags_.empty() && !update_points) return this->fail(NLS_STATUS_INVALID_ARGUMENT, NLS_NO_ELEMENT, 0);
    weights_.clear();
    if ((Flags & NLS_SUBDIVIDE_MOBIUS) && linear_weights_.is_valid()) {
      // In export_flat's vertex order (the vertex indices).
      if (!update_points) return this->fail(NLS_STATUS_INVALID_ARGUMENT, NLS_NO_ELEMENT, 0);
      weights_.reserve(m.n_vertices());
      for (auto v : m.all_vertices()) weights_.push_back(m.property(linear_weights_, v));
    }
    FlatMesh cur = in, next;
    // update_points = false: one level at a time, old vertices put back after each.
    const uint32_t per_call = update_points ? static_cast<uint32_t>(n) : 1u;
    const std::size_t calls = n == 0 ? 1 : (update_points ? 1 : n);
    for (std::size_t c = 0; c < calls; ++c) {
      if (!run(cur, per_call, flags, next, static_cast<uint32_t>(c))) return false;
      if (!update_points) {
        const std::size_t keep = cur.vertex_count();
        std::copy(cur.positions.begin(), cur.positions.begin() + static_cast<std::ptrdiff_t>(3 * keep), next.positions.begin());
      }
      std::swap(cur, next);
    }
    if (cur.vertex_count() < nv_old) return this->fail(NLS_STATUS_INVALID_ARGUMENT, NLS_NO_ELEMENT, 0);
    mesh_t backup = m;
    if (!detail::rebuild(m, cur)) {
      m = backup;
      return this->fail(NLS_STATUS_NON_MANIFOLD_EDGE, NLS_NO_ELEMENT, static_cast<uint32_t>(n));
    }
    detail::inherit_properties(m, backup, Scheme, in, static_cast<uint32_t>(n));
    return true;
  }

 private:
  bool run(const FlatMesh& in, uint32_t levels, uint32_t flags, FlatMesh& out, uint32_t done) {
    uint32_t element = NLS_NO_ELEMENT, fallbacks = 0;
    const nls_tags t = tags_.view();
    nls_status s = nlsubdiv::flat::run_levels(Scheme, flags, in, levels, out, element, fallbacks, tags_.empty() ? nullptr : &t,
                                              (Flags & NLS_SUBDIVIDE_MOBIUS) ? linear_weight_ : 0.0,
                                              weights_.empty() ? nullptr : weights_.data(),
                                              pool_ ? pool_->executor() : nullptr);
    if (s != NLS_STATUS_OK) return this->fail(s, element, done + 1);
    this->out_.fallbacks += fallbacks;
    return true;
  }

  /// The feature edges and vertices of `m` (with feature creases on) and the elements with
  /// a sharpness property value as tags (vertex indices are export_flat's).
  void feature_tags(const mesh_t& m, nlsubdiv::flat::FlatTags& t) const {
    const bool edge_flags = features_ && m.has_edge_status(), vertex_flags = features_ && m.has_vertex_status();
    for (auto e : m.edges()) {
      double s = edge_sharpness_.is_valid() ? m.property(edge_sharpness_, e) : 0.0;
      if (s == 0.0 && edge_flags && m.status(e).feature()) s = crease_sharpness_;
      if (s == 0.0) continue;  // smooth (NaN is not 0: the kernel refuses it)
      auto h = m.halfedge_handle(e, 0);
      t.crease_vertices.push_back(static_cast<uint32_t>(m.from_vertex_handle(h).idx()));
      t.crease_vertices.push_back(static_cast<uint32_t>(m.to_vertex_handle(h).idx()));
      t.crease_sharpness.push_back(s);
    }
    for (auto v : m.vertices()) {
      double s = vertex_sharpness_.is_valid() ? m.property(vertex_sharpness_, v) : 0.0;
      if (s == 0.0 && vertex_flags && m.status(v).feature()) s = corner_sharpness_;
      if (s == 0.0) continue;
      t.corner_vertices.push_back(static_cast<uint32_t>(v.idx()));
      t.corner_sharpness.push_back(s);
    }
  }

  bool features_ = false;
  OpenMesh::EPropHandleT<double> edge_sharpness_;
  OpenMesh::VPropHandleT<double> vertex_sharpness_;
  double crease_sharpness_ = 10.0;
  double corner_sharpness_ = 10.0;
  uint32_t crease_method_ = NLS_CREASE_UNIFORM;
  double linear_weight_ = 0.0;
  std::shared_ptr<nlsubdiv::ThreadPool> pool_;  // shared by copies of the subdivider
  OpenMesh::VPropHandleT<double> linear_weights_;
  std::vector<double> weights_;
  nlsubdiv::flat::FlatTags tags_;
};

/// Möbius Modified Butterfly through the driver (the tier-1 class MobiusButterflyT is below).
template <typename M> using MobiusButterflyBulkT = BulkSubdividerT<M, NLS_SCHEME_MODIFIED_BUTTERFLY, NLS_SUBDIVIDE_MOBIUS>;
/// Möbius Kobbelt (interpolating quad scheme; bulk path: its virtual points need a 2-ring).
template <typename M> using MobiusKobbeltT = BulkSubdividerT<M, NLS_SCHEME_KOBBELT, NLS_SUBDIVIDE_MOBIUS>;
/// Möbius Doo–Sabin (bulk path; the mesh must be a PolyMesh).
template <typename M> using MobiusDooSabinT = BulkSubdividerT<M, NLS_SCHEME_DOO_SABIN, NLS_SUBDIVIDE_MOBIUS>;
/// Bulk Möbius Loop and Catmull–Clark: the default mode, with the fold guard (the tier-1
/// classes below run the paper's rules, the driver's literal mode; the two agree where the
/// guard changes nothing).
template <typename M> using MobiusLoopBulkT = BulkSubdividerT<M, NLS_SCHEME_LOOP, NLS_SUBDIVIDE_MOBIUS>;
template <typename M> using MobiusCatmullClarkBulkT = BulkSubdividerT<M, NLS_SCHEME_CATMULL_CLARK, NLS_SUBDIVIDE_MOBIUS>;
/// The linear schemes (equal to OpenMesh's LoopT, ModifiedButterflyT, CatmullClarkT on the
/// meshes they accept; peer-rules.md gives the boundary rules).
template <typename M> using LinearLoopT = BulkSubdividerT<M, NLS_SCHEME_LOOP, 0>;
template <typename M> using LinearCatmullClarkT = BulkSubdividerT<M, NLS_SCHEME_CATMULL_CLARK, 0>;
template <typename M> using LinearButterflyT = BulkSubdividerT<M, NLS_SCHEME_MODIFIED_BUTTERFLY, 0>;
template <typename M> using LinearKobbeltT = BulkSubdividerT<M, NLS_SCHEME_KOBBELT, 0>;
template <typename M> using LinearDooSabinT = BulkSubdividerT<M, NLS_SCHEME_DOO_SABIN, 0>;
/// Spherelike interpolating subdivision (seed 003 §3; any polygons -> quads, so use a
/// PolyMesh; no Möbius form). Coincident points of one circle or a spike are
/// NLS_STATUS_DEGENERATE_GEOMETRY naming the output vertex (it has no fallback).
template <typename M> using SpherelikeT = BulkSubdividerT<M, NLS_SCHEME_SPHERELIKE, 0>;

// ---------------------------------------------------------------------------------------
// Differential-space subdivision (seed 001 §3): nls_differential_subdivide.
// ---------------------------------------------------------------------------------------

/// Differential-space subdivision of a triangle mesh: the differential coordinates are
/// subdivided with the stencil (set_stencil: NLS_DIFFERENTIAL_LOOP, _BUTTERFLY or _DIRMAG)
/// and the mesh is reconstructed from them by a least-squares solve (nls_differential_subdivide).
///
/// The reconstruction is global and done once for all levels: `sd(k)` is ONE
/// nls_differential_subdivide call with levels = k, which is not the same as k calls of
/// `sd(1)` (each would reconstruct from a re-estimated differential mesh). For the same
/// reason update_points = false is refused (NLS_STATUS_INVALID_ARGUMENT).
///
/// Transactional like the other classes: on any error, including NLS_STATUS_NOT_CONVERGED
/// (the solver reached max_iterations; iterations() and residual() then say how far it got),
/// the mesh is unchanged, operator() returns false and status() / message() say why. Faces
/// that are not triangles are NLS_STATUS_UNSUPPORTED_FACE_TYPE naming the face. set_strict(true)
/// adds the strict input checks (detail::strict_check) and, with §4.4 edits
/// (set_curvature_scale_property, set_normal_property), makes a folded output
/// NLS_STATUS_FOLDED_SURFACE naming the first folded face; the kernel has no fallbacks here.
template <typename MeshType, typename RealType = double>
class DifferentialT : public SubdividerBaseT<MeshType, RealType> {
 public:
  typedef SubdividerBaseT<MeshType, RealType> base_t;
  typedef MeshType mesh_t;
  DifferentialT() { nls_differential_default_options(&opt_); }
  explicit DifferentialT(uint32_t stencil) : DifferentialT() { set_stencil(stencil); }
  /// OpenMesh's interface 1: attached to `m`, then `sd(n)`.
  explicit DifferentialT(mesh_t& m) : DifferentialT() { this->attach(m); }
  ~DifferentialT() override { this->detach(); }

  /// NLS_DIFFERENTIAL_LOOP (default), NLS_DIFFERENTIAL_BUTTERFLY or NLS_DIFFERENTIAL_DIRMAG
  /// (then dirmag_levels() levels use DirMag, default 1).
  void set_stencil(uint32_t stencil) { stencil_ = stencil; }
  uint32_t stencil() const { return stencil_; }
  /// DirMag only: the first this many levels use DirMag (at least 1; seed 001 uses 1 or 2).
  void set_dirmag_levels(uint32_t n) { dirmag_levels_ = n; }
  uint32_t dirmag_levels() const { return dirmag_levels_; }
  /// Relative residual of the reconstruction to reach (default 1e-10).
  void set_tolerance(double t) { opt_.tolerance = t; }
  double tolerance() const { return opt_.tolerance; }
  /// Iteration cap of the reconstruction (default 100); reaching it is NLS_STATUS_NOT_CONVERGED.
  void set_max_iterations(uint32_t n) { opt_.max_iterations = n; }
  uint32_t max_iterations() const { return opt_.max_iterations; }

  /// §4.4 editing (nls_differential_options::curvature_scale): a vertex property of the
  /// attached mesh with one factor per control vertex on its mean curvature (1 keeps it, 2
  /// doubles it). The property is read at each call; an invalid handle (the default) means
  /// no curvature edit. A non-finite factor is refused with the kernel's status naming the
  /// vertex, mesh unchanged.
  void set_curvature_scale_property(OpenMesh::VPropHandleT<double> h) { curvature_ = h; }
  /// §4.4 editing (nls_differential_options::normals): a vertex property with the target
  /// normal direction of each control vertex (normalised by the library; a zero vector keeps
  /// the vertex's own normal). An invalid handle (the default) means no normal edit.
  void set_normal_property(OpenMesh::VPropHandleT<OpenMesh::Vec3d> h) { normals_ = h; }
  /// The solver report of the last call (success or NLS_STATUS_NOT_CONVERGED; zero otherwise).
  const nls_differential_report& report() const { return rep_; }
  uint32_t iterations() const { return rep_.iterations; }
  double residual() const { return rep_.relative_residual; }

  const char* name() const override {
    return stencil_ == NLS_DIFFERENTIAL_BUTTERFLY ? "Uniform nlsubdiv differential Butterfly"
           : stencil_ == NLS_DIFFERENTIAL_DIRMAG  ? "Uniform nlsubdiv differential DirMag"
                                                  : "Uniform nlsubdiv differential Loop";
  }

 protected:
  bool subdivide(mesh_t& m, size_t n, const bool update_points = true) override {
    this->reset();
    rep_ = nls_differential_report{};
    if (n > NLS_MAX_LEVELS || !update_points) return this->fail(NLS_STATUS_INVALID_ARGUMENT, NLS_NO_ELEMENT, 0);
    FlatMesh in, out;
    nls_status s = detail::export_flat(m, in);
    if (s != NLS_STATUS_OK) return this->fail(s, NLS_NO_ELEMENT, 0);
    uint32_t el = NLS_NO_ELEMENT;
    nls_differential_options o = opt_;
    o.scheme = stencil_;
    o.levels = static_cast<uint32_t>(n);
    o.dirmag_levels = stencil_ == NLS_DIFFERENTIAL_DIRMAG ? dirmag_levels_ : 0u;
    // §4.4 edits from the vertex properties, in vertex index order (export_flat's); with
    // strict mode a folded edited output is NLS_STATUS_FOLDED_SURFACE.
    std::vector<double> curvature, normals;
    if (curvature_.is_valid()) {
      for (auto v : m.all_vertices()) curvature.push_back(m.property(curvature_, v));
      o.curvature_scale = curvature.data();
    } else {
      o.curvature_scale = nullptr;
    }
    if (normals_.is_valid()) {
      for (auto v : m.all_vertices()) {
        const OpenMesh::Vec3d& n = m.property(normals_, v);
        normals.insert(normals.end(), {n[0], n[1], n[2]});
      }
      o.normals = normals.data();
    } else {
      o.normals = nullptr;
    }
    o.strict = this->strict_ ? 1u : 0u;
    if (this->strict_) {
      // The kernel's validation first (its statuses win: plan), then the strict checks.
      s = nlsubdiv::flat::validate(NLS_SCHEME_LOOP, 0, in, el);
      if (s == NLS_STATUS_OK) s = detail::strict_check(in, el);
      if (s != NLS_STATUS_OK) return this->fail(s, el, 1);
    }
    s = nlsubdiv::flat::run_differential(o, in, out, el, rep_);
    if (s != NLS_STATUS_OK) return this->fail(s, el, static_cast<uint32_t>(n));
    if (out.vertex_count() < in.vertex_count()) return this->fail(NLS_STATUS_INVALID_ARGUMENT, NLS_NO_ELEMENT, 0);
    mesh_t backup = m;
    if (!detail::rebuild(m, out)) {
      m = backup;
      return this->fail(NLS_STATUS_NON_MANIFOLD_EDGE, NLS_NO_ELEMENT, static_cast<uint32_t>(n));
    }
    // The output has the faces of spatial Loop (both stencils split 1-to-4).
    detail::inherit_properties(m, backup, NLS_SCHEME_LOOP, in, static_cast<uint32_t>(n));
    return true;
  }

 private:
  nls_differential_options opt_{};
  uint32_t stencil_ = NLS_DIFFERENTIAL_LOOP;
  uint32_t dirmag_levels_ = 1;
  nls_differential_report rep_{};
  OpenMesh::VPropHandleT<double> curvature_;
  OpenMesh::VPropHandleT<OpenMesh::Vec3d> normals_;
};

/// The three stencils as their own types (same options and report as DifferentialT).
template <typename M> struct DifferentialLoopT : DifferentialT<M> {
  DifferentialLoopT() : DifferentialT<M>(NLS_DIFFERENTIAL_LOOP) {}
  explicit DifferentialLoopT(M& m) : DifferentialT<M>(NLS_DIFFERENTIAL_LOOP) { this->attach(m); }
};
template <typename M> struct DifferentialButterflyT : DifferentialT<M> {
  DifferentialButterflyT() : DifferentialT<M>(NLS_DIFFERENTIAL_BUTTERFLY) {}
  explicit DifferentialButterflyT(M& m) : DifferentialT<M>(NLS_DIFFERENTIAL_BUTTERFLY) { this->attach(m); }
};
template <typename M> struct DifferentialDirMagT : DifferentialT<M> {
  DifferentialDirMagT() : DifferentialT<M>(NLS_DIFFERENTIAL_DIRMAG) {}
  explicit DifferentialDirMagT(M& m) : DifferentialT<M>(NLS_DIFFERENTIAL_DIRMAG) { this->attach(m); }
};

// ---------------------------------------------------------------------------------------
// Tier 1: Möbius Loop and Catmull–Clark from the star rules, with OpenMesh's connectivity.
// ---------------------------------------------------------------------------------------

/// Shared machinery of the tier-1 classes: one level per call of `level()`, the driver's
/// spoke starts and half-edge orientation, the boundary curve rules and the fallbacks.
template <typename MeshType, uint32_t Scheme, typename RealType = double>
class StarSubdividerT : public SubdividerBaseT<MeshType, RealType> {
 public:
  typedef SubdividerBaseT<MeshType, RealType> base_t;
  typedef MeshType mesh_t;
  typedef typename MeshType::VertexHandle VH;
  typedef typename MeshType::HalfedgeHandle HH;
  typedef typename MeshType::FaceHandle FH;
  using P3 = detail::P3;

  StarSubdividerT() = default;
  /// OpenMesh's interface 1: attached to `m`, then `sd(n)`.
  explicit StarSubdividerT(mesh_t& m) { this->attach(m); }
  ~StarSubdividerT() override { this->detach(); }

  const char* name() const override {
    return Scheme == NLS_SCHEME_LOOP                ? "Uniform nlsubdiv Moebius Loop (star rules)"
           : Scheme == NLS_SCHEME_MODIFIED_BUTTERFLY ? "Uniform nlsubdiv Moebius Modified Butterfly (star rules)"
                                                     : "Uniform nlsubdiv Moebius Catmull-Clark (star rules)";
  }

 protected:
  bool subdivide(mesh_t& m, size_t n, const bool update_points = true) override {
    this->reset();
    if (n == 0) return true;
    mesh_t backup = m;  // levels after the first can still fail (strict mode, overflow)
    for (std::size_t k = 0; k < n; ++k) {
      if (!level(m, update_points, static_cast<uint32_t>(k + 1))) {
        if (k > 0) m = backup;
        return false;
      }
    }
    return true;
  }

 private:
  // Per level: the flat copy, the position of every half-edge's corner, candidates.
  FlatMesh flat_;
  std::vector<uint32_t> corner_of_;  // half-edge idx -> corner index in flat_ (faces only)
  std::vector<P3> pos_;              // current positions by vertex idx
  std::vector<P3> edge_c_, face_c_;  // per half-edge candidates (NaN: none)
  std::vector<P3> new_;              // output positions in the driver's order
  std::vector<uint32_t> edge_rank_;  // OpenMesh edge idx -> driver edge index
  uint32_t level_ = 0;
  bool failed_ = false;
  bool need_driver_ = false;  // Butterfly: an element needs the linear fallback (2-ring rule)

  P3 pos(VH v) const { return pos_[static_cast<std::size_t>(v.idx())]; }

  /// Counts a fallback at output vertex `k`, or fails in strict mode.
  bool fallback(std::size_t k) {
    if (this->strict_) {
      failed_ = true;
      this->fail(NLS_STATUS_FALLBACK_IN_STRICT_MODE, static_cast<uint32_t>(k), level_);
      return false;
    }
    ++this->out_.fallbacks;
    return true;
  }

  /// Butterfly: a fallback is an error in strict mode, else the level comes from the driver.
  bool driver_fallback(std::size_t k) {
    if (this->strict_) {
      failed_ = true;
      this->fail(NLS_STATUS_FALLBACK_IN_STRICT_MODE, static_cast<uint32_t>(k), level_);
      return false;
    }
    need_driver_ = true;
    return true;
  }

  /// The driver's star of v: spokes counter-clockwise from the outgoing half-edge with the
  /// lowest corner index (interior) or from the face-side outgoing boundary half-edge
  /// (boundary; the last spoke is then the incoming boundary half-edge `in`, reported with
  /// an invalid half-edge in `spokes`).
  void star(const mesh_t& m, VH v, std::vector<HH>& spokes, std::vector<VH>& ring, HH& in) const {
    spokes.clear();
    ring.clear();
    in = HH();
    HH h0;
    uint32_t best = UINT32_MAX;
    for (auto h : m.voh_range(v)) {
      if (m.is_boundary(h)) continue;
      if (m.is_boundary(m.opposite_halfedge_handle(h))) {
        h0 = h;
        best = 0;
        break;
      }
      uint32_t c = corner_of_[static_cast<std::size_t>(h.idx())];
      if (c < best) {
        best = c;
        h0 = h;
      }
    }
    if (!h0.is_valid()) return;
    HH h = h0;
    std::size_t guard = 0;
    do {
      spokes.push_back(h);
      ring.push_back(m.to_vertex_handle(h));
      HH p = m.prev_halfedge_handle(h);
      HH o = m.opposite_halfedge_handle(p);
      if (m.is_boundary(o)) {  // closing spoke of a boundary star: p = b1 -> v
        in = p;
        spokes.push_back(HH());
        ring.push_back(m.from_vertex_handle(p));
        break;
      }
      h = o;
    } while (h != h0 && ++guard < 4096);
  }

  std::size_t face_count_at(const mesh_t& m, VH v) const {
    std::size_t k = 0;
    for (auto f : m.vf_range(v)) {
      (void)f;
      ++k;
    }
    return k;
  }
  bool is_ear(const mesh_t& m, VH v) const { return m.is_boundary(v) && face_count_at(m, v) == 1; }

  std::vector<P3> face_points(FH f) const {
    std::vector<P3> pts;
    const uint32_t a = flat_.offsets[static_cast<std::size_t>(f.idx())], b = flat_.offsets[static_cast<std::size_t>(f.idx()) + 1];
    for (uint32_t c = a; c < b; ++c) pts.push_back(pos_[flat_.indices[c]]);
    return pts;
  }
  /// The half-edge of face f starting at corner i (flat order).
  HH corner_halfedge(const mesh_t& m, FH f, std::size_t i) const {
    HH h = m.halfedge_handle(f);
    for (std::size_t k = 0; k < i; ++k) h = m.next_halfedge_handle(h);
    return h;
  }

  // ---- one level ----
  bool level(mesh_t& m, bool update_points, uint32_t lvl) {
    level_ = lvl;
    failed_ = false;
    nls_status s = detail::export_flat(m, flat_);
    if (s != NLS_STATUS_OK) return this->fail(s, NLS_NO_ELEMENT, lvl);
    uint32_t element = NLS_NO_ELEMENT;
    const uint32_t flags = NLS_SUBDIVIDE_MOBIUS | (this->strict_ ? NLS_SUBDIVIDE_STRICT : 0u);
    s = detail::validate(Scheme, flags, flat_, element);
    if (s == NLS_STATUS_OK && this->strict_ && lvl == 1) s = detail::strict_check(flat_, element);
    if (s != NLS_STATUS_OK) return this->fail(s, element, lvl);

    const std::size_t nv = m.n_vertices(), ne = m.n_edges(), nf = m.n_faces(), nh = m.n_halfedges();
    pos_.resize(nv);
    for (std::size_t i = 0; i < nv; ++i) pos_[i] = detail::point(m, m.vertex_handle(static_cast<int>(i)));
    corner_of_.assign(nh, UINT32_MAX);
    for (auto f : m.faces()) {
      HH h = m.halfedge_handle(f);
      for (uint32_t c = flat_.offsets[static_cast<std::size_t>(f.idx())]; c < flat_.offsets[static_cast<std::size_t>(f.idx()) + 1]; ++c) {
        corner_of_[static_cast<std::size_t>(h.idx())] = c;
        h = m.next_halfedge_handle(h);
      }
    }
    // Driver edge numbering: ascending (min, max) vertex pair.
    std::vector<std::pair<uint64_t, uint32_t>> keys;
    keys.reserve(ne);
    for (auto e : m.edges()) {
      auto h = m.halfedge_handle(e, 0);
      uint64_t a = static_cast<uint64_t>(m.from_vertex_handle(h).idx()), b = static_cast<uint64_t>(m.to_vertex_handle(h).idx());
      keys.emplace_back((std::min(a, b) << 32) | std::max(a, b), static_cast<uint32_t>(e.idx()));
    }
    std::sort(keys.begin(), keys.end());
    edge_rank_.assign(ne, 0);
    for (std::size_t r = 0; r < keys.size(); ++r) edge_rank_[keys[r].second] = static_cast<uint32_t>(r);

    edge_c_.assign(nh, detail::nan3());
    face_c_.assign(nh, detail::nan3());
    const std::size_t nout = nv + ne + (Scheme == NLS_SCHEME_CATMULL_CLARK ? nf : 0);
    new_.assign(nout, detail::nan3());

    need_driver_ = false;
    if (!vertex_pass(m)) return false;
    if (Scheme == NLS_SCHEME_CATMULL_CLARK && !faces_pass(m, nv + ne)) return false;
    if (!edges_pass(m, nv)) return false;
    if (Scheme != NLS_SCHEME_MODIFIED_BUTTERFLY && !boundary_vertices(m, nv)) return false;
    if (need_driver_) {
      // Butterfly's linear fallback reads the 2-ring (Zorin / OpenMesh stencils): this level
      // is taken from the driver on the same flat copy instead (same layout, same values
      // elsewhere, the fallbacks counted by its report).
      FlatMesh out;
      uint32_t el = NLS_NO_ELEMENT, fb = 0;
      s = nlsubdiv::flat::run_levels(Scheme, flags, flat_, 1, out, el, fb);
      if (s != NLS_STATUS_OK) return this->fail(s, el, lvl);
      if (out.vertex_count() != new_.size()) return this->fail(NLS_STATUS_INVALID_ARGUMENT, NLS_NO_ELEMENT, lvl);
      for (std::size_t k = 0; k < new_.size(); ++k) new_[k] = {out.positions[3 * k], out.positions[3 * k + 1], out.positions[3 * k + 2]};
      this->out_.fallbacks += fb;
    }
    if (!update_points)
      for (std::size_t i = 0; i < nv; ++i) new_[i] = pos_[i];
    for (std::size_t k = 0; k < new_.size(); ++k)
      if (!detail::finite3(new_[k])) return this->fail(NLS_STATUS_NUMERICAL_FAILURE, static_cast<uint32_t>(k), lvl);

    // The driver's connectivity (patterns 1->4 and quads), then the rebuild.
    FlatMesh out;
    out.positions.reserve(3 * nout);
    for (const P3& p : new_) out.positions.insert(out.positions.end(), p.begin(), p.end());
    out.offsets.assign(1, 0);
    auto E = [&](HH h) { return static_cast<uint32_t>(nv + edge_rank_[static_cast<std::size_t>(m.edge_handle(h).idx())]); };
    for (auto f : m.faces()) {
      if (Scheme != NLS_SCHEME_CATMULL_CLARK) {
        HH h0 = m.halfedge_handle(f), h1 = m.next_halfedge_handle(h0), h2 = m.next_halfedge_handle(h1);
        uint32_t v0 = static_cast<uint32_t>(m.from_vertex_handle(h0).idx()), v1 = static_cast<uint32_t>(m.from_vertex_handle(h1).idx()),
                 v2 = static_cast<uint32_t>(m.from_vertex_handle(h2).idx());
        uint32_t e0 = E(h0), e1 = E(h1), e2 = E(h2);
        const uint32_t tris[4][3] = {{v0, e0, e2}, {v1, e1, e0}, {v2, e2, e1}, {e0, e1, e2}};
        for (const auto& t : tris) {
          out.indices.insert(out.indices.end(), t, t + 3);
          out.offsets.push_back(static_cast<uint32_t>(out.indices.size()));
        }
      } else {
        const uint32_t fp = static_cast<uint32_t>(nv + ne + static_cast<std::size_t>(f.idx()));
        HH h0 = m.halfedge_handle(f), h = h0;
        do {
          const uint32_t q[4] = {static_cast<uint32_t>(m.from_vertex_handle(h).idx()), E(h), fp, E(m.prev_halfedge_handle(h))};
          out.indices.insert(out.indices.end(), q, q + 4);
          out.offsets.push_back(static_cast<uint32_t>(out.indices.size()));
          h = m.next_halfedge_handle(h);
        } while (h != h0);
      }
    }
    mesh_t backup = m;
    if (!detail::rebuild(m, out)) {
      m = backup;
      return this->fail(NLS_STATUS_NON_MANIFOLD_EDGE, NLS_NO_ELEMENT, lvl);
    }
    detail::inherit_properties(m, backup, Scheme, flat_, 1);
    return true;
  }

  /// Star rules at every non-isolated, non-ear vertex (the driver gives ears no form), then
  /// the interior vertex points.
  bool vertex_pass(const mesh_t& m) {
    std::vector<HH> spokes;
    std::vector<VH> ring;
    std::vector<double> ring_xyz, corners, ec, fc;
    std::vector<uint32_t> offs, irregular;
    HH in;
    for (auto v : m.vertices()) {
      const std::size_t vi = static_cast<std::size_t>(v.idx());
      star(m, v, spokes, ring, in);
      if (spokes.empty()) {  // isolated: carried through
        new_[vi] = pos_[vi];
        continue;
      }
      const bool boundary = in.is_valid();
      const std::size_t n = ring.size();
      P3 vp = detail::nan3();
      if (!is_ear(m, v)) {
        ring_xyz.clear();
        for (VH u : ring) {
          P3 p = pos(u);
          ring_xyz.insert(ring_xyz.end(), p.begin(), p.end());
        }
        ec.assign(3 * n, NAN);
        nls_status s;
        const P3 pv = pos_[vi];
        if (Scheme == NLS_SCHEME_LOOP) {
          const nls_star_view star = flat::star_of(pv.data(), ring_xyz.data(), n, !boundary);
          s = nls_mobius_loop_star(&star, vp.data(), ec.data());
        } else if (Scheme == NLS_SCHEME_MODIFIED_BUTTERFLY) {
          irregular.assign(n, 0);
          for (std::size_t j = 0; j < n; ++j)
            irregular[j] = (!m.is_boundary(ring[j]) && m.valence(ring[j]) != 6) ? 1u : 0u;
          const nls_star_view star = flat::star_of(pv.data(), ring_xyz.data(), n, !boundary);
          s = nls_mobius_butterfly_star(&star, irregular.data(), ec.data());
        } else {
          const std::size_t nfs = boundary ? n - 1 : n;
          offs.assign(1, 0);
          corners.clear();
          for (std::size_t j = 0; j < nfs; ++j) {
            for (const P3& p : face_points(m.face_handle(spokes[j]))) corners.insert(corners.end(), p.begin(), p.end());
            offs.push_back(static_cast<uint32_t>(corners.size() / 3));
          }
          fc.assign(3 * nfs, NAN);
          const nls_star_view star =
              flat::star_of(pv.data(), ring_xyz.data(), n, !boundary, offs.data(), nfs, corners.data(), corners.size() / 3);
          s = nls_mobius_catmull_clark_star(&star, vp.data(), ec.data(), fc.data());
          if (s == NLS_STATUS_OK)
            for (std::size_t j = 0; j < nfs; ++j) face_c_[static_cast<std::size_t>(spokes[j].idx())] = {fc[3 * j], fc[3 * j + 1], fc[3 * j + 2]};
        }
        if (s == NLS_STATUS_OK) {
          for (std::size_t j = 0; j < n; ++j)
            if (spokes[j].is_valid()) edge_c_[static_cast<std::size_t>(spokes[j].idx())] = {ec[3 * j], ec[3 * j + 1], ec[3 * j + 2]};
        } else {
          vp = detail::nan3();
        }
      }
      if (Scheme == NLS_SCHEME_MODIFIED_BUTTERFLY) {  // interpolating
        new_[vi] = pos_[vi];
        continue;
      }
      if (!boundary) {
        if (!detail::finite3(vp)) {
          if (!fallback(vi)) return false;
          std::vector<P3> rp;
          for (VH u : ring) rp.push_back(pos(u));
          if (Scheme == NLS_SCHEME_LOOP) {
            double a = 0.375;
            if (n != 6) {
              double c = 0.375 + 0.25 * std::cos(2.0 * 3.14159265358979323846 / static_cast<double>(n));
              a = 0.625 - c * c;
            }
            vp = detail::lin2(1.0 - a, pos_[vi], a / static_cast<double>(n), detail::sum(rp));
          } else {
            std::vector<P3> fcs;
            for (HH h : spokes) fcs.push_back(detail::centroid(face_points(m.face_handle(h))));
            const double nf = static_cast<double>(n);
            vp = detail::lin2((nf - 2.0) / nf, pos_[vi], 1.0 / (nf * nf), detail::add(detail::sum(rp), detail::sum(fcs)));
          }
        }
        new_[vi] = vp;
      }
    }
    return true;
  }

  /// Catmull–Clark face points: ears borrow the face candidate of the first non-ear corner at
  /// offset h, h+1, h-1, h+2, ... (h = d/2), as the driver does; then nls_face_point_with_ids
  /// with OpenMesh's vertex indices (the driver's tie-break, independent of the face start).
  bool faces_pass(const mesh_t& m, std::size_t start) {
    for (auto f : m.faces()) {
      const std::vector<P3> verts = face_points(f);
      const std::size_t d = verts.size();
      std::vector<HH> hs;
      for (std::size_t i = 0; i < d; ++i) hs.push_back(corner_halfedge(m, f, i));
      std::vector<double> vx, cx;
      std::vector<uint32_t> ids;
      bool all = true;
      for (std::size_t i = 0; i < d; ++i) {
        ids.push_back(static_cast<uint32_t>(m.from_vertex_handle(hs[i]).idx()));
        P3 c = face_c_[static_cast<std::size_t>(hs[i].idx())];
        if (is_ear(m, m.from_vertex_handle(hs[i]))) {
          c = detail::nan3();
          const std::size_t h = d / 2;
          for (std::size_t k = 0; k < d; ++k) {
            const std::size_t step = (k + 1) / 2;
            const std::size_t off = (k % 2 == 1) ? h + step : h + d - step;
            const std::size_t j = (i + off) % d;
            if (!is_ear(m, m.from_vertex_handle(hs[j]))) {
              c = face_c_[static_cast<std::size_t>(hs[j].idx())];
              break;
            }
          }
        }
        all = all && detail::finite3(c);
        vx.insert(vx.end(), verts[i].begin(), verts[i].end());
        cx.insert(cx.end(), c.begin(), c.end());
      }
      P3 p = detail::nan3();
      const std::size_t k = start + static_cast<std::size_t>(f.idx());
      if (!(all && nls_face_point_with_ids(vx.data(), cx.data(), ids.data(), d, p.data()) == NLS_STATUS_OK)) {
        if (!fallback(k)) return false;
        p = detail::centroid(verts);
      }
      new_[k] = p;
    }
    return true;
  }

  /// Interior edges: F4(a, e_a, e_b, b) with the hint of the face on the left of a -> b
  /// (a the smaller index); boundary edges: the Möbius curve rule F4(P_{i-1}, P_i, P_{i+1},
  /// P_{i+2}).
  bool edges_pass(const mesh_t& m, std::size_t start) {
    for (auto e : m.edges()) {
      const std::size_t k = start + edge_rank_[static_cast<std::size_t>(e.idx())];
      HH h = m.halfedge_handle(e, 0);
      if (m.is_boundary(e)) {
        if (m.is_boundary(h)) h = m.opposite_halfedge_handle(h);  // face side, a -> b
        HH hb = m.opposite_halfedge_handle(h);
        const P3 p0 = pos(m.to_vertex_handle(m.next_halfedge_handle(hb))), a = pos(m.from_vertex_handle(h)),
                 b = pos(m.to_vertex_handle(h)), p3 = pos(m.from_vertex_handle(m.prev_halfedge_handle(hb)));
        P3 q;
        if (nls_f4(p0.data(), a.data(), b.data(), p3.data(), q.data()) != NLS_STATUS_OK) {
          if (Scheme == NLS_SCHEME_MODIFIED_BUTTERFLY) {
            if (!driver_fallback(k)) return false;
            continue;
          }
          if (!fallback(k)) return false;
          q = detail::midpoint(a, b);
        }
        new_[k] = q;
        continue;
      }
      if (m.from_vertex_handle(h).idx() > m.to_vertex_handle(h).idx()) h = m.opposite_halfedge_handle(h);
      HH t = m.opposite_halfedge_handle(h);
      const P3 a = pos(m.from_vertex_handle(h)), b = pos(m.to_vertex_handle(h));
      const P3 ca = edge_c_[static_cast<std::size_t>(h.idx())], cb = edge_c_[static_cast<std::size_t>(t.idx())];
      const P3 hint = pos(m.to_vertex_handle(m.next_halfedge_handle(h)));
      P3 q = detail::nan3();
      bool have = false;
      if (detail::finite3(ca) && detail::finite3(cb)) {
        have = nls_f4_hinted(a.data(), ca.data(), cb.data(), b.data(), hint.data(), q.data()) == NLS_STATUS_OK;
      } else if (detail::finite3(ca)) {
        q = ca;
        have = true;
      } else if (detail::finite3(cb)) {
        q = cb;
        have = true;
      }
      if (!(have && detail::finite3(q))) {
        if (Scheme == NLS_SCHEME_MODIFIED_BUTTERFLY) {
          if (!driver_fallback(k)) return false;
          continue;
        }
        if (!fallback(k)) return false;
        if (Scheme == NLS_SCHEME_LOOP) {
          const P3 c = pos(m.to_vertex_handle(m.next_halfedge_handle(h))), d = pos(m.to_vertex_handle(m.next_halfedge_handle(t)));
          q = detail::add(detail::scale(detail::add(a, b), 0.375), detail::scale(detail::add(c, d), 0.125));
        } else {
          const P3 f0 = detail::centroid(face_points(m.face_handle(h))), f1 = detail::centroid(face_points(m.face_handle(t)));
          q = detail::scale(detail::add(detail::add(a, b), detail::add(f0, f1)), 0.25);
        }
      }
      new_[k] = q;
    }
    return true;
  }

  /// Boundary vertices: the Möbius approximating curve rule F4(P_{i-1}, E_{i-1/2}, E_{i+1/2},
  /// P_{i+1}); fallback the crease rule.
  bool boundary_vertices(const mesh_t& m, std::size_t start) {
    std::vector<HH> spokes;
    std::vector<VH> ring;
    HH in;
    for (auto v : m.vertices()) {
      if (!m.is_boundary(v)) continue;
      star(m, v, spokes, ring, in);
      if (spokes.empty() || !in.is_valid()) continue;
      const std::size_t vi = static_cast<std::size_t>(v.idx());
      HH out_h = spokes.front();
      const P3 b0 = pos(m.to_vertex_handle(out_h)), b1 = pos(m.from_vertex_handle(in));
      const P3 e_out = new_[start + edge_rank_[static_cast<std::size_t>(m.edge_handle(out_h).idx())]];
      const P3 e_in = new_[start + edge_rank_[static_cast<std::size_t>(m.edge_handle(in).idx())]];
      P3 q;
      if (nls_f4(b1.data(), e_in.data(), e_out.data(), b0.data(), q.data()) != NLS_STATUS_OK) {
        if (!fallback(vi)) return false;
        q = detail::crease(pos_[vi], b0, b1);
      }
      new_[vi] = q;
    }
    return true;
  }
};

/// Möbius Loop from the tier-1 star rules (triangle meshes; a PolyMesh of triangles works too).
template <typename M> using MobiusLoopT = StarSubdividerT<M, NLS_SCHEME_LOOP>;
/// Möbius Modified Butterfly from the tier-1 star rules (nls_mobius_butterfly_star; triangles).
/// An element that needs the linear fallback (a 2-ring stencil) makes the level come from
/// the driver on the same mesh (same result; strict mode: an error).
template <typename M> using MobiusButterflyT = StarSubdividerT<M, NLS_SCHEME_MODIFIED_BUTTERFLY>;
/// Möbius Catmull–Clark from the tier-1 star rules (any polygon mesh; output quads, so use a
/// PolyMesh).
template <typename M> using MobiusCatmullClarkT = StarSubdividerT<M, NLS_SCHEME_CATMULL_CLARK>;

}  // namespace openmesh
}  // namespace nlsubdiv

#endif  // NLSUBDIV_OPENMESH_HH
