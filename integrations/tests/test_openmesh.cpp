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
/// driver's tagged call; no feature is the untagged result; a Möbius subdivider with features
/// is refused (NLS_STATUS_TAGS_NOT_SUPPORTED) with the mesh unchanged.
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
  // Schemes without tag rules refuse a mesh with features, unchanged.
  Poly d = cube;
  nom::MobiusCatmullClarkBulkT<Poly> mob;
  mob.set_feature_creases(true);
  const bool refused = !mob(d, 1) && mob.status() == NLS_STATUS_TAGS_NOT_SUPPORTED && flat_of(d) == flat_of(cube);
  Poly e = cube;
  nom::LinearCatmullClarkT<Poly> per_level;
  per_level.set_feature_creases(true);
  const bool refused2 = !per_level(e, 1, false) && per_level.status() == NLS_STATUS_INVALID_ARGUMENT;
  if (refused && refused2)
    t.pass("features refused by Möbius subdividers and by per-level calls, mesh unchanged", 0);
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
  for (const auto& w : t.worst) std::printf("  %-60s worst max_rel_dist %.3e\n", w.first.c_str(), w.second);
  double secs = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  std::printf("test_openmesh: %d passed, %d failed, %d skipped (%.1f s)\n", t.passed, t.failed, t.skipped, secs);
  return t.failed ? 1 : 0;
}
