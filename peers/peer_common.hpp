// peer_common.hpp: shared types of the peer reference harness (peer_subdivide).
//
// The harness runs the linear subdivision schemes of OpenMesh 9.0, CGAL 5.5 and
// OpenSubdiv 3.5 on one OFF mesh. Each library backend lives in its own
// translation unit (peer_openmesh.cpp, peer_cgal.cpp, peer_osd.cpp) so the
// heavy headers compile in parallel; they share only this header.
#ifndef NLSUBDIV_PEER_COMMON_HPP
#define NLSUBDIV_PEER_COMMON_HPP

#include <cstddef>
#include <string>
#include <vector>

namespace peer {

// A polygon mesh as flat arrays: xyz has 3 * nv() doubles, face f has
// fsize[f] vertex indices starting at fidx[fstart(f)].
struct Mesh {
  std::vector<double> xyz;
  std::vector<int> fsize;
  std::vector<int> fidx;

  std::size_t nv() const { return xyz.size() / 3; }
  std::size_t nf() const { return fsize.size(); }
  void clear() { xyz.clear(); fsize.clear(); fidx.clear(); }
  void add_vertex(double x, double y, double z) {
    xyz.push_back(x); xyz.push_back(y); xyz.push_back(z);
  }
};

// Exit codes of peer_subdivide (documented in peers/README.md).
enum Exit : int {
  EXIT_OK = 0,           // output written
  EXIT_USAGE = 1,        // bad arguments, I/O error, output too large
  EXIT_REJECTED = 2,     // unreadable/invalid mesh, or the library rejects it
  EXIT_UNSUPPORTED = 3,  // the library does not implement this scheme
};

enum class Scheme { Loop, CatmullClark, Butterfly, DooSabin, Sqrt3 };

// Result of a backend: status is EXIT_OK or EXIT_REJECTED (msg says why).
struct Outcome {
  int status = EXIT_OK;
  std::string msg;
  static Outcome ok() { return Outcome(); }
  static Outcome reject(const std::string& m) { Outcome o; o.status = EXIT_REJECTED; o.msg = m; return o; }
};

// Backends. `in` is validated (indices in range, faces of >= 3 distinct
// vertices, finite coordinates, no unreferenced vertices; triangles only for
// Loop/Butterfly/Sqrt3; for OpenMesh and CGAL also an oriented 2-manifold with
// boundary). `out` receives the refined mesh, faces in the library's own
// vertex order and orientation.
Outcome run_openmesh(Scheme s, int levels, const Mesh& in, Mesh& out);
Outcome run_cgal(Scheme s, int levels, const Mesh& in, Mesh& out);
Outcome run_osd(Scheme s, int levels, const Mesh& in, Mesh& out);

// The harness's own oriented-2-manifold check (peer_subdivide.cpp).
bool validate_manifold_mesh(const Mesh& m, std::string& err);

}  // namespace peer

#endif
