// Integration test of integrations/openmesh/nlsubdiv_openmesh.hh against Debian's OpenMesh 9:
//
//   test_openmesh MESH_DIR
//
// 1. every subdivider equals the driver (nls_mesh_subdivide on the same mesh, same
//    scheme and flags), order-independent, <= 1e-12 relative, on every mesh of MESH_DIR that
//    OpenMesh loads whole (1 or 2 levels by size); where the driver refuses a mesh the
//    subdivider must refuse it with the same status and leave it unchanged;
//    the differential classes equal the differential driver on the triangle meshes of <= 3000
//    faces, refuse non-triangles and report NOT_CONVERGED (max_iterations = 1), unchanged;
// 2. LinearLoopT / LinearButterflyT equal OpenMesh's LoopT / ModifiedButterflyT (and
//    LinearCatmullClarkT equals CatmullClarkT on closed meshes, peer-rules.md);
// 3. every mesh of MESH_DIR/bad that OpenMesh can load (in a child process: OpenMesh's own
//    reader may abort on some) is refused by every applicable subdivider with the mesh
//    unchanged, and the process survives.
// Last line: "test_openmesh: N passed, M failed, K skipped".
#include <OpenMesh/Core/IO/MeshIO.hh>
#include <OpenMesh/Core/Mesh/PolyMesh_ArrayKernelT.hh>
#include <OpenMesh/Core/Mesh/TriMesh_ArrayKernelT.hh>
#include <OpenMesh/Tools/Subdivider/Uniform/CatmullClarkT.hh>
#include <OpenMesh/Tools/Subdivider/Uniform/LoopT.hh>
#include <OpenMesh/Tools/Subdivider/Uniform/ModifiedButterFlyT.hh>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cmath>
#include <functional>
#include <iostream>
#include <memory>
#include <sstream>

#include <nlsubdiv/openmesh/nlsubdiv_openmesh.hh>  // installed header (scripts/install.sh)
#include "common.hpp"

using Poly = OpenMesh::PolyMesh_ArrayKernelT<OpenMesh::DefaultTraitsDouble>;
using Tri = OpenMesh::TriMesh_ArrayKernelT<OpenMesh::DefaultTraitsDouble>;
namespace nom = nlsubdiv::openmesh;
using itest::Flat;

template <class M>
Flat flat_of(const M& m) {
  nom::FlatMesh f;
  Flat r;
  if (nom::detail::export_flat(m, f) != NLS_STATUS_OK) return r;
  r.pos = f.positions;
  r.off = f.offsets;
  r.idx = f.indices;
  return r;
}

/// One subdivider under test: runs `levels` levels on `m`; false + status on refusal.
template <class M>
struct Plugin {
  std::string name;
  uint32_t scheme, flags;
  std::function<bool(M&, uint32_t, bool, nls_status&)> run;
};

template <class M, class SD>
Plugin<M> make(const std::string& name, uint32_t scheme, uint32_t flags, bool attach_style) {
  return Plugin<M>{name, scheme, flags, [attach_style](M& m, uint32_t levels, bool strict, nls_status& st) {
                     SD sd;
                     sd.set_strict(strict);
                     bool ok;
                     if (attach_style) {
                       ok = sd.attach(m) && sd(levels);
                       sd.detach();
                     } else {
                       ok = sd(m, levels);
                     }
                     st = sd.status();
                     if (ok != (st == NLS_STATUS_OK)) st = static_cast<nls_status>(9999);  // inconsistent report
                     return ok;
                   }};
}

template <class M>
std::vector<Plugin<M>> plugins(const std::string& tag) {
  const uint32_t MOB = NLS_SUBDIVIDE_MOBIUS;
  // The subdividers that evaluate the star rules on OpenMesh's own connectivity run the
  // paper's rules; the fold guard needs a whole-mesh pass, which only the driver (the Bulk
  // subdividers) makes: their reference is the driver's literal mode.
  const uint32_t LIT = NLS_SUBDIVIDE_MOBIUS | NLS_SUBDIVIDE_LITERAL;
  std::vector<Plugin<M>> p = {
      make<M, nom::MobiusLoopT<M>>("MobiusLoopT<" + tag + ">", NLS_SCHEME_LOOP, LIT, true),
      make<M, nom::MobiusLoopBulkT<M>>("MobiusLoopBulkT<" + tag + ">", NLS_SCHEME_LOOP, MOB, false),
      make<M, nom::MobiusButterflyT<M>>("MobiusButterflyT<" + tag + ">", NLS_SCHEME_MODIFIED_BUTTERFLY, LIT, true),
      make<M, nom::MobiusButterflyBulkT<M>>("MobiusButterflyBulkT<" + tag + ">", NLS_SCHEME_MODIFIED_BUTTERFLY, MOB, false),
      make<M, nom::LinearLoopT<M>>("LinearLoopT<" + tag + ">", NLS_SCHEME_LOOP, 0, false),
      make<M, nom::LinearButterflyT<M>>("LinearButterflyT<" + tag + ">", NLS_SCHEME_MODIFIED_BUTTERFLY, 0, true),
  };
  if (!M::is_trimesh()) {
    std::vector<Plugin<M>> q = {
        make<M, nom::MobiusCatmullClarkT<M>>("MobiusCatmullClarkT<" + tag + ">", NLS_SCHEME_CATMULL_CLARK, LIT, true),
        make<M, nom::MobiusCatmullClarkBulkT<M>>("MobiusCatmullClarkBulkT<" + tag + ">", NLS_SCHEME_CATMULL_CLARK, MOB, false),
        make<M, nom::MobiusKobbeltT<M>>("MobiusKobbeltT<" + tag + ">", NLS_SCHEME_KOBBELT, MOB, true),
        make<M, nom::MobiusDooSabinT<M>>("MobiusDooSabinT<" + tag + ">", NLS_SCHEME_DOO_SABIN, MOB, false),
        make<M, nom::LinearCatmullClarkT<M>>("LinearCatmullClarkT<" + tag + ">", NLS_SCHEME_CATMULL_CLARK, 0, true),
        make<M, nom::LinearKobbeltT<M>>("LinearKobbeltT<" + tag + ">", NLS_SCHEME_KOBBELT, 0, false),
        make<M, nom::LinearDooSabinT<M>>("LinearDooSabinT<" + tag + ">", NLS_SCHEME_DOO_SABIN, 0, true),
        make<M, nom::SpherelikeT<M>>("SpherelikeT<" + tag + ">", NLS_SCHEME_SPHERELIKE, 0, true),
    };
    p.insert(p.end(), q.begin(), q.end());
  }
  return p;
}

/// The vertex and face counts of an OFF file's header (0 when unreadable).
static std::size_t off_face_count(const std::string& path, std::size_t* vertices = nullptr) {
  FILE* f = std::fopen(path.c_str(), "r");
  if (!f) return 0;
  char line[4096];
  std::size_t nv = 0, nf = 0;
  bool header = false;
  while (std::fgets(line, sizeof line, f)) {
    std::string s(line);
    auto h = s.find('#');
    if (h != std::string::npos) s = s.substr(0, h);
    std::istringstream in(s);
    std::string tok;
    while (in >> tok) {
      if (!header) {
        if (tok.find("OFF") != std::string::npos) header = true;
        continue;
      }
      nv = std::strtoul(tok.c_str(), nullptr, 10);
      in >> nf;
      std::fclose(f);
      if (vertices) *vertices = nv;
      return nf;
    }
  }
  std::fclose(f);
  (void)nv;
  return 0;
}

template <class M>
bool load(const std::string& path, M& m) {
  OpenMesh::IO::Options opt;
  std::streambuf* old = std::cerr.rdbuf(nullptr);  // OpenMesh's omerr complaints
  std::streambuf* oldo = std::cout.rdbuf(nullptr);
  bool ok = OpenMesh::IO::read_mesh(m, path, opt);
  std::cerr.rdbuf(old);
  std::cout.rdbuf(oldo);
  return ok;
}

static const double TOL = 1e-12;

template <class M>
void check_plugins(itest::Tally& t, const std::string& mesh, const M& m0, const std::string& tag) {
  const Flat in = flat_of(m0);
  const uint32_t levels = m0.n_faces() <= 3000 ? 2 : 1;
  for (auto& p : plugins<M>(tag)) {
    Flat ref;
    nls_status ds = itest::driver(p.scheme, p.flags, in, levels, ref);
    M m = m0;
    nls_status ps = NLS_STATUS_OK;
    bool ok = p.run(m, levels, false, ps);
    std::string what = p.name + " = driver";
    std::string where = p.name + " on " + mesh + " (" + std::to_string(levels) + " levels)";
    if (ds != NLS_STATUS_OK) {
      if (!ok && ps == ds && flat_of(m) == in)
        t.pass(p.name + " refuses what the driver refuses", 0);
      else
        t.fail(where + ": driver says " + nls_status_str(ds) + ", plugin " + (ok ? "succeeded" : nls_status_str(ps)) + " / mesh changed?");
      continue;
    }
    if (!ok) {
      t.fail(where + ": refused (" + std::string(nls_status_str(ps)) + ") but the driver accepts");
      continue;
    }
    itest::Cmp c = itest::compare(flat_of(m), ref);
    if (c.ok(TOL))
      t.pass(what, c.max_rel);
    else
      t.fail(where + ": " + c.summary());
    if (std::getenv("NLS_ITEST_VERBOSE")) std::printf("  %s: %s\n", where.c_str(), c.summary().c_str());
  }
}

template <class S>
auto size_table(S& sd, std::size_t n, int) -> decltype(sd.init_weights(n), void()) {
  sd.init_weights(n);  // LoopT indexes past its valence-50 table otherwise (peers/peer_openmesh.cpp)
}
template <class S>
void size_table(S&, std::size_t, long) {}

template <class Ours, class Theirs, class M>
void check_openmesh_peer(itest::Tally& t, const std::string& mesh, const M& m0, const char* what, uint32_t levels) {
  M a = m0, b = m0;
  Ours ours;
  bool ok = ours(a, levels);
  if (!ok && ours.level() == 1 && ours.status() != NLS_STATUS_FALLBACK_IN_STRICT_MODE) {
    // The input is one the kernel refuses (checked against the driver above); OpenMesh's own
    // subdividers take it (e.g. a non-manifold vertex): nothing to compare.
    std::printf("skip %s on %s: ours refuses it (%s), as the driver does\n", what, mesh.c_str(), ours.message());
    ++t.skipped;
    return;
  }
  Theirs theirs;
  std::size_t maxval = 0;
  for (auto v : m0.vertices()) maxval = std::max<std::size_t>(maxval, m0.valence(v));
  size_table(theirs, std::max<std::size_t>(50, 2 * maxval + 8), 0);
  theirs.attach(b);
  bool ok2 = theirs(levels);
  theirs.detach();
  if (!ok || !ok2) {
    t.fail(std::string(what) + " on " + mesh + ": ours " + (ok ? "ok" : ours.message()) + ", OpenMesh " + (ok2 ? "ok" : "failed"));
    return;
  }
  itest::Cmp c = itest::compare(flat_of(a), flat_of(b));
  if (c.ok(TOL))
    t.pass(what, c.max_rel);
  else
    t.fail(std::string(what) + " on " + mesh + ": " + c.summary());
}

/// The differential classes against the differential driver on a triangle mesh (<= 3000
/// faces; 2 levels up to 400 faces, else 1): the same mesh, order-independent, <= TOL, with
/// the same iterations and residual; sd(k) is one call of k levels. With max_iterations = 1
/// both must say NLS_STATUS_NOT_CONVERGED, the mesh unchanged.
template <class M>
void check_differential(itest::Tally& t, const std::string& mesh, const M& m0) {
  const Flat in = flat_of(m0);
  const uint32_t levels = m0.n_faces() <= 400 ? 2 : 1;
  struct S {
    const char* name;
    uint32_t stencil;
    std::function<nom::DifferentialT<M>*()> make;
  };
  const S cases[] = {{"DifferentialLoopT", NLS_DIFFERENTIAL_LOOP, [] { return new nom::DifferentialLoopT<M>(); }},
                     {"DifferentialButterflyT", NLS_DIFFERENTIAL_BUTTERFLY, [] { return new nom::DifferentialButterflyT<M>(); }},
                     {"DifferentialDirMagT", NLS_DIFFERENTIAL_DIRMAG, [] { return new nom::DifferentialDirMagT<M>(); }}};
  for (const S& c : cases) {
    const std::string where = std::string(c.name) + " on " + mesh + " (" + std::to_string(levels) + " levels)";
    Flat ref;
    nls_differential_report drep{};
    nls_status ds = itest::driver_differential(c.stencil, c.stencil == NLS_DIFFERENTIAL_DIRMAG ? 1 : 0, 100, 1e-10, in, levels, ref, drep);
    std::unique_ptr<nom::DifferentialT<M>> sd(c.make());
    M m = m0;
    sd->attach(m);
    bool ok = (*sd)(levels);
    sd->detach();
    if (ds != NLS_STATUS_OK) {
      if (!ok && sd->status() == ds && flat_of(m) == in)
        t.pass(std::string(c.name) + " refuses what the driver refuses", 0);
      else
        t.fail(where + ": driver says " + nls_status_str(ds) + ", plugin " + (ok ? "succeeded" : sd->message()));
    } else if (!ok) {
      t.fail(where + ": refused (" + sd->message() + ") but the driver accepts");
    } else {
      itest::Cmp cmp = itest::compare(flat_of(m), ref);
      if (cmp.ok(TOL) && sd->iterations() == drep.iterations && sd->residual() == drep.relative_residual)
        t.pass(std::string(c.name) + " = differential driver", cmp.max_rel);
      else
        t.fail(where + ": " + cmp.summary() + " iterations " + std::to_string(sd->iterations()) + " vs " + std::to_string(drep.iterations));
      if (std::getenv("NLS_ITEST_VERBOSE")) std::printf("  %s: %s\n", where.c_str(), cmp.summary().c_str());
    }
    // NOT_CONVERGED: max_iterations = 1 (tolerance 0 so one iteration cannot reach it).
    Flat r1;
    nls_differential_report rep1{};
    nls_status d1 = itest::driver_differential(c.stencil, c.stencil == NLS_DIFFERENTIAL_DIRMAG ? 1 : 0, 1, 0.0, in, levels, r1, rep1);
    M m1 = m0;
    std::unique_ptr<nom::DifferentialT<M>> sd1(c.make());
    sd1->set_max_iterations(1);
    sd1->set_tolerance(0.0);
    bool ok1 = (*sd1)(m1, levels);
    if (d1 == NLS_STATUS_NOT_CONVERGED && !ok1 && sd1->status() == NLS_STATUS_NOT_CONVERGED && flat_of(m1) == in && sd1->iterations() == rep1.iterations)
      t.pass(std::string(c.name) + ": max_iterations = 1 -> NOT_CONVERGED, mesh unchanged", 0);
    else
      t.fail(where + " max_iterations 1: driver " + nls_status_str(d1) + ", plugin " + (ok1 ? "succeeded" : sd1->message()) +
             (flat_of(m1) == in ? "" : ", mesh changed"));
  }
}

/// The differential classes refuse a mesh with a non-triangle (the face named), unchanged.
static void differential_refuses_non_triangles(itest::Tally& t) {
  Poly m;
  std::vector<Poly::VertexHandle> v;
  for (int k = 0; k < 6; ++k) v.push_back(m.add_vertex(Poly::Point(k % 3, k / 3, 0.1 * k)));
  m.add_face(v[0], v[1], v[4]);
  m.add_face(v[0], v[4], v[3]);
  m.add_face(std::vector<Poly::VertexHandle>{v[1], v[2], v[5], v[4]});
  const Flat before = flat_of(m);
  for (uint32_t st : {NLS_DIFFERENTIAL_LOOP, NLS_DIFFERENTIAL_BUTTERFLY, NLS_DIFFERENTIAL_DIRMAG}) {
    nom::DifferentialT<Poly> sd(st);
    Poly mm = m;
    bool ok = sd(mm, 1);
    if (!ok && sd.status() == NLS_STATUS_UNSUPPORTED_FACE_TYPE && sd.element() == 2 && flat_of(mm) == before)
      t.pass("DifferentialT refuses a quad (face named), mesh unchanged", 0);
    else
      t.fail(std::string(sd.name()) + " on a mesh with a quad: " + (ok ? "accepted" : sd.message()));
  }
}

/// Child process: load `path`, run every plugin in strict mode; exit 3 if OpenMesh cannot
/// load it, 0 if every plugin refused and left the mesh unchanged, 1 otherwise.
static int bad_child(const std::string& path, int fd, bool valid) {
  Poly m0;
  if (!load(path, m0) || m0.n_vertices() == 0) {
    if (write(fd, "N", 1) != 1) return 4;
    return 3;
  }
  std::size_t fv = 0, ff = off_face_count(path, &fv);
  if (m0.n_vertices() != fv || m0.n_faces() != ff) {
    std::printf("    OpenMesh repairs it on load: %zu of %zu vertices, %zu of %zu faces (not loaded as it is)\n", m0.n_vertices(), fv,
                m0.n_faces(), ff);
    std::fflush(stdout);
    if (write(fd, "R", 1) != 1) return 4;
    return 3;
  }
  if (write(fd, "L", 1) != 1) return 4;
  const Flat before = flat_of(m0);
  int bad = 0;
  for (auto& p : plugins<Poly>("PolyMesh")) {
    Poly m = m0;
    nls_status st = NLS_STATUS_OK;
    bool ok = p.run(m, 1, !valid, st);
    bool same = flat_of(m) == before;
    std::printf("    %-30s %s%s\n", p.name.c_str(), ok ? "accepted" : nls_status_str(st), ok ? "" : same ? ", mesh unchanged" : " MESH CHANGED");
    if (valid ? !(ok || (st == NLS_STATUS_UNSUPPORTED_FACE_TYPE && same)) : (ok || !same)) ++bad;
  }
  std::fflush(stdout);
  return bad ? 1 : 0;
}

/// Broken meshes an OpenMesh host can hold although its reader would not produce them:
/// each must be refused by the subdividers with the status named, the mesh unchanged.
static void synthetic(itest::Tally& t) {
  auto grid = [](int n) {
    Poly m;
    std::vector<Poly::VertexHandle> v;
    for (int j = 0; j <= n; ++j)
      for (int i = 0; i <= n; ++i) v.push_back(m.add_vertex(Poly::Point(i, j, 0.1 * i * j)));
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i) {
        auto a = v[j * (n + 1) + i], b = v[j * (n + 1) + i + 1], c = v[(j + 1) * (n + 1) + i + 1], d = v[(j + 1) * (n + 1) + i];
        m.add_face(a, b, c);
        m.add_face(a, c, d);
      }
    return m;
  };
  struct Case {
    const char* what;
    nls_status expect;
    bool strict;
    std::function<void(Poly&)> spoil;
  };
  std::vector<Case> cases = {
      {"NaN coordinate", NLS_STATUS_NON_FINITE_INPUT, false, [](Poly& m) { m.set_point(m.vertex_handle(4), Poly::Point(NAN, 0, 0)); }},
      {"infinite coordinate", NLS_STATUS_NON_FINITE_INPUT, false, [](Poly& m) { m.set_point(m.vertex_handle(0), Poly::Point(0, INFINITY, 0)); }},
      {"fan of valence 130", NLS_STATUS_VALENCE_TOO_HIGH, false,
       [](Poly& m) {
         m.clear();
         auto c = m.add_vertex(Poly::Point(0, 0, 0));
         std::vector<Poly::VertexHandle> r;
         for (int k = 0; k < 130; ++k) r.push_back(m.add_vertex(Poly::Point(std::cos(k * 0.0483), std::sin(k * 0.0483), 0)));
         for (int k = 0; k < 130; ++k) m.add_face(c, r[k], r[(k + 1) % 130]);
       }},
      {"unreferenced vertex (strict)", NLS_STATUS_INVALID_ARGUMENT, true, [](Poly& m) { m.add_vertex(Poly::Point(9, 9, 9)); }},
      {"two vertices at one position (strict)", NLS_STATUS_DEGENERATE_GEOMETRY, true,
       [](Poly& m) { m.set_point(m.vertex_handle(0), m.point(m.vertex_handle(24))); }},
      {"deleted elements (no garbage collection)", NLS_STATUS_INVALID_ARGUMENT, false,
       [](Poly& m) {
         m.request_face_status();
         m.request_edge_status();
         m.request_vertex_status();
         m.delete_face(m.face_handle(0), true);
       }},
  };
  for (const auto& c : cases) {
    Poly m0 = grid(4);
    c.spoil(m0);
    for (auto& p : plugins<Poly>("PolyMesh")) {
      if (p.scheme == NLS_SCHEME_KOBBELT) continue;  // triangles: refused for the face type first
      Poly m = m0;
      nls_status st = NLS_STATUS_OK;
      bool ok = p.run(m, 2, c.strict, st);
      bool same = m.n_vertices() == m0.n_vertices() && m.n_faces() == m0.n_faces();
      if (same)
        for (auto v : m0.vertices()) {
          auto a = m.point(v), b = m0.point(v);
          for (int k = 0; k < 3; ++k) same = same && (a[k] == b[k] || (std::isnan(a[k]) && std::isnan(b[k])));
        }
      if (!ok && st == c.expect && same)
        t.pass(std::string("in-memory broken mesh refused: ") + c.what, 0);
      else
        t.fail(p.name + " on " + c.what + ": " + (ok ? "accepted" : nls_status_str(st)) + (same ? "" : ", mesh changed"));
    }
  }
}

/// Sharp features: OpenMesh feature edges and vertices through set_feature_creases equal the
/// C driver's tagged call with the same tags given directly, bit for bit; a unit cube with all
/// twelve edges feature keeps its corners and has 12 (2^k - 1) + 8 vertices on its edge lines
/// after k = 2 levels of Catmull-Clark (the rules' consequence, not a recorded output), and
/// so does Kobbelt (its 4-point crease rule keeps the edges straight), each equal to the
/// driver's tagged call; so does Möbius Catmull–Clark (every vertex a corner: each face
/// refined alone, its edges open Möbius curves of collinear points); no feature is the
/// untagged result; a Doo–Sabin subdivider with features is refused
/// (NLS_STATUS_TAGS_NOT_SUPPORTED) with the mesh unchanged.
static void feature_creases(itest::Tally& t) {
  static const double P[8][3] = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, {0, 0, 1}, {1, 0, 1}, {1, 1, 1}, {0, 1, 1}};
  static const int F[6][4] = {{0, 3, 2, 1}, {4, 5, 6, 7}, {0, 1, 5, 4}, {1, 2, 6, 5}, {2, 3, 7, 6}, {3, 0, 4, 7}};
  Poly cube;
  std::vector<Poly::VertexHandle> vh;
  for (auto& p : P) vh.push_back(cube.add_vertex(Poly::Point(p[0], p[1], p[2])));
  for (auto& f : F) cube.add_face(std::vector<Poly::VertexHandle>{vh[f[0]], vh[f[1]], vh[f[2]], vh[f[3]]});
  Poly plain = cube;
  cube.request_edge_status();
  cube.request_vertex_status();
  for (auto e : cube.edges()) cube.status(e).set_feature(true);
  // The driver with the twelve edges typed as vertex pairs.
  nls_tags tags{};
  static const uint32_t E[24] = {0, 1, 1, 2, 2, 3, 3, 0, 4, 5, 5, 6, 6, 7, 7, 4, 0, 4, 1, 5, 2, 6, 3, 7};
  static const double S[12] = {10, 10, 10, 10, 10, 10, 10, 10, 10, 10, 10, 10};
  tags.crease_vertices = E;
  tags.crease_sharpness = S;
  tags.crease_count = 12;
  nlsubdiv::flat::FlatMesh in, want;
  nom::detail::export_flat(plain, in);
  uint32_t el = 0, fb = 0;
  nls_status ds = nlsubdiv::flat::run_levels(NLS_SCHEME_CATMULL_CLARK, 0, in, 2, want, el, fb, &tags);
  Poly a = cube;
  nom::LinearCatmullClarkT<Poly> sd;
  sd.set_feature_creases(true);
  const bool ok = sd(a, 2);
  Flat got = flat_of(a);
  const bool same = ds == NLS_STATUS_OK && ok && got.pos == want.positions && got.off == want.offsets && got.idx == want.indices;
  std::size_t on_edges = 0;
  bool corners_kept = got.nv() >= 8;
  for (std::size_t v = 0; v < got.nv(); ++v) {
    int n = 0;
    for (int k = 0; k < 3; ++k) n += (std::fabs(got.pos[3 * v + k]) <= 1e-15 || std::fabs(got.pos[3 * v + k] - 1.0) <= 1e-15);
    on_edges += n >= 2;
    if (v < 8)
      for (int k = 0; k < 3; ++k) corners_kept = corners_kept && got.pos[3 * v + k] == P[v][k];
  }
  if (same && on_edges == 12 * 3 + 8 && corners_kept)
    t.pass("OpenMesh feature edges = driver tags (sharp cube keeps its edges and corners)", 0);
  else
    t.fail(std::string("feature creases: ") + (ok ? "" : sd.message()) + (same ? "" : " differs from the tagged driver") +
           (corners_kept ? "" : " corners moved") + " on_edges=" + std::to_string(on_edges));
  // Kobbelt: the same tags through LinearKobbeltT, the driver's bits, the edges kept.
  {
    nlsubdiv::flat::FlatMesh kwant;
    uint32_t kel = 0, kfb = 0;
    nls_status ks = nlsubdiv::flat::run_levels(NLS_SCHEME_KOBBELT, 0, in, 2, kwant, kel, kfb, &tags);
    Poly k = cube;
    nom::LinearKobbeltT<Poly> ksd;
    ksd.set_feature_creases(true);
    const bool kok = ksd(k, 2);
    Flat kgot = flat_of(k);
    const bool ksame =
        ks == NLS_STATUS_OK && kok && kgot.pos == kwant.positions && kgot.off == kwant.offsets && kgot.idx == kwant.indices;
    std::size_t kon = 0;
    for (std::size_t v = 0; v < kgot.nv(); ++v) {
      int n = 0;
      for (int c = 0; c < 3; ++c) n += (std::fabs(kgot.pos[3 * v + c]) <= 1e-15 || std::fabs(kgot.pos[3 * v + c] - 1.0) <= 1e-15);
      kon += n >= 2;
    }
    if (ksame && kon == 12 * 3 + 8)
      t.pass("OpenMesh Kobbelt feature edges = driver tags (sharp cube keeps its edges)", 0);
    else
      t.fail(std::string("Kobbelt feature creases: ") + (kok ? "" : ksd.message()) + (ksame ? "" : " differs from the tagged driver") +
             " on_edges=" + std::to_string(kon));
  }
  // No feature flag set: the untagged result.
  Poly b = plain, c = plain;
  nom::LinearCatmullClarkT<Poly> sd2, sd3;
  sd2.set_feature_creases(true);
  if (sd2(b, 2) && sd3(c, 2) && flat_of(b) == flat_of(c))
    t.pass("OpenMesh feature creases without features = untagged", 0);
  else
    t.fail("feature creases without features differ from the untagged subdivider");
  // Möbius Catmull-Clark with the same features: the driver's tagged Möbius bits. Every
  // vertex is a corner (three sharp edges), so each face is refined alone with its edges as
  // open Möbius curves between corners: collinear points stay on their line and a planar
  // face in its plane, so the edge lines are kept as by the linear rules.
  {
    nlsubdiv::flat::FlatMesh mwant;
    uint32_t mel = 0, mfb = 0;
    nls_status ms = nlsubdiv::flat::run_levels(NLS_SCHEME_CATMULL_CLARK, NLS_SUBDIVIDE_MOBIUS, in, 2, mwant, mel, mfb, &tags);
    Poly m = cube;
    nom::MobiusCatmullClarkBulkT<Poly> msd;
    msd.set_feature_creases(true);
    const bool mok = msd(m, 2);
    Flat mgot = flat_of(m);
    const bool msame =
        ms == NLS_STATUS_OK && mok && mgot.pos == mwant.positions && mgot.off == mwant.offsets && mgot.idx == mwant.indices;
    std::size_t mon = 0, on_faces = 0;
    for (std::size_t v = 0; v < mgot.nv(); ++v) {
      int n = 0;
      for (int k = 0; k < 3; ++k) n += (std::fabs(mgot.pos[3 * v + k]) <= 1e-12 || std::fabs(mgot.pos[3 * v + k] - 1.0) <= 1e-12);
      mon += n >= 2;
      on_faces += n >= 1;
    }
    Poly mp = plain;
    nom::MobiusCatmullClarkBulkT<Poly> mplain;
    const bool differs = mplain(mp, 2) && !(flat_of(mp) == mgot);
    if (msame && mon == 12 * 3 + 8 && on_faces == mgot.nv() && differs)
      t.pass("OpenMesh Möbius Catmull-Clark feature edges = driver tags (sharp cube keeps its edges and faces)", 0);
    else
      t.fail(std::string("Möbius feature creases: ") + (mok ? "" : msd.message()) + (msame ? "" : " differs from the tagged driver") +
             " on_edges=" + std::to_string(mon) + " on_faces=" + std::to_string(on_faces) + (differs ? "" : " same as untagged"));
  }
  // Per-element sharpness from OpenMesh properties: the top face's edges infinitely sharp,
  // one vertical edge 1.5, vertex 0 a corner of 2.5; the driver with the same tags typed
  // directly (tag order does not matter to the kernel). A NaN value is refused, mesh unchanged.
  {
    Poly q = plain;
    OpenMesh::EPropHandleT<double> esh;
    OpenMesh::VPropHandleT<double> vsh;
    q.add_property(esh);
    q.add_property(vsh);
    for (auto e : q.edges()) q.property(esh, e) = 0.0;
    for (auto v : q.vertices()) q.property(vsh, v) = 0.0;
    auto edge_of = [&](int a, int b) -> Poly::EdgeHandle {
      for (auto h : q.voh_range(q.vertex_handle(a)))
        if (q.to_vertex_handle(h).idx() == b) return Poly::EdgeHandle(q.edge_handle(h));
      return Poly::EdgeHandle();
    };
    static const uint32_t PE[10] = {4, 5, 5, 6, 6, 7, 7, 4, 0, 4};
    static const double PS[5] = {10, 10, 10, 10, 1.5};
    for (int k = 0; k < 5; ++k) q.property(esh, edge_of(static_cast<int>(PE[2 * k]), static_cast<int>(PE[2 * k + 1]))) = PS[k];
    q.property(vsh, q.vertex_handle(0)) = 2.5;
    nls_tags pt{};
    static const uint32_t PV[1] = {0};
    static const double PVS[1] = {2.5};
    pt.crease_vertices = PE;
    pt.crease_sharpness = PS;
    pt.crease_count = 5;
    pt.corner_vertices = PV;
    pt.corner_sharpness = PVS;
    pt.corner_count = 1;
    nlsubdiv::flat::FlatMesh pwant;
    uint32_t pel = 0, pfb = 0;
    nls_status ps = nlsubdiv::flat::run_levels(NLS_SCHEME_CATMULL_CLARK, 0, in, 2, pwant, pel, pfb, &pt);
    Poly r = q;
    nom::LinearCatmullClarkT<Poly> psd;
    psd.set_sharpness_properties(esh, vsh);
    const bool pok = psd(r, 2);
    Flat pgot = flat_of(r);
    const bool psame = ps == NLS_STATUS_OK && pok && pgot.pos == pwant.positions && pgot.off == pwant.offsets && pgot.idx == pwant.indices;
    Poly nan_mesh = q;
    nan_mesh.property(esh, edge_of(0, 1)) = std::nan("");
    Poly nan_copy = nan_mesh;
    nom::LinearCatmullClarkT<Poly> nsd;
    nsd.set_sharpness_properties(esh, vsh);
    const bool refused_nan = !nsd(nan_mesh, 1) && nsd.status() == NLS_STATUS_INVALID_SHARPNESS && flat_of(nan_mesh) == flat_of(nan_copy);
    const bool differs = !(pgot == flat_of(b));
    if (psame && refused_nan && differs)
      t.pass("OpenMesh sharpness properties = driver tags (semi-sharp, corner); NaN refused", 0);
    else
      t.fail(std::string("sharpness properties: ") + (pok ? "" : psd.message()) + (psame ? "" : " differs from the tagged driver") +
             (refused_nan ? "" : " NaN not refused: " + std::string(nsd.message())) + (differs ? "" : " same as untagged"));
  }
  // Schemes without tag rules refuse a mesh with features, unchanged.
  Poly d = cube;
  nom::MobiusDooSabinT<Poly> mob;
  mob.set_feature_creases(true);
  const bool refused = !mob(d, 1) && mob.status() == NLS_STATUS_TAGS_NOT_SUPPORTED && flat_of(d) == flat_of(cube);
  Poly e = cube;
  nom::LinearCatmullClarkT<Poly> per_level;
  per_level.set_feature_creases(true);
  const bool refused2 = !per_level(e, 1, false) && per_level.status() == NLS_STATUS_INVALID_ARGUMENT;
  if (refused && refused2)
    t.pass("features refused by Doo-Sabin and by per-level calls, mesh unchanged", 0);
  else
    t.fail(std::string("features not refused: ") + mob.message() + " / " + per_level.message());
}

/// OpenMesh's interface 1 (`Sd sd(mesh); sd(n)`) gives interface 2's result bit for bit, for
/// a driver class, a star-rule class and a differential class; messages name the element's
/// kind ("face 0" for a quad under Loop).
static void openmesh_interfaces_and_messages(itest::Tally& t) {
  Tri a;
  std::vector<Tri::VertexHandle> v;
  static const double Q[6][3] = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1.3}};
  static const int T[8][3] = {{0, 2, 4}, {2, 1, 4}, {1, 3, 4}, {3, 0, 4}, {2, 0, 5}, {1, 2, 5}, {3, 1, 5}, {0, 3, 5}};
  for (auto& q : Q) v.push_back(a.add_vertex(Tri::Point(q[0], q[1], q[2])));
  for (auto& f : T) a.add_face(v[f[0]], v[f[1]], v[f[2]]);
  bool same = true;
  {
    Tri m1 = a, m2 = a;
    nom::LinearLoopT<Tri> s1(m1);
    same = same && s1(2);
    nom::LinearLoopT<Tri> s2;
    same = same && s2(m2, 2) && flat_of(m1) == flat_of(m2);
  }
  {
    Tri m1 = a, m2 = a;
    nom::MobiusLoopT<Tri> s1(m1);
    same = same && s1(1);
    nom::MobiusLoopT<Tri> s2;
    same = same && s2(m2, 1) && flat_of(m1) == flat_of(m2);
  }
  {
    Tri m1 = a, m2 = a;
    nom::DifferentialLoopT<Tri> s1(m1);
    same = same && s1(1);
    nom::DifferentialLoopT<Tri> s2;
    same = same && s2(m2, 1) && flat_of(m1) == flat_of(m2);
  }
  if (same)
    t.pass("OpenMesh interface 1 (constructor with the mesh) = interface 2", 0);
  else
    t.fail("OpenMesh interface 1 differs from interface 2");
  Poly q;
  auto a0 = q.add_vertex(Poly::Point(0, 0, 0)), a1 = q.add_vertex(Poly::Point(1, 0, 0)), a2 = q.add_vertex(Poly::Point(1, 1, 0)),
       a3 = q.add_vertex(Poly::Point(0, 1, 0));
  q.add_face(std::vector<Poly::VertexHandle>{a0, a1, a2, a3});
  nom::LinearLoopT<Poly> loop;
  const bool refused = !loop(q, 1);
  const std::string msg = loop.message();
  if (refused && msg.find("(face 0)") != std::string::npos)
    t.pass("messages name the element's kind (face 0)", 0);
  else
    t.fail("message for a quad under Loop: " + msg);
}

// ---- spectrum weight, differential edits, properties ----

static nlsubdiv::flat::FlatMesh to_fm(const Flat& f) {
  nlsubdiv::flat::FlatMesh m;
  m.positions = f.pos;
  m.offsets = f.off;
  m.indices = f.idx;
  return m;
}
static Flat of_fm(const nlsubdiv::flat::FlatMesh& m) {
  Flat f;
  f.pos = m.positions;
  f.off = m.offsets;
  f.idx = m.indices;
  return f;
}

template <class M>
static M octahedron() {
  static const double Q[6][3] = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
  static const int T[8][3] = {{0, 2, 4}, {2, 1, 4}, {1, 3, 4}, {3, 0, 4}, {2, 0, 5}, {1, 2, 5}, {3, 1, 5}, {0, 3, 5}};
  M m;
  std::vector<typename M::VertexHandle> v;
  for (auto& q : Q) v.push_back(m.add_vertex(typename M::Point(q[0], q[1], q[2])));
  for (auto& f : T) m.add_face(v[f[0]], v[f[1]], v[f[2]]);
  return m;
}

/// set_linear_weight: 0 = Möbius, 1 = linear bit for bit, 0.5 = the C ABI, 2 refused.
static void spectrum_weight(itest::Tally& t) {
  const Tri oct = octahedron<Tri>();
  const Flat in = flat_of(oct);
  Tri mob = oct, lin = oct, w0 = oct, w1 = oct, wh = oct, bad = oct;
  nom::MobiusLoopBulkT<Tri> a, b, c, d, e;
  nom::LinearLoopT<Tri> l;
  b.set_linear_weight(0.0);
  c.set_linear_weight(1.0);
  d.set_linear_weight(0.5);
  e.set_linear_weight(2.0);
  const bool ok = a(mob, 2) && l(lin, 2) && b(w0, 2) && c(w1, 2) && d(wh, 2);
  const bool refused = !e(bad, 2) && e.status() == NLS_STATUS_INVALID_ARGUMENT && flat_of(bad) == in;
  nlsubdiv::flat::FlatMesh half;
  uint32_t el = 0, fb = 0;
  const nls_status hs = nlsubdiv::flat::run_levels(NLS_SCHEME_LOOP, NLS_SUBDIVIDE_MOBIUS, to_fm(in), 2, half, el, fb, nullptr, 0.5);
  if (ok && refused && hs == NLS_STATUS_OK && flat_of(w0) == flat_of(mob) && flat_of(w1) == flat_of(lin) && flat_of(wh) == of_fm(half) &&
      !(flat_of(mob) == flat_of(lin)) && !(flat_of(wh) == flat_of(mob)) && !(flat_of(wh) == flat_of(lin)))
    t.pass("OpenMesh set_linear_weight: 0 = Möbius, 1 = linear bit for bit, 0.5 = C ABI, 2 refused", 0);
  else
    t.fail(std::string("OpenMesh set_linear_weight: ") + e.message());
  // Catmull-Clark: weight 1 = linear.
  Poly cube;
  {
    static const double P[8][3] = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, {0, 0, 1}, {1, 0, 1}, {1, 1, 1}, {0, 1, 1}};
    static const int F[6][4] = {{0, 3, 2, 1}, {4, 5, 6, 7}, {0, 1, 5, 4}, {1, 2, 6, 5}, {2, 3, 7, 6}, {3, 0, 4, 7}};
    std::vector<Poly::VertexHandle> v;
    for (auto& p : P) v.push_back(cube.add_vertex(Poly::Point(p[0], p[1], p[2])));
    for (auto& f : F) cube.add_face(std::vector<Poly::VertexHandle>{v[f[0]], v[f[1]], v[f[2]], v[f[3]]});
  }
  Poly cm = cube, cl = cube;
  nom::MobiusCatmullClarkBulkT<Poly> sc;
  sc.set_linear_weight(1.0);
  nom::LinearCatmullClarkT<Poly> lc;
  if (sc(cm, 2) && lc(cl, 2) && flat_of(cm) == flat_of(cl))
    t.pass("OpenMesh set_linear_weight(1): Möbius Catmull-Clark = Catmull-Clark bit for bit", 0);
  else
    t.fail("OpenMesh set_linear_weight(1) Catmull-Clark");
}

/// set_linear_weight_property: equal values = set_linear_weight of that value bit for bit,
/// mixed values = the C ABI's linear_weights with the same array, a NaN refused naming its
/// vertex (mesh unchanged), update_points = false refused.
static void spectrum_weight_property(itest::Tally& t) {
  const Tri oct = octahedron<Tri>();
  const Flat in = flat_of(oct);
  Tri eq = oct, g = oct, mixed = oct, bad = oct, keep = oct;
  OpenMesh::VPropHandleT<double> u;
  for (Tri* m : {&eq, &mixed, &bad, &keep}) m->add_property(u, "linear weight");
  for (auto v : eq.vertices()) eq.property(u, v) = 0.3;
  std::vector<double> uw;
  for (auto v : mixed.vertices()) {
    mixed.property(u, v) = (v.idx() % 3) / 2.0;
    uw.push_back(mixed.property(u, v));
  }
  for (auto v : bad.vertices()) bad.property(u, v) = v.idx() == 4 ? std::nan("") : 0.5;
  for (auto v : keep.vertices()) keep.property(u, v) = 0.5;
  nom::MobiusLoopBulkT<Tri> a, b, c, d, e;
  a.set_linear_weight_property(u);
  b.set_linear_weight(0.3);
  c.set_linear_weight_property(u);
  d.set_linear_weight_property(u);
  e.set_linear_weight_property(u);
  const bool ok = a(eq, 2) && b(g, 2) && c(mixed, 2);
  nlsubdiv::flat::FlatMesh want;
  uint32_t el = 0, fb = 0;
  const nls_status cs = nlsubdiv::flat::run_levels(NLS_SCHEME_LOOP, NLS_SUBDIVIDE_MOBIUS, to_fm(in), 2, want, el, fb, nullptr, 0.0, uw.data());
  const bool refused = !d(bad, 2) && d.status() == NLS_STATUS_INVALID_ARGUMENT && d.element() == 4 && flat_of(bad) == in;
  const bool one_by_one = !e(keep, 2, false) && e.status() == NLS_STATUS_INVALID_ARGUMENT && flat_of(keep) == in;
  if (ok && cs == NLS_STATUS_OK && flat_of(eq) == flat_of(g) && flat_of(mixed) == of_fm(want) && !(flat_of(mixed) == flat_of(g)) &&
      refused && one_by_one)
    t.pass("OpenMesh set_linear_weight_property: equal = set_linear_weight, mixed = C ABI linear_weights, NaN refused naming the vertex", 0);
  else
    t.fail(std::string("OpenMesh set_linear_weight_property: ") + d.message());
}

/// `Sd` on `mesh0` (`levels` levels, linear weight `u`) on 2, 3, 7 and all threads, each
/// subdivider called twice (its pool serves both calls), against one thread.
template <class Sd, class M>
static void same_bits(itest::Tally& t, const M& mesh0, unsigned levels, const char* what, double u = 0.0) {
  M ref = mesh0;
  Sd sd1;
  sd1.set_linear_weight(u);
  const bool ok1 = sd1(ref, levels);
  bool all = ok1;
  std::string why;
  for (unsigned n : {2u, 3u, 7u, 0u}) {
    Sd sd;
    sd.set_linear_weight(u);
    sd.set_threads(n);
    for (int rep = 0; rep < 2; ++rep) {
      M m = mesh0;
      const bool ok = sd(m, levels);
      if (ok != ok1 || !(flat_of(m) == flat_of(ref)) || sd.fallbacks() != sd1.fallbacks() || sd.status() != sd1.status()) {
        all = false;
        why += " threads " + std::to_string(n);
      }
    }
    if (n != 0 && sd.threads() != n) all = false;
  }
  if (all)
    t.pass(std::string("OpenMesh set_threads: ") + what + ": 1, 2, 3, 7 and all threads give the same bits", 0);
  else
    t.fail(std::string("OpenMesh set_threads: ") + what + ":" + why);
}

/// set_threads: the same output and fallbacks for 1, 2, 3, 7 and the hardware's thread count
/// (every pass of the kernel split over a persistent pool); a pool is reused by later calls;
/// a refused call is refused the same way on the pool, mesh unchanged.
static void threads(itest::Tally& t) {
  Tri oct = octahedron<Tri>();
  // Off the sphere, so that the Möbius rules differ from the sphere's and the guard has work.
  for (auto v : oct.vertices()) oct.point(v) *= 1.0 + 0.1 * v.idx();
  Poly cube;
  {
    static const double P[8][3] = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, {0, 0, 1}, {1, 0, 1}, {1, 1, 1}, {0, 1, 1.3}};
    static const int F[6][4] = {{0, 3, 2, 1}, {4, 5, 6, 7}, {0, 1, 5, 4}, {1, 2, 6, 5}, {2, 3, 7, 6}, {3, 0, 4, 7}};
    std::vector<Poly::VertexHandle> v;
    for (auto& p : P) v.push_back(cube.add_vertex(Poly::Point(p[0], p[1], p[2])));
    for (auto& f : F) cube.add_face(std::vector<Poly::VertexHandle>{v[f[0]], v[f[1]], v[f[2]], v[f[3]]});
  }
  same_bits<nom::MobiusLoopBulkT<Tri>>(t, oct, 4, "Möbius Loop, 4 levels");
  same_bits<nom::MobiusButterflyBulkT<Tri>>(t, oct, 4, "Möbius Butterfly, 4 levels");
  same_bits<nom::MobiusCatmullClarkBulkT<Poly>>(t, cube, 4, "Möbius Catmull-Clark, 4 levels");
  same_bits<nom::LinearCatmullClarkT<Poly>>(t, cube, 4, "Catmull-Clark, 4 levels");
  same_bits<nom::MobiusLoopBulkT<Tri>>(t, oct, 3, "Möbius Loop at linear weight 0.5, 3 levels", 0.5);
  // A refused call: the same status on the pool, the mesh unchanged.
  Tri bad = oct;
  nom::MobiusLoopBulkT<Tri> e;
  e.set_threads(3);
  e.set_linear_weight(2.0);
  if (!e(bad, 2) && e.status() == NLS_STATUS_INVALID_ARGUMENT && flat_of(bad) == flat_of(oct))
    t.pass("OpenMesh set_threads(3): a bad weight is refused as on one thread, mesh unchanged", 0);
  else
    t.fail(std::string("OpenMesh set_threads(3) refusal: ") + e.message());
}

/// Differential edits through vertex properties = the C ABI with the same arrays.
static void differential_edits(itest::Tally& t) {
  const Tri oct = octahedron<Tri>();
  const Flat in = flat_of(oct);
  auto c_diff = [&](const std::vector<double>* cs, const std::vector<double>* ns, Flat& out, uint32_t& el) {
    nls_differential_options o{};
    nls_differential_default_options(&o);
    o.scheme = NLS_DIFFERENTIAL_LOOP;
    o.levels = 2;
    o.curvature_scale = cs ? cs->data() : nullptr;
    o.normals = ns ? ns->data() : nullptr;
    nlsubdiv::flat::FlatMesh fo;
    nls_differential_report rep{};
    nls_status s = nlsubdiv::flat::run_differential(o, to_fm(in), fo, el, rep);
    out = of_fm(fo);
    return s;
  };
  std::vector<double> scale(6, 1.0), normals(18, 0.0);
  scale[4] = 2.0;
  normals[3 * 4 + 0] = 0.3;
  normals[3 * 4 + 2] = 1.0;
  Flat want_c, want_n, plain;
  uint32_t el = 0;
  const nls_status s1 = c_diff(&scale, nullptr, want_c, el), s2 = c_diff(nullptr, &normals, want_n, el), s3 = c_diff(nullptr, nullptr, plain, el);
  Tri a = oct, b = oct;
  OpenMesh::VPropHandleT<double> cp;
  a.add_property(cp, "curvature scale");
  for (auto v : a.vertices()) a.property(cp, v) = v.idx() == 4 ? 2.0 : 1.0;
  OpenMesh::VPropHandleT<OpenMesh::Vec3d> np;
  b.add_property(np, "target normal");
  for (auto v : b.vertices()) b.property(np, v) = v.idx() == 4 ? OpenMesh::Vec3d(0.3, 0, 1.0) : OpenMesh::Vec3d(0, 0, 0);
  nom::DifferentialLoopT<Tri> sa, sb;
  sa.set_curvature_scale_property(cp);
  sb.set_normal_property(np);
  const bool ok = sa(a, 2) && sb(b, 2);
  const Flat fa = flat_of(a), fb = flat_of(b);
  if (ok && s1 == NLS_STATUS_OK && s2 == NLS_STATUS_OK && s3 == NLS_STATUS_OK && fa == want_c && fb == want_n && !(fa == plain) && !(fb == plain))
    t.pass("OpenMesh differential edits (curvature and normal properties) = C ABI arrays bit for bit", 0);
  else
    t.fail(std::string("OpenMesh differential edits: ") + sa.message() + " / " + sb.message());
  if (ok && fa.pos[3 * 4 + 2] > plain.pos[3 * 4 + 2])
    t.pass("OpenMesh doubled curvature on the apex moves it outward", 0);
  else
    t.fail("OpenMesh doubled curvature does not move the apex outward");
  scale[4] = NAN;
  Flat dummy;
  uint32_t cel = 0;
  const nls_status cs = c_diff(&scale, nullptr, dummy, cel);
  Tri c = oct;
  OpenMesh::VPropHandleT<double> cp2;
  c.add_property(cp2, "curvature scale");
  for (auto v : c.vertices()) c.property(cp2, v) = v.idx() == 4 ? NAN : 1.0;
  nom::DifferentialLoopT<Tri> sc;
  sc.set_curvature_scale_property(cp2);
  const bool okc = sc(c, 2);
  if (!okc && cs != NLS_STATUS_OK && sc.status() == cs && sc.element() == 4 && cel == 4 && flat_of(c) == in)
    t.pass(std::string("OpenMesh NaN curvature scale refused: ") + sc.message(), 0);
  else
    t.fail(std::string("OpenMesh NaN curvature scale: ") + (okc ? "accepted" : sc.message()));
}

/// A planar regular grid (n x n unit squares; triangles: each square split by its diagonal).
template <class M>
static M planar_grid(int n, bool triangles) {
  M m;
  std::vector<typename M::VertexHandle> v;
  for (int j = 0; j <= n; ++j)
    for (int i = 0; i <= n; ++i) v.push_back(m.add_vertex(typename M::Point(i, j, 0)));
  auto at = [&](int i, int j) { return v[static_cast<std::size_t>(j * (n + 1) + i)]; };
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      if (triangles) {
        m.add_face(at(i, j), at(i + 1, j), at(i + 1, j + 1));
        m.add_face(at(i, j), at(i + 1, j + 1), at(i, j + 1));
      } else {
        m.add_face(std::vector<typename M::VertexHandle>{at(i, j), at(i + 1, j), at(i + 1, j + 1), at(i, j + 1)});
      }
    }
  return m;
}

/// Whether point (x, y) lies strictly inside face f of m (its polygon is convex, counter-clockwise).
template <class M>
static bool inside(const M& m, typename M::FaceHandle f, double x, double y) {
  std::vector<typename M::Point> p;
  for (auto v : m.fv_range(f)) p.push_back(m.point(v));
  for (std::size_t i = 0; i < p.size(); ++i) {
    const auto& a = p[i];
    const auto& b = p[(i + 1) % p.size()];
    if ((b[0] - a[0]) * (y - a[1]) - (b[1] - a[1]) * (x - a[0]) <= 1e-12) return false;
  }
  return true;
}

/// Properties through one level of `SD` on the planar grid, checked from the geometry: linear
/// Loop and Catmull-Clark keep a regular planar grid in place (edge points are the edge
/// midpoints, face points the centroids), so the input face of a child face is the one input
/// face containing its centroid, and the input edge of a child edge (a, e) with a an input
/// vertex is (a, 2e - a). Old vertices keep their vertex property, new ones hold the default.
template <class M, class SD>
static bool properties_one_level(const M& m0, std::string& why) {
  M m = m0;
  OpenMesh::VPropHandleT<int> vp;
  OpenMesh::EPropHandleT<int> ep;
  OpenMesh::FPropHandleT<int> fp;
  m.add_property(vp, "vp");
  m.add_property(ep, "ep");
  m.add_property(fp, "fp");
  for (auto v : m.vertices()) m.property(vp, v) = 1000 + v.idx();
  for (auto e : m.edges()) m.property(ep, e) = 2000 + e.idx();
  for (auto f : m.faces()) m.property(fp, f) = 3000 + f.idx();
  const std::size_t nv0 = m.n_vertices();
  SD sd;
  if (!sd(m, 1)) {
    why = sd.message();
    return false;
  }
  for (auto v : m.vertices()) {
    const int want = static_cast<std::size_t>(v.idx()) < nv0 ? 1000 + v.idx() : 0;
    if (m.property(vp, v) != want) {
      why = "vertex " + std::to_string(v.idx());
      return false;
    }
  }
  for (auto f : m.faces()) {
    double cx = 0, cy = 0, k = 0;
    for (auto v : m.fv_range(f)) cx += m.point(v)[0], cy += m.point(v)[1], k += 1;
    cx /= k, cy /= k;
    int want = -1;
    for (auto g : m0.faces())
      if (inside(m0, g, cx, cy)) want = want == -1 ? 3000 + g.idx() : -2;
    if (want < 0 || m.property(fp, f) != want) {
      why = "face " + std::to_string(f.idx()) + " has " + std::to_string(m.property(fp, f)) + ", its centroid's face " + std::to_string(want);
      return false;
    }
  }
  std::size_t inherited = 0;
  for (auto e : m.edges()) {
    auto h = m.halfedge_handle(e, 0);
    auto a = m.from_vertex_handle(h), b = m.to_vertex_handle(h);
    if (static_cast<std::size_t>(a.idx()) >= nv0) std::swap(a, b);
    int want = 0;
    if (static_cast<std::size_t>(a.idx()) < nv0 && static_cast<std::size_t>(b.idx()) >= nv0) {
      const auto pa = m0.point(a), pe = m.point(b);
      const typename M::Point q(2 * pe[0] - pa[0], 2 * pe[1] - pa[1], 2 * pe[2] - pa[2]);
      for (auto v : m0.vertices())
        if (m0.point(v) == q) {
          auto hh = m0.find_halfedge(a, v);
          if (hh.is_valid()) want = 2000 + m0.edge_handle(hh).idx();
        }
    }
    if (m.property(ep, e) != want) {
      why = "edge " + std::to_string(e.idx()) + " has " + std::to_string(m.property(ep, e)) + ", wanted " + std::to_string(want);
      return false;
    }
    inherited += want != 0;
  }
  if (inherited != 2 * m0.n_edges()) {
    why = std::to_string(inherited) + " inheriting edges, not 2 per input edge";
    return false;
  }
  return true;
}

/// The face and edge properties of `m` as arrays.
template <class M>
static std::pair<std::vector<int>, std::vector<int>> fe_props(const M& m, OpenMesh::FPropHandleT<int> fp, OpenMesh::EPropHandleT<int> ep) {
  std::pair<std::vector<int>, std::vector<int>> r;
  for (auto f : m.faces()) r.first.push_back(m.property(fp, f));
  for (auto e : m.edges()) r.second.push_back(m.property(ep, e));
  return r;
}

/// `levels` levels of SD on m0 with face and edge properties set; their arrays after.
template <class M, class SD>
static std::pair<std::vector<int>, std::vector<int>> props_after(const M& m0, unsigned levels, bool one_by_one, Flat* out = nullptr) {
  M m = m0;
  OpenMesh::EPropHandleT<int> ep;
  OpenMesh::FPropHandleT<int> fp;
  m.add_property(ep, "ep");
  m.add_property(fp, "fp");
  for (auto e : m.edges()) m.property(ep, e) = 2000 + e.idx();
  for (auto f : m.faces()) m.property(fp, f) = 3000 + f.idx();
  SD sd;
  bool ok = true;
  if (one_by_one)
    for (unsigned k = 0; k < levels; ++k) ok = ok && sd(m, 1);
  else
    ok = sd(m, levels);
  if (out) *out = flat_of(m);
  if (!ok) return {};
  return fe_props(m, fp, ep);
}

static void properties(itest::Tally& t) {
  const Tri tg = planar_grid<Tri>(3, true);
  const Poly qg = planar_grid<Poly>(3, false);
  std::string why;
  if (properties_one_level<Tri, nom::LinearLoopT<Tri>>(tg, why))
    t.pass("OpenMesh properties: LinearLoopT children inherit face and edge properties (from the geometry), old vertices keep theirs", 0);
  else
    t.fail("OpenMesh properties LinearLoopT: " + why);
  if (properties_one_level<Poly, nom::LinearCatmullClarkT<Poly>>(qg, why))
    t.pass("OpenMesh properties: LinearCatmullClarkT children inherit face and edge properties (from the geometry)", 0);
  else
    t.fail("OpenMesh properties LinearCatmullClarkT: " + why);
  // k levels at once = k calls of one level (the one-level rule verified above).
  const auto loop3 = props_after<Tri, nom::LinearLoopT<Tri>>(tg, 3, false), loop111 = props_after<Tri, nom::LinearLoopT<Tri>>(tg, 3, true);
  const auto cc2 = props_after<Poly, nom::LinearCatmullClarkT<Poly>>(qg, 2, false), cc11 = props_after<Poly, nom::LinearCatmullClarkT<Poly>>(qg, 2, true);
  auto inherits = [](const std::pair<std::vector<int>, std::vector<int>>& p) {
    return std::count(p.first.begin(), p.first.end(), 0) == 0 &&
           std::count_if(p.second.begin(), p.second.end(), [](int v) { return v != 0; }) > 0;
  };
  if (inherits(loop3) && loop3 == loop111 && inherits(cc2) && cc2 == cc11)
    t.pass("OpenMesh properties: k levels in one call = k calls of one level (Loop 3, Catmull-Clark 2)", 0);
  else
    t.fail("OpenMesh properties: multi-level inheritance differs from level-by-level");
  // The tier-1 classes and the differential classes (same connectivity and order as linear
  // Loop / Catmull-Clark, include/nlsubdiv.h) inherit as the linear bulk classes do.
  const Tri oct = octahedron<Tri>();
  const auto lin = props_after<Tri, nom::LinearLoopT<Tri>>(oct, 2, false);
  const auto star = props_after<Tri, nom::MobiusLoopT<Tri>>(oct, 2, false);
  const auto bulk = props_after<Tri, nom::MobiusLoopBulkT<Tri>>(oct, 2, false);
  const auto diff = props_after<Tri, nom::DifferentialLoopT<Tri>>(oct, 2, false);
  const auto ccl = props_after<Poly, nom::LinearCatmullClarkT<Poly>>(qg, 2, false);
  const auto ccs = props_after<Poly, nom::MobiusCatmullClarkT<Poly>>(qg, 2, false);
  if (inherits(lin) && star == lin && bulk == lin && diff == lin && inherits(ccl) && ccs == ccl)
    t.pass("OpenMesh properties: MobiusLoopT, MobiusLoopBulkT, DifferentialLoopT, MobiusCatmullClarkT inherit as the linear classes", 0);
  else
    t.fail("OpenMesh properties: tier-1 / bulk / differential inheritance differs from linear");
  // Doo-Sabin (dual): vertex properties reset to the default; the first faces are the input
  // faces shrunk (centroid inside the input face), the others hold the default.
  {
    Poly m = qg;
    OpenMesh::VPropHandleT<int> vp;
    OpenMesh::FPropHandleT<int> fp;
    m.add_property(vp, "vp");
    m.add_property(fp, "fp");
    for (auto v : m.vertices()) m.property(vp, v) = 7;
    for (auto f : m.faces()) m.property(fp, f) = 3000 + f.idx();
    nom::LinearDooSabinT<Poly> sd;
    bool ok = sd(m, 1), good = ok;
    for (auto v : m.vertices()) good = good && m.property(vp, v) == 0;
    for (auto f : m.faces()) {
      double cx = 0, cy = 0, k = 0;
      for (auto v : m.fv_range(f)) cx += m.point(v)[0], cy += m.point(v)[1], k += 1;
      int want = 0;
      for (auto g : qg.faces())
        if (static_cast<std::size_t>(f.idx()) < qg.n_faces() && inside(qg, g, cx / k, cy / k)) want = 3000 + g.idx();
      good = good && m.property(fp, f) == want;
    }
    if (good)
      t.pass("OpenMesh properties: Doo-Sabin resets vertex properties, its face-faces inherit", 0);
    else
      t.fail(std::string("OpenMesh properties Doo-Sabin: ") + (ok ? "wrong values" : sd.message()));
  }
}

int main(int argc, char** argv) {
  if (argc < 2) {
    std::fprintf(stderr, "usage: %s MESH_DIR\n", argv[0]);
    return 2;
  }
  const std::string dir = argv[1];
  itest::Tally t;
  auto t0 = std::chrono::steady_clock::now();
  const auto files = itest::off_files(dir);
  if (files.empty()) {
    std::printf("SKIP no meshes in %s\n", dir.c_str());
    ++t.skipped;
  }
  for (const auto& f : files) {
    const std::string path = dir + "/" + f;
    Poly pm;
    if (!load(path, pm) || pm.n_faces() != off_face_count(path)) {
      std::printf("skip %s: OpenMesh does not load it whole (%zu of %zu faces)\n", f.c_str(), pm.n_faces(), off_face_count(path));
      ++t.skipped;
      continue;
    }
    check_plugins(t, f, pm, "PolyMesh");
    const Flat fl = flat_of(pm);
    if (itest::all_faces(fl, 3) && pm.n_faces() <= 3000) check_differential(t, f, pm);
    if (itest::all_faces(fl, 3)) {
      Tri tm;
      if (load(path, tm) && tm.n_faces() == pm.n_faces()) {
        check_plugins(t, f, tm, "TriMesh");
        const uint32_t lv = tm.n_faces() <= 3000 ? 2 : 1;
        check_openmesh_peer<nom::LinearLoopT<Tri>, OpenMesh::Subdivider::Uniform::LoopT<Tri>>(t, f, tm, "LinearLoopT = OpenMesh LoopT", lv);
        check_openmesh_peer<nom::LinearButterflyT<Tri>, OpenMesh::Subdivider::Uniform::ModifiedButterflyT<Tri>>(
            t, f, tm, "LinearButterflyT = OpenMesh ModifiedButterflyT", lv);
      }
    }
    bool closed = true;
    for (auto v : pm.vertices()) closed = closed && !pm.is_boundary(v);
    if (closed)
      check_openmesh_peer<nom::LinearCatmullClarkT<Poly>, OpenMesh::Subdivider::Uniform::CatmullClarkT<Poly>>(
          t, f, pm, "LinearCatmullClarkT = OpenMesh CatmullClarkT (closed)", pm.n_faces() <= 3000 ? 2 : 1);
  }
  // Bad meshes, each in a child process.
  const auto bad = itest::off_files(dir + "/bad");
  if (bad.empty()) {
    std::printf("SKIP no meshes in %s/bad\n", dir.c_str());
    ++t.skipped;
  }
  int loaded = 0, refused = 0;
  for (const auto& f : bad) {
    int fds[2];
    if (pipe(fds) != 0) return 2;
    std::fflush(stdout);
    pid_t pid = fork();
    if (pid == 0) {
      close(fds[0]);
      std::printf("  bad/%s:\n", f.c_str());
      std::fflush(stdout);
      _exit(bad_child(dir + "/bad/" + f, fds[1], f.rfind("format_", 0) == 0));
    }
    close(fds[1]);
    char mark = 0;
    ssize_t got = read(fds[0], &mark, 1);
    close(fds[0]);
    int st = 0;
    waitpid(pid, &st, 0);
    if (got == 1 && mark == 'R') {
      ++t.skipped;
      continue;
    }
    if (got != 1 || mark != 'L') {
      std::printf("    OpenMesh cannot load it (%s)\n", WIFSIGNALED(st) ? "its reader aborted" : "read_mesh failed or empty");
      ++t.skipped;
      continue;
    }
    ++loaded;
    const bool valid = f.rfind("format_", 0) == 0;  // layout variants of a valid mesh (README of the meshes)
    if (WIFEXITED(st) && WEXITSTATUS(st) == 0) {
      if (!valid) ++refused;
      t.pass(valid ? "bad/format_* (valid layout variants) accepted" : "bad mesh refused (strict), unchanged, host alive", 0);
    } else {
      t.fail("bad/" + f + (WIFSIGNALED(st) ? ": the host process died" : valid ? ": a valid mesh was refused" : ": accepted or changed by a subdivider"));
    }
  }
  std::printf("bad meshes: %zu files, %d loaded as they are by OpenMesh (format_* included), %d broken ones refused by every subdivider with the mesh unchanged\n",
              bad.size(), loaded, refused);
  synthetic(t);
  differential_refuses_non_triangles(t);
  feature_creases(t);
  openmesh_interfaces_and_messages(t);
  spectrum_weight(t);
  spectrum_weight_property(t);
  threads(t);
  differential_edits(t);
  properties(t);
  for (const auto& w : t.worst) std::printf("  %-60s worst max_rel_dist %.3e\n", w.first.c_str(), w.second);
  double secs = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  std::printf("test_openmesh: %d passed, %d failed, %d skipped (%.1f s)\n", t.passed, t.failed, t.skipped, secs);
  return t.failed ? 1 : 0;
}
