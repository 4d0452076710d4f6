// Does the driver's result depend on which corner each face starts at?
//
//   face_start MESH.off... 
//
// For each mesh (loaded with OpenMesh, flat arrays as the plugins export them) and each
// Möbius scheme that accepts it: the driver on the mesh as it is, and on the same mesh with
// every face's corner list rotated by one (the same polygon, same orientation), compared
// order-independently after 1 and 2 levels. A mathematically start-independent rule gives
// rounding-level differences (~1e-16); anything larger is a dependence on the face start.
#include <OpenMesh/Core/IO/MeshIO.hh>
#include <OpenMesh/Core/Mesh/PolyMesh_ArrayKernelT.hh>

#include <iostream>

#include <nlsubdiv/openmesh/nlsubdiv_openmesh.hh>  // installed header (scripts/install.sh)
#include "common.hpp"

using Poly = OpenMesh::PolyMesh_ArrayKernelT<OpenMesh::DefaultTraitsDouble>;

int main(int argc, char** argv) {
  const struct {
    const char* name;
    uint32_t scheme;
  } schemes[] = {{"loop", NLS_SCHEME_LOOP},
                 {"catmull-clark", NLS_SCHEME_CATMULL_CLARK},
                 {"butterfly", NLS_SCHEME_MODIFIED_BUTTERFLY},
                 {"kobbelt", NLS_SCHEME_KOBBELT},
                 {"doo-sabin", NLS_SCHEME_DOO_SABIN},
                 {"simplest", NLS_SCHEME_SIMPLEST},
                 {"dual", NLS_SCHEME_DUAL},
                 {"vertex-insertion", NLS_SCHEME_VERTEX_INSERTION},
                 {"dual-truncation", NLS_SCHEME_DUAL_TRUNCATION}};
  for (int a = 1; a < argc; ++a) {
    Poly m;
    std::streambuf* old = std::cerr.rdbuf(nullptr);
    bool loaded = OpenMesh::IO::read_mesh(m, argv[a]);
    std::cerr.rdbuf(old);
    if (!loaded) continue;
    nlsubdiv::openmesh::FlatMesh fm;
    if (nlsubdiv::openmesh::detail::export_flat(m, fm) != NLS_STATUS_OK) continue;
    itest::Flat in{fm.positions, fm.offsets, fm.indices}, rot = in;
    for (std::size_t f = 0; f < in.nf(); ++f)
      std::rotate(rot.idx.begin() + in.off[f], rot.idx.begin() + in.off[f] + 1, rot.idx.begin() + in.off[f + 1]);
    for (const auto& s : schemes)
      for (uint32_t flags : {0u, (uint32_t)NLS_SUBDIVIDE_MOBIUS}) {
        std::printf("%-36s %-18s %-7s", argv[a], s.name, flags ? "mobius" : "linear");
        for (uint32_t lv = 1; lv <= 2; ++lv) {
          itest::Flat x, y;
          nls_status s1 = itest::driver(s.scheme, flags, in, lv, x), s2 = itest::driver(s.scheme, flags, rot, lv, y);
          if (s1 || s2) {
            std::printf("  level %u: %s", lv, nls_status_str(s1 ? s1 : s2));
            break;
          }
          itest::Cmp c = itest::compare(x, y);
          std::printf("  level %u: max_rel %.2e%s", lv, c.max_rel, c.faces ? "" : " faces DIFFER");
        }
        std::printf("\n");
      }
  }
  return 0;
}
