// OpenMesh 9.0 backend of peer_subdivide.
//
// Traps avoided (aesthetics-anchors.md 1.6, reliability-anchors.md):
// * never use the SubdividerT(mesh&) constructor (its attach() calls the pure
//   prepare() from the base constructor: "pure virtual method called"), and
//   always detach() before the subdivider is destroyed (~SubdividerT calls
//   the pure cleanup() otherwise). We use attach() / op()(n) / detach().
// * add_face aborts on repeated-vertex and 2-vertex faces and on closing
//   fans: the caller has validated the face list as an oriented 2-manifold;
//   every add_face result is still checked.
// * LoopT and Sqrt3T precompute weights for valence < 50 and index past the
//   table above that: we size the table with their public init_weights().
#include "peer_common.hpp"

#include <OpenMesh/Core/Mesh/PolyMesh_ArrayKernelT.hh>
#include <OpenMesh/Core/Mesh/TriMesh_ArrayKernelT.hh>
#include <OpenMesh/Tools/Subdivider/Uniform/CatmullClarkT.hh>
#include <OpenMesh/Tools/Subdivider/Uniform/LoopT.hh>
#include <OpenMesh/Tools/Subdivider/Uniform/ModifiedButterFlyT.hh>
#include <OpenMesh/Tools/Subdivider/Uniform/Sqrt3T.hh>

#include <algorithm>
#include <string>
#include <vector>

namespace peer {
namespace {

using OMTri = OpenMesh::TriMesh_ArrayKernelT<OpenMesh::DefaultTraitsDouble>;
using OMPoly = OpenMesh::PolyMesh_ArrayKernelT<OpenMesh::DefaultTraitsDouble>;
static_assert(std::is_same<OMTri::Point, OpenMesh::Vec3d>::value, "double points expected");

template <class M>
Outcome build(const Mesh& in, M& om) {
  std::vector<typename M::VertexHandle> vh;
  vh.reserve(in.nv());
  for (std::size_t v = 0; v < in.nv(); ++v)
    vh.push_back(om.add_vertex(typename M::Point(in.xyz[3 * v], in.xyz[3 * v + 1], in.xyz[3 * v + 2])));
  std::vector<typename M::VertexHandle> fv;
  std::size_t s = 0;
  for (std::size_t f = 0; f < in.nf(); ++f) {
    fv.clear();
    for (int k = 0; k < in.fsize[f]; ++k) fv.push_back(vh[std::size_t(in.fidx[s + std::size_t(k)])]);
    s += std::size_t(in.fsize[f]);
    typename M::FaceHandle fh = om.add_face(fv);
    if (!fh.is_valid())
      return Outcome::reject("OpenMesh add_face refused face " + std::to_string(f));
  }
  if (om.n_faces() != in.nf()) return Outcome::reject("OpenMesh face count mismatch after build");
  return Outcome::ok();
}

template <class M>
void extract(const M& om, Mesh& out) {
  out.clear();
  // ArrayKernel without deletions: handles are 0..n-1 in creation order.
  out.xyz.reserve(om.n_vertices() * 3);
  for (auto v : om.vertices()) {
    const auto& p = om.point(v);
    out.add_vertex(p[0], p[1], p[2]);
  }
  for (auto f : om.faces()) {
    // walk next-halfedges: the face's own orientation, as given at add_face
    auto h0 = om.halfedge_handle(f);
    auto h = h0;
    int n = 0;
    do {
      out.fidx.push_back(om.from_vertex_handle(h).idx());
      ++n;
      h = om.next_halfedge_handle(h);
    } while (h != h0 && n <= 1000000);
    out.fsize.push_back(n);
  }
}

template <class M>
std::size_t max_valence(const M& om) {
  std::size_t mv = 0;
  for (auto v : om.vertices()) mv = std::max<std::size_t>(mv, om.valence(v));
  return mv;
}

// attach / op()(n) / detach, detach also on the failure path.
template <class Sub, class M>
Outcome apply(Sub& sd, M& om, int levels, const char* what) {
  if (!sd.attach(om)) return Outcome::reject(std::string(what) + ": attach() failed");
  bool ok = sd(std::size_t(levels));
  sd.detach();
  if (!ok) return Outcome::reject(std::string(what) + ": subdivide() returned false");
  return Outcome::ok();
}

}  // namespace

Outcome run_openmesh(Scheme s, int levels, const Mesh& in, Mesh& out) {
  namespace U = OpenMesh::Subdivider::Uniform;
  if (s == Scheme::CatmullClark) {
    OMPoly om;
    Outcome o = build(in, om);
    if (o.status) return o;
    if (levels > 0) {
      U::CatmullClarkT<OMPoly> sd;
      o = apply(sd, om, levels, "CatmullClarkT");
      if (o.status) return o;
    }
    extract(om, out);
    return Outcome::ok();
  }
  OMTri om;
  Outcome o = build(in, om);
  if (o.status) return o;
  if (levels > 0) {
    // Old vertices keep their valence; new ones have valence <= 6 (Loop,
    // butterfly) or <= 2n+2 around √3 boundaries; size tables generously.
    const std::size_t table = std::max<std::size_t>(50, 2 * max_valence(om) + 8);
    switch (s) {
      case Scheme::Loop: {
        U::LoopT<OMTri> sd;
        sd.init_weights(table);
        o = apply(sd, om, levels, "LoopT");
        break;
      }
      case Scheme::Butterfly: {
        U::ModifiedButterflyT<OMTri> sd;  // grows its own table (max valence >= 30)
        o = apply(sd, om, levels, "ModifiedButterflyT");
        break;
      }
      case Scheme::Sqrt3: {
        U::Sqrt3T<OMTri> sd;
        sd.init_weights(table);
        o = apply(sd, om, levels, "Sqrt3T");
        break;
      }
      default:
        return Outcome::reject("internal: scheme not available in OpenMesh");
    }
    if (o.status) return o;
  }
  extract(om, out);
  return Outcome::ok();
}

}  // namespace peer
