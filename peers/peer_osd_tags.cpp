// peer_osd_tags: OpenSubdiv 3.5 uniform refinement of a mesh with sharp-feature tags, the
// reference of tests/crease_peer.rs (which builds this file with g++ and runs it).
//
//   peer_osd_tags < input > output
//
// Input, one item per line:
//   scheme loop|catmark      levels N      method uniform|chaikin
//   v x y z                  f n i0 .. i(n-1)
//   crease a b sharpness     corner v sharpness
// Output: "nv nf" of the last level, then its nv positions "x y z" (%.17g).
//
// Sdc options: VTX_BOUNDARY_EDGE_ONLY (every boundary a crease, as nlsubdiv), the given
// creasing method, default TRI_SUB_CATMARK. Positions are interpolated level by level with
// Far::PrimvarRefinerReal<double> (the float PrimvarRefiner would round the weights).
// Sharpness values are handed to OpenSubdiv as float, its own precision.
#include <opensubdiv/far/error.h>
#include <opensubdiv/far/primvarRefiner.h>
#include <opensubdiv/far/topologyDescriptor.h>
#include <opensubdiv/far/topologyRefinerFactory.h>

#include <cstdio>
#include <iostream>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

using namespace OpenSubdiv;

namespace {

struct V3 {
  double p[3];
  void Clear(void* = nullptr) { p[0] = p[1] = p[2] = 0.0; }
  void AddWithWeight(const V3& s, double w) {
    p[0] += w * s.p[0];
    p[1] += w * s.p[1];
    p[2] += w * s.p[2];
  }
};

std::string g_error;
void on_error(Far::ErrorType, const char* msg) {
  g_error += msg ? msg : "(null)";
  g_error += "; ";
}

int fail(const std::string& m) {
  std::cerr << "peer_osd_tags: " << m << "\n";
  return 2;
}

}  // namespace

int main() {
  std::string scheme = "catmark", method = "uniform";
  int levels = 1;
  std::vector<double> xyz;
  std::vector<int> fsize, fidx, creases, corners;
  std::vector<float> crease_w, corner_w;
  std::string line;
  while (std::getline(std::cin, line)) {
    std::istringstream in(line);
    std::string key;
    if (!(in >> key)) continue;
    if (key == "scheme") in >> scheme;
    else if (key == "levels") in >> levels;
    else if (key == "method") in >> method;
    else if (key == "v") {
      double x, y, z;
      if (!(in >> x >> y >> z)) return fail("bad vertex: " + line);
      xyz.insert(xyz.end(), {x, y, z});
    } else if (key == "f") {
      int n;
      if (!(in >> n) || n < 3) return fail("bad face: " + line);
      fsize.push_back(n);
      for (int i = 0; i < n; ++i) {
        int v;
        if (!(in >> v)) return fail("bad face: " + line);
        fidx.push_back(v);
      }
    } else if (key == "crease") {
      int a, b;
      double s;
      if (!(in >> a >> b >> s)) return fail("bad crease: " + line);
      creases.insert(creases.end(), {a, b});
      crease_w.push_back(float(s));
    } else if (key == "corner") {
      int v;
      double s;
      if (!(in >> v >> s)) return fail("bad corner: " + line);
      corners.push_back(v);
      corner_w.push_back(float(s));
    } else {
      return fail("unknown line: " + line);
    }
  }
  Sdc::SchemeType type;
  if (scheme == "loop") type = Sdc::SCHEME_LOOP;
  else if (scheme == "catmark") type = Sdc::SCHEME_CATMARK;
  else return fail("unknown scheme " + scheme);
  Sdc::Options sdc;
  sdc.SetVtxBoundaryInterpolation(Sdc::Options::VTX_BOUNDARY_EDGE_ONLY);
  if (method == "chaikin") sdc.SetCreasingMethod(Sdc::Options::CREASE_CHAIKIN);
  else if (method == "uniform") sdc.SetCreasingMethod(Sdc::Options::CREASE_UNIFORM);
  else return fail("unknown method " + method);

  Far::TopologyDescriptor desc;
  desc.numVertices = int(xyz.size() / 3);
  desc.numFaces = int(fsize.size());
  desc.numVertsPerFace = fsize.data();
  desc.vertIndicesPerFace = fidx.data();
  desc.numCreases = int(crease_w.size());
  desc.creaseVertexIndexPairs = creases.data();
  desc.creaseWeights = crease_w.data();
  desc.numCorners = int(corner_w.size());
  desc.cornerVertexIndices = corners.data();
  desc.cornerWeights = corner_w.data();

  using Factory = Far::TopologyRefinerFactory<Far::TopologyDescriptor>;
  Far::SetErrorCallback(on_error);
  std::unique_ptr<Far::TopologyRefiner> refiner(
      Factory::Create(desc, Factory::Options(type, sdc)));
  if (!refiner) return fail("TopologyRefinerFactory::Create failed: " + g_error);
  Far::TopologyRefiner::UniformOptions uo(levels);
  uo.fullTopologyInLastLevel = true;
  refiner->RefineUniform(uo);
  if (!g_error.empty()) return fail("OpenSubdiv error: " + g_error);

  std::vector<V3> verts(std::size_t(refiner->GetNumVerticesTotal()));
  for (std::size_t v = 0; v < xyz.size() / 3; ++v)
    for (int c = 0; c < 3; ++c) verts[v].p[c] = xyz[3 * v + std::size_t(c)];
  Far::PrimvarRefinerReal<double> primvar(*refiner);
  V3* src = verts.data();
  for (int l = 1; l <= levels; ++l) {
    V3* dst = src + refiner->GetLevel(l - 1).GetNumVertices();
    primvar.Interpolate(l, src, dst);
    src = dst;
  }
  const Far::TopologyLevel& last = refiner->GetLevel(levels);
  std::printf("%d %d\n", last.GetNumVertices(), last.GetNumFaces());
  for (int v = 0; v < last.GetNumVertices(); ++v)
    std::printf("%.17g %.17g %.17g\n", src[v].p[0], src[v].p[1], src[v].p[2]);
  return 0;
}
