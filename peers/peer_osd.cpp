// OpenSubdiv 3.5 backend of peer_subdivide: Far::TopologyRefiner uniform
// refinement (SCHEME_LOOP / SCHEME_CATMARK, VTX_BOUNDARY_EDGE_ONLY, default
// TRI_SUB_CATMARK and CREASE_UNIFORM, no creases), positions interpolated level
// by level with Far::PrimvarRefinerReal<double> (the float PrimvarRefiner
// would round the weights).
#include "peer_common.hpp"

#include <opensubdiv/far/error.h>
#include <opensubdiv/far/primvarRefiner.h>
#include <opensubdiv/far/topologyDescriptor.h>
#include <opensubdiv/far/topologyRefinerFactory.h>

#include <memory>
#include <string>
#include <vector>

namespace peer {
namespace {

using namespace OpenSubdiv;

struct V3 {
  double p[3];
  void Clear(void* = nullptr) { p[0] = p[1] = p[2] = 0.0; }
  void AddWithWeight(const V3& s, double w) {
    p[0] += w * s.p[0];
    p[1] += w * s.p[1];
    p[2] += w * s.p[2];
  }
};

std::string g_osd_error;

void on_error(Far::ErrorType, const char* msg) {
  if (!g_osd_error.empty()) g_osd_error += "; ";
  g_osd_error += msg ? msg : "(null)";
}

}  // namespace

Outcome run_osd(Scheme s, int levels, const Mesh& in, Mesh& out) {
  Sdc::SchemeType type;
  if (s == Scheme::Loop) type = Sdc::SCHEME_LOOP;
  else if (s == Scheme::CatmullClark) type = Sdc::SCHEME_CATMARK;
  else return Outcome::reject("internal: scheme not available in OpenSubdiv");

  Sdc::Options sdc;
  sdc.SetVtxBoundaryInterpolation(Sdc::Options::VTX_BOUNDARY_EDGE_ONLY);

  Far::TopologyDescriptor desc;
  desc.numVertices = int(in.nv());
  desc.numFaces = int(in.nf());
  desc.numVertsPerFace = in.fsize.data();
  desc.vertIndicesPerFace = in.fidx.data();

  using Factory = Far::TopologyRefinerFactory<Far::TopologyDescriptor>;
  g_osd_error.clear();
  Far::SetErrorCallback(on_error);
  std::unique_ptr<Far::TopologyRefiner> refiner(
      Factory::Create(desc, Factory::Options(type, sdc)));
  if (!refiner)
    return Outcome::reject("OpenSubdiv TopologyRefinerFactory::Create failed: " + g_osd_error);

  if (levels > 0) {
    Far::TopologyRefiner::UniformOptions uo(levels);
    uo.fullTopologyInLastLevel = true;
    refiner->RefineUniform(uo);
    if (refiner->GetMaxLevel() != levels)
      return Outcome::reject("OpenSubdiv RefineUniform stopped early: " + g_osd_error);
  }
  if (!g_osd_error.empty()) return Outcome::reject("OpenSubdiv error: " + g_osd_error);

  std::vector<V3> verts(std::size_t(refiner->GetNumVerticesTotal()));
  for (std::size_t v = 0; v < in.nv(); ++v)
    for (int c = 0; c < 3; ++c) verts[v].p[c] = in.xyz[3 * v + std::size_t(c)];
  Far::PrimvarRefinerReal<double> primvar(*refiner);
  V3* src = verts.data();
  for (int l = 1; l <= levels; ++l) {
    V3* dst = src + refiner->GetLevel(l - 1).GetNumVertices();
    primvar.Interpolate(l, src, dst);
    src = dst;
  }

  const Far::TopologyLevel& last = refiner->GetLevel(levels);
  out.clear();
  out.xyz.reserve(std::size_t(last.GetNumVertices()) * 3);
  for (int v = 0; v < last.GetNumVertices(); ++v) out.add_vertex(src[v].p[0], src[v].p[1], src[v].p[2]);
  for (int f = 0; f < last.GetNumFaces(); ++f) {
    Far::ConstIndexArray fv = last.GetFaceVertices(f);
    out.fsize.push_back(fv.size());
    for (int j = 0; j < fv.size(); ++j) out.fidx.push_back(fv[j]);
  }
  return Outcome::ok();
}

}  // namespace peer
