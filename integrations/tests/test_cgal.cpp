// Integration test of integrations/cgal/nlsubdiv_cgal.h against Debian's CGAL 5.5:
//
//   test_cgal MESH_DIR
//
// 1. every free function equals the driver (same scheme and flags, same flat copy of the
//    mesh), order-independent, <= 1e-12 relative, on every mesh of MESH_DIR that CGAL's OFF
//    reader loads whole into a Surface_mesh (1 or 2 levels by size); where the driver refuses
//    a mesh, the function must refuse it with the same status and leave it unchanged;
//    the differential functions equal the differential driver on the triangle meshes of
//    <= 3000 faces, refuse non-triangles and report NOT_CONVERGED (max_iterations = 1);
// 2. Mobius_loop_mask_3 (PTQ, 2 iterations) and Mobius_catmull_clark_mask_3 (PQQ, per host
//    level: the driver on the host's own level-1 mesh) driven by CGAL's own hosts (PTQ,
//    PQQ with number_of_iterations(2)) equal the driver too, and the functions work on
//    Polyhedron_3;
// 3. every mesh of MESH_DIR/bad that CGAL loads as it is (child process) is refused by every
//    function in strict mode with the mesh unchanged, and the process survives.
// Last line: "test_cgal: N passed, M failed, K skipped".
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/IO/OFF.h>
#include <CGAL/Polyhedron_3.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/boost/graph/IO/OFF.h>
#include <CGAL/subdivision_method_3.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cmath>
#include <functional>
#include <iostream>
#include <sstream>

#include <nlsubdiv/cgal/nlsubdiv_cgal.h>  // installed header (scripts/install.sh)
#include "common.hpp"

typedef CGAL::Exact_predicates_inexact_constructions_kernel K;
typedef CGAL::Surface_mesh<K::Point_3> SM;
typedef CGAL::Polyhedron_3<K> Poly;
namespace nc = nlsubdiv::cgal;
using itest::Flat;

template <class PM>
Flat flat_of(const PM& pm) {
  nc::detail::Level<PM> lv;
  lv.build(pm, get(CGAL::vertex_point, pm), SIZE_MAX);
  Flat r;
  r.pos = lv.flat.positions;
  r.off = lv.flat.offsets;
  r.idx = lv.flat.indices;
  return r;
}

template <class PM>
struct Fn {
  std::string name;
  uint32_t scheme, flags;
  std::function<nc::Report(PM&, unsigned, nc::Options)> run;
};

#define FN(f, s, fl) \
  Fn<PM> { #f, s, fl, [](PM& m, unsigned n, nc::Options o) { return nc::f(m, CGAL::parameters::number_of_iterations(n), o); } }

template <class PM>
std::vector<Fn<PM>> functions() {
  const uint32_t M = NLS_SUBDIVIDE_MOBIUS;
  // Loop and Butterfly run as masks in CGAL's own PTQ host, evaluating the star rules: the
  // paper's rules (the fold guard needs the driver's whole-mesh pass), so their reference is
  // the driver's literal mode.
  const uint32_t L = NLS_SUBDIVIDE_MOBIUS | NLS_SUBDIVIDE_LITERAL;
  return {FN(mobius_loop_subdivision, NLS_SCHEME_LOOP, L),
          FN(mobius_butterfly_subdivision, NLS_SCHEME_MODIFIED_BUTTERFLY, L),
          FN(mobius_catmull_clark_subdivision, NLS_SCHEME_CATMULL_CLARK, M),
          FN(mobius_kobbelt_subdivision, NLS_SCHEME_KOBBELT, M),
          FN(mobius_doo_sabin_subdivision, NLS_SCHEME_DOO_SABIN, M),
          FN(mobius_simplest_subdivision, NLS_SCHEME_SIMPLEST, M),
          FN(mobius_dual_subdivision, NLS_SCHEME_DUAL, M),
          FN(mobius_vertex_insertion_subdivision, NLS_SCHEME_VERTEX_INSERTION, M),
          FN(mobius_dual_truncation_subdivision, NLS_SCHEME_DUAL_TRUNCATION, M),
          FN(loop_subdivision, NLS_SCHEME_LOOP, 0),
          FN(catmull_clark_subdivision, NLS_SCHEME_CATMULL_CLARK, 0),
          FN(butterfly_subdivision, NLS_SCHEME_MODIFIED_BUTTERFLY, 0),
          FN(kobbelt_subdivision, NLS_SCHEME_KOBBELT, 0),
          FN(doo_sabin_subdivision, NLS_SCHEME_DOO_SABIN, 0),
          FN(spherelike_subdivision, NLS_SCHEME_SPHERELIKE, 0)};
}

static const double TOL = 1e-12;

static std::size_t off_counts(const std::string& path, std::size_t& nv) {
  FILE* f = std::fopen(path.c_str(), "r");
  if (!f) return 0;
  char line[4096];
  bool header = false;
  std::size_t nf = 0;
  nv = 0;
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
      return nf;
    }
  }
  std::fclose(f);
  return 0;
}

template <class PM>
bool load(const std::string& path, PM& pm) {
  std::streambuf* old = std::cerr.rdbuf(nullptr);
  bool ok = CGAL::IO::read_OFF(path, pm);
  std::cerr.rdbuf(old);
  std::size_t nv = 0, nf = off_counts(path, nv);
  return ok && num_vertices(pm) == nv && num_faces(pm) == nf && nf > 0;
}

template <class PM>
void check_functions(itest::Tally& t, const std::string& mesh, const PM& pm0, const std::string& tag) {
  const Flat in = flat_of(pm0);
  const unsigned levels = num_faces(pm0) <= 3000 ? 2 : 1;
  for (auto& fn : functions<PM>()) {
    Flat ref;
    nls_status ds = itest::driver(fn.scheme, fn.flags, in, levels, ref);
    PM pm = pm0;
    nc::Report r = fn.run(pm, levels, nc::Options());
    const std::string where = fn.name + "<" + tag + "> on " + mesh + " (" + std::to_string(levels) + " levels)";
    if (ds != NLS_STATUS_OK) {
      if (!r.ok() && r.status == ds && flat_of(pm) == in)
        t.pass(fn.name + "<" + tag + "> refuses what the driver refuses", 0);
      else
        t.fail(where + ": driver says " + nls_status_str(ds) + ", function " + r.message());
      continue;
    }
    if (!r.ok()) {
      t.fail(where + ": refused (" + r.message() + ") but the driver accepts");
      continue;
    }
    itest::Cmp c = itest::compare(flat_of(pm), ref);
    if (c.ok(TOL))
      t.pass(fn.name + "<" + tag + "> = driver [" + r.path + "]", c.max_rel);
    else
      t.fail(where + ": " + c.summary());
    if (std::getenv("NLS_ITEST_VERBOSE")) std::printf("  %s: %s\n", where.c_str(), c.summary().c_str());
  }
}

/// The masks driven by CGAL's own hosts over two iterations.
static void check_masks_with_cgal_hosts(itest::Tally& t, const std::string& mesh, const SM& pm0) {
  const Flat in = flat_of(pm0);
  {
    Flat ref;
    if (itest::driver(NLS_SCHEME_LOOP, NLS_SUBDIVIDE_MOBIUS | NLS_SUBDIVIDE_LITERAL, in, 2, ref) == NLS_STATUS_OK) {
      SM pm = pm0;
      nc::Mobius_loop_mask_3<SM> mask(&pm, get(CGAL::vertex_point, pm));
      CGAL::Subdivision_method_3::PTQ(pm, mask, CGAL::parameters::number_of_iterations(2));
      itest::Cmp c = itest::compare(flat_of(pm), ref);
      if (mask.report().ok() && c.ok(TOL))
        t.pass("Mobius_loop_mask_3 in CGAL's PTQ (2 iterations) = driver", c.max_rel);
      else
        t.fail("Mobius_loop_mask_3 in PTQ on " + mesh + ": " + mask.report().message() + " " + c.summary());
    }
  }
  {
    Flat ref;
    if (itest::driver(NLS_SCHEME_CATMULL_CLARK, NLS_SUBDIVIDE_MOBIUS, in, 2, ref) == NLS_STATUS_OK) {
      // The mask's contract: each host step is the driver's level of the host's mesh as the
      // host numbers it (the face-point tie-break is by vertex id, and CGAL numbers refined
      // levels its own way), so level 2 is compared with the driver run on CGAL's level 1.
      SM pm = pm0;
      nc::Mobius_catmull_clark_mask_3<SM> mask(&pm, get(CGAL::vertex_point, pm));
      CGAL::Subdivision_method_3::PQQ(pm, mask, CGAL::parameters::number_of_iterations(1));
      Flat ref1, ref2;
      const Flat host1 = flat_of(pm);
      const bool ok1 = mask.report().ok() && itest::driver(NLS_SCHEME_CATMULL_CLARK, NLS_SUBDIVIDE_MOBIUS, in, 1, ref1) == NLS_STATUS_OK;
      itest::Cmp c1 = itest::compare(host1, ref1);
      nc::Mobius_catmull_clark_mask_3<SM> mask2(&pm, get(CGAL::vertex_point, pm));
      mask2.set_previous_vertex_count(in.nv());
      CGAL::Subdivision_method_3::PQQ(pm, mask2, CGAL::parameters::number_of_iterations(1));
      const bool ok2 = mask2.report().ok() && itest::driver(NLS_SCHEME_CATMULL_CLARK, NLS_SUBDIVIDE_MOBIUS, host1, 1, ref2) == NLS_STATUS_OK;
      itest::Cmp c2 = itest::compare(flat_of(pm), ref2);
      if (ok1 && ok2 && c1.ok(TOL) && c2.ok(TOL))
        t.pass("Mobius_catmull_clark_mask_3 in CGAL's PQQ (2 iterations) = driver per host level", std::max(c1.max_rel, c2.max_rel));
      else
        t.fail("Mobius_catmull_clark_mask_3 in PQQ on " + mesh + ": " + mask2.report().message() + " level 1 " + c1.summary() + " level 2 " + c2.summary());
    }
  }
  // Our linear Loop equals CGAL's own Loop_subdivision (peer-rules.md: same boundary rules).
  {
    SM a = pm0, b = pm0;
    nc::Report r = nc::loop_subdivision(a, CGAL::parameters::number_of_iterations(2));
    if (r.ok()) {
      CGAL::Subdivision_method_3::Loop_subdivision(b, CGAL::parameters::number_of_iterations(2));
      itest::Cmp c = itest::compare(flat_of(a), flat_of(b));
      if (c.ok(TOL))
        t.pass("loop_subdivision = CGAL Loop_subdivision", c.max_rel);
      else
        t.fail("loop_subdivision vs CGAL Loop_subdivision on " + mesh + ": " + c.summary());
    }
  }
}

/// The differential functions against the differential driver on a triangle mesh (<= 3000
/// faces; 2 levels up to 400 faces, else 1); max_iterations = 1 -> NOT_CONVERGED, unchanged.
template <class PM>
void check_differential(itest::Tally& t, const std::string& mesh, const PM& pm0) {
  const Flat in = flat_of(pm0);
  const unsigned levels = num_faces(pm0) <= 400 ? 2 : 1;
  typedef std::function<nc::Report(PM&, unsigned, nc::DifferentialOptions)> F;
  struct S {
    const char* name;
    uint32_t stencil;
    F run;
  };
  const S cases[] = {
      {"differential_loop_subdivision", NLS_DIFFERENTIAL_LOOP,
       [](PM& m, unsigned n, nc::DifferentialOptions o) { return nc::differential_loop_subdivision(m, CGAL::parameters::number_of_iterations(n), o); }},
      {"differential_butterfly_subdivision", NLS_DIFFERENTIAL_BUTTERFLY,
       [](PM& m, unsigned n, nc::DifferentialOptions o) { return nc::differential_butterfly_subdivision(m, CGAL::parameters::number_of_iterations(n), o); }},
      {"differential_dirmag_subdivision", NLS_DIFFERENTIAL_DIRMAG,
       [](PM& m, unsigned n, nc::DifferentialOptions o) { return nc::differential_dirmag_subdivision(m, CGAL::parameters::number_of_iterations(n), o); }}};
  for (const S& c : cases) {
    const std::string where = std::string(c.name) + " on " + mesh + " (" + std::to_string(levels) + " levels)";
    const uint32_t dm = c.stencil == NLS_DIFFERENTIAL_DIRMAG ? 1 : 0;
    Flat ref;
    nls_differential_report drep{};
    nls_status ds = itest::driver_differential(c.stencil, dm, 100, 1e-10, in, levels, ref, drep);
    PM pm = pm0;
    nc::Report r = c.run(pm, levels, nc::DifferentialOptions());
    if (ds != NLS_STATUS_OK) {
      if (!r.ok() && r.status == ds && flat_of(pm) == in)
        t.pass(std::string(c.name) + " refuses what the driver refuses", 0);
      else
        t.fail(where + ": driver says " + nls_status_str(ds) + ", function " + r.message());
    } else if (!r.ok()) {
      t.fail(where + ": refused (" + r.message() + ") but the driver accepts");
    } else {
      itest::Cmp cmp = itest::compare(flat_of(pm), ref);
      if (cmp.ok(TOL) && r.iterations == drep.iterations && r.residual == drep.relative_residual)
        t.pass(std::string(c.name) + " = differential driver", cmp.max_rel);
      else
        t.fail(where + ": " + cmp.summary() + " iterations " + std::to_string(r.iterations) + " vs " + std::to_string(drep.iterations));
    }
    Flat r1;
    nls_differential_report rep1{};
    nls_status d1 = itest::driver_differential(c.stencil, dm, 1, 0.0, in, levels, r1, rep1);
    PM pm1 = pm0;
    nc::DifferentialOptions o1;
    o1.max_iterations = 1;
    o1.tolerance = 0.0;
    nc::Report q = c.run(pm1, levels, o1);
    if (d1 == NLS_STATUS_NOT_CONVERGED && q.status == NLS_STATUS_NOT_CONVERGED && flat_of(pm1) == in && q.iterations == rep1.iterations)
      t.pass(std::string(c.name) + ": max_iterations = 1 -> NOT_CONVERGED, mesh unchanged", 0);
    else
      t.fail(where + " max_iterations 1: driver " + nls_status_str(d1) + ", function " + q.message() + (flat_of(pm1) == in ? "" : ", mesh changed"));
  }
}

/// The differential functions refuse a mesh with a quad (the face named), unchanged.
static void differential_refuses_non_triangles(itest::Tally& t) {
  SM m;
  std::vector<SM::Vertex_index> v;
  for (int k = 0; k < 6; ++k) v.push_back(m.add_vertex(K::Point_3(k % 3, k / 3, 0.1 * k)));
  m.add_face(v[0], v[1], v[4]);
  m.add_face(v[0], v[4], v[3]);
  m.add_face(v[1], v[2], v[5], v[4]);
  const Flat before = flat_of(m);
  const nc::Report rs[] = {nc::differential_loop_subdivision(m), nc::differential_butterfly_subdivision(m), nc::differential_dirmag_subdivision(m)};
  for (const nc::Report& r : rs)
    if (r.status == NLS_STATUS_UNSUPPORTED_FACE_TYPE && r.element == 2 && flat_of(m) == before)
      t.pass("differential_*_subdivision refuse a quad (face named), mesh unchanged", 0);
    else
      t.fail("differential function on a mesh with a quad: " + r.message());
}

static int bad_child(const std::string& path, int fd, bool valid) {
  SM pm0;
  if (!load(path, pm0)) {
    if (write(fd, "N", 1) != 1) return 4;
    return 3;
  }
  if (write(fd, "L", 1) != 1) return 4;
  const Flat before = flat_of(pm0);
  int bad = 0;
  for (auto& fn : functions<SM>()) {
    SM pm = pm0;
    nc::Options o;
    o.strict = !valid;
    nc::Report r = fn.run(pm, 1, o);
    bool same = flat_of(pm) == before;
    std::printf("    %-38s %s%s\n", fn.name.c_str(), r.ok() ? "accepted" : r.message().c_str(), r.ok() ? "" : same ? ", mesh unchanged" : " MESH CHANGED");
    if (valid ? !(r.ok() || (r.status == NLS_STATUS_UNSUPPORTED_FACE_TYPE && same)) : (r.ok() || !same)) ++bad;
  }
  std::fflush(stdout);
  return bad ? 1 : 0;
}

/// Sharp features through the named parameters edge_is_constrained_map (creases) and
/// vertex_is_constrained_map (corners): a unit cube with all twelve edges constrained equals
/// the C driver's tagged call with the same edges given as vertex pairs, keeps its corners
/// and has 12 (2^k - 1) + 8 vertices on its edge lines after k = 2 levels of Catmull-Clark;
/// one constrained corner stays put under Loop on an octahedron; Möbius Catmull-Clark with
/// the same edges equals the driver's tagged Möbius call and keeps the edge lines, Möbius
/// Loop keeps a constrained corner; Doo-Sabin with a constrained edge is refused
/// (NLS_STATUS_TAGS_NOT_SUPPORTED), mesh unchanged.
static void sharp_features(itest::Tally& t) {
  static const double P[8][3] = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, {0, 0, 1}, {1, 0, 1}, {1, 1, 1}, {0, 1, 1}};
  static const int F[6][4] = {{0, 3, 2, 1}, {4, 5, 6, 7}, {0, 1, 5, 4}, {1, 2, 6, 5}, {2, 3, 7, 6}, {3, 0, 4, 7}};
  SM cube;
  std::vector<SM::Vertex_index> vh;
  for (auto& p : P) vh.push_back(cube.add_vertex(K::Point_3(p[0], p[1], p[2])));
  for (auto& f : F) cube.add_face(vh[f[0]], vh[f[1]], vh[f[2]], vh[f[3]]);
  const Flat in = flat_of(cube);
  // The driver, with the twelve edges typed as vertex pairs (the cube's vertex indices).
  static const uint32_t E[24] = {0, 1, 1, 2, 2, 3, 3, 0, 4, 5, 5, 6, 6, 7, 7, 4, 0, 4, 1, 5, 2, 6, 3, 7};
  static const double S[12] = {10, 10, 10, 10, 10, 10, 10, 10, 10, 10, 10, 10};
  nls_tags tags{};
  tags.crease_vertices = E;
  tags.crease_sharpness = S;
  tags.crease_count = 12;
  nlsubdiv::flat::FlatMesh fin, want;
  fin.positions = in.pos;
  fin.offsets = in.off;
  fin.indices = in.idx;
  uint32_t el = 0, fb = 0;
  const nls_status ds = nlsubdiv::flat::run_levels(NLS_SCHEME_CATMULL_CLARK, 0, fin, 2, want, el, fb, &tags);
  SM a = cube;
  auto ecm = a.add_property_map<SM::Edge_index, bool>("e:sharp", true).first;
  nc::Report r = nc::catmull_clark_subdivision(a, CGAL::parameters::number_of_iterations(2).edge_is_constrained_map(ecm));
  Flat got = flat_of(a), ref;
  ref.pos = want.positions;
  ref.off = want.offsets;
  ref.idx = want.indices;
  itest::Cmp c = itest::compare(got, ref);
  std::size_t on_edges = 0;
  bool corners_kept = got.nv() >= 8;
  for (std::size_t v = 0; v < got.nv(); ++v) {
    int n = 0;
    for (int k = 0; k < 3; ++k) n += (std::fabs(got.pos[3 * v + k]) <= 1e-15 || std::fabs(got.pos[3 * v + k] - 1.0) <= 1e-15);
    on_edges += n >= 2;
    if (v < 8)
      for (int k = 0; k < 3; ++k) corners_kept = corners_kept && got.pos[3 * v + k] == P[v][k];
  }
  if (ds == NLS_STATUS_OK && r.ok() && c.ok(0.0) && on_edges == 12 * 3 + 8 && corners_kept)
    t.pass("CGAL edge_is_constrained_map = driver tags (sharp cube keeps its edges and corners)", c.max_rel);
  else
    t.fail(std::string("CGAL sharp features: ") + r.message() + "; " + c.summary() + " on_edges=" + std::to_string(on_edges) +
           (corners_kept ? "" : " corners moved"));
  // A constrained corner under Loop: octahedron, vertex 4 kept bit for bit.
  auto make_oct = [] {
    static const double Q[6][3] = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
    static const int T[8][3] = {{0, 2, 4}, {2, 1, 4}, {1, 3, 4}, {3, 0, 4}, {2, 0, 5}, {1, 2, 5}, {3, 1, 5}, {0, 3, 5}};
    SM m;
    std::vector<SM::Vertex_index> oh;
    for (auto& q : Q) oh.push_back(m.add_vertex(K::Point_3(q[0], q[1], q[2])));
    for (auto& f : T) m.add_face(oh[f[0]], oh[f[1]], oh[f[2]]);
    return m;
  };
  SM oct = make_oct();
  auto vcm = oct.add_property_map<SM::Vertex_index, bool>("v:corner", false).first;
  put(vcm, SM::Vertex_index(4), true);
  nc::Report r2 = nc::loop_subdivision(oct, CGAL::parameters::number_of_iterations(3).vertex_is_constrained_map(vcm));
  const auto p4 = oct.point(SM::Vertex_index(4)), p5 = oct.point(SM::Vertex_index(5));
  if (r2.ok() && p4.x() == 0 && p4.y() == 0 && p4.z() == 1 && p5.z() != -1)
    t.pass("CGAL vertex_is_constrained_map corner kept, the free apex moves", 0);
  else
    t.fail(std::string("CGAL corner: ") + r2.message());
  // Möbius Catmull-Clark with the twelve constrained edges: the driver's tagged Möbius call
  // (every vertex a corner: each face refined alone, its edges open Möbius curves of
  // collinear points, so the edge lines stay); Möbius Loop keeps a constrained corner.
  SM b = cube;
  auto ecm2 = b.add_property_map<SM::Edge_index, bool>("e:sharp", true).first;
  nc::Report r3 = nc::mobius_catmull_clark_subdivision(b, CGAL::parameters::number_of_iterations(2).edge_is_constrained_map(ecm2));
  nlsubdiv::flat::FlatMesh mwant;
  const nls_status ms = nlsubdiv::flat::run_levels(NLS_SCHEME_CATMULL_CLARK, NLS_SUBDIVIDE_MOBIUS, fin, 2, mwant, el, fb, &tags);
  Flat mgot = flat_of(b), mref;
  mref.pos = mwant.positions;
  mref.off = mwant.offsets;
  mref.idx = mwant.indices;
  itest::Cmp mc = itest::compare(mgot, mref);
  std::size_t mon = 0;
  for (std::size_t v = 0; v < mgot.nv(); ++v) {
    int n = 0;
    for (int k = 0; k < 3; ++k) n += (std::fabs(mgot.pos[3 * v + k]) <= 1e-12 || std::fabs(mgot.pos[3 * v + k] - 1.0) <= 1e-12);
    mon += n >= 2;
  }
  // An octahedron made irregular (vertex 5 moved), so that no symmetry keeps vertex 4.
  SM d = make_oct();
  d.point(SM::Vertex_index(5)) = K::Point_3(0.1, 0.05, -0.9);
  SM d_plain = d;
  auto vcm2 = d.add_property_map<SM::Vertex_index, bool>("v:corner", false).first;
  put(vcm2, SM::Vertex_index(4), true);
  nc::Report r4 = nc::mobius_loop_subdivision(d, CGAL::parameters::number_of_iterations(2).vertex_is_constrained_map(vcm2));
  nc::Report r4p = nc::mobius_loop_subdivision(d_plain, CGAL::parameters::number_of_iterations(2));
  const auto q4 = d.point(SM::Vertex_index(4)), w4 = d_plain.point(SM::Vertex_index(4));
  const bool kept = q4.x() == 0 && q4.y() == 0 && q4.z() == 1, moved = !(w4.x() == 0 && w4.y() == 0 && w4.z() == 1);
  if (ms == NLS_STATUS_OK && r3.ok() && mc.ok(0.0) && mon == 12 * 3 + 8 && r4.ok() && r4p.ok() && kept && moved)
    t.pass("CGAL Möbius functions take constrained edges (= driver tags) and corners", mc.max_rel);
  else
    t.fail(std::string("CGAL Möbius with features: ") + r3.message() + "; " + mc.summary() + " on_edges=" + std::to_string(mon) +
           " / " + r4.message());
  // Per-element sharpness through nlsubdiv's edge_sharpness_map / vertex_sharpness_map:
  // the top face's edges infinitely sharp, one vertical edge 1.5, vertex 0 a corner of 2.5
  // = the driver with the same tags; a NaN value is refused, mesh unchanged.
  {
    SM g = cube;
    auto esm = g.add_property_map<SM::Edge_index, double>("e:sharpness", 0.0).first;
    auto vsm = g.add_property_map<SM::Vertex_index, double>("v:sharpness", 0.0).first;
    static const uint32_t GE[10] = {4, 5, 5, 6, 6, 7, 7, 4, 0, 4};
    static const double GS[5] = {10, 10, 10, 10, 1.5};
    auto edge_of = [&](uint32_t a, uint32_t b) { return g.edge(g.halfedge(SM::Vertex_index(a), SM::Vertex_index(b))); };
    for (int k = 0; k < 5; ++k) put(esm, edge_of(GE[2 * k], GE[2 * k + 1]), GS[k]);
    put(vsm, SM::Vertex_index(0), 2.5);
    nls_tags gt{};
    static const uint32_t GV[1] = {0};
    static const double GVS[1] = {2.5};
    gt.crease_vertices = GE;
    gt.crease_sharpness = GS;
    gt.crease_count = 5;
    gt.corner_vertices = GV;
    gt.corner_sharpness = GVS;
    gt.corner_count = 1;
    nlsubdiv::flat::FlatMesh gwant;
    const nls_status gs = nlsubdiv::flat::run_levels(NLS_SCHEME_CATMULL_CLARK, 0, fin, 2, gwant, el, fb, &gt);
    nc::Report rg = nc::catmull_clark_subdivision(
        g, nlsubdiv::parameters::number_of_iterations(2).edge_sharpness_map(esm).vertex_sharpness_map(vsm));
    Flat ggot = flat_of(g), gref;
    gref.pos = gwant.positions;
    gref.off = gwant.offsets;
    gref.idx = gwant.indices;
    itest::Cmp gc = itest::compare(ggot, gref);
    SM h = cube;
    auto hsm = h.add_property_map<SM::Edge_index, double>("e:sharpness", 0.0).first;
    put(hsm, *CGAL::edges(h).begin(), std::nan(""));
    nc::Report rh = nc::catmull_clark_subdivision(h, nlsubdiv::parameters::number_of_iterations(1).edge_sharpness_map(hsm));
    if (gs == NLS_STATUS_OK && rg.ok() && gc.ok(0.0) && rh.status == NLS_STATUS_INVALID_SHARPNESS && flat_of(h) == in)
      t.pass("CGAL edge_sharpness_map / vertex_sharpness_map = driver tags (semi-sharp, corner); NaN refused", gc.max_rel);
    else
      t.fail(std::string("CGAL sharpness maps: ") + rg.message() + "; " + gc.summary() + " / NaN: " + rh.message());
  }
  // A scheme without tag rules refuses, mesh unchanged.
  SM e = cube;
  auto ecm3 = e.add_property_map<SM::Edge_index, bool>("e:sharp", true).first;
  nc::Report r5 = nc::mobius_doo_sabin_subdivision(e, CGAL::parameters::number_of_iterations(1).edge_is_constrained_map(ecm3));
  if (r5.status == NLS_STATUS_TAGS_NOT_SUPPORTED && flat_of(e) == in)
    t.pass("CGAL Doo-Sabin refuses constrained edges, mesh unchanged", 0);
  else
    t.fail(std::string("CGAL Doo-Sabin with features: ") + r5.message());
}

// ---- CGAL-style entry points (nlsubdiv::Subdivision_method_3) ----
namespace SM3 = nlsubdiv::Subdivision_method_3;
namespace NP = nlsubdiv::parameters;

/// Runs a new-style call: its Report through the named parameter report(r); a thrown
/// Subdivision_error must carry the same Report and only when it is not ok.
template <class F>
nc::Report call_new(F f, bool* consistent = nullptr) {
  nc::Report r;
  bool ok = true;
  try {
    f(r);
    ok = r.ok();
  } catch (const SM3::Subdivision_error& e) {
    ok = !r.ok() && e.status() == r.status && e.element() == r.element && e.level() == r.level && std::string(e.what()) == r.message();
  }
  if (consistent) *consistent = ok;
  return r;
}

template <class PM>
struct NewFn {
  std::string name;
  std::function<nc::Report(PM&, unsigned)> old_fn;
  std::function<void(PM&, unsigned, nc::Report&)> new_fn;
};

#define NEWFN(oldf, newf, extra)                                                                                   \
  NewFn<PM> {                                                                                                      \
    #newf, [](PM& m, unsigned n) { return nc::oldf(m, CGAL::parameters::number_of_iterations(n)); },               \
        [](PM& m, unsigned n, nc::Report& r) { SM3::newf(m, NP::number_of_iterations(n) extra.report(r)); } \
  }

template <class PM>
std::vector<NewFn<PM>> new_functions() {
  return {NEWFN(mobius_loop_subdivision, Mobius_Loop_subdivision, .literal(true)),
          NEWFN(mobius_butterfly_subdivision, Mobius_Butterfly_subdivision, .literal(true)),
          NEWFN(mobius_catmull_clark_subdivision, Mobius_CatmullClark_subdivision, ),
          NEWFN(mobius_kobbelt_subdivision, Mobius_Kobbelt_subdivision, ),
          NEWFN(mobius_doo_sabin_subdivision, Mobius_DooSabin_subdivision, ),
          NEWFN(mobius_simplest_subdivision, Mobius_Simplest_subdivision, ),
          NEWFN(mobius_dual_subdivision, Mobius_Dual_subdivision, ),
          NEWFN(mobius_vertex_insertion_subdivision, Mobius_VertexInsertion_subdivision, ),
          NEWFN(mobius_dual_truncation_subdivision, Mobius_DualTruncation_subdivision, ),
          NEWFN(loop_subdivision, Loop_subdivision, ),
          NEWFN(catmull_clark_subdivision, CatmullClark_subdivision, ),
          NEWFN(butterfly_subdivision, Butterfly_subdivision, ),
          NEWFN(kobbelt_subdivision, Kobbelt_subdivision, ),
          NEWFN(doo_sabin_subdivision, DooSabin_subdivision, ),
          NEWFN(simplest_subdivision, Simplest_subdivision, ),
          NEWFN(dual_subdivision, Dual_subdivision, ),
          NEWFN(vertex_insertion_subdivision, VertexInsertion_subdivision, ),
          NEWFN(dual_truncation_subdivision, DualTruncation_subdivision, ),
          NEWFN(spherelike_subdivision, Spherelike_subdivision, ),
          NEWFN(differential_loop_subdivision, Differential_Loop_subdivision, ),
          NEWFN(differential_butterfly_subdivision, Differential_Butterfly_subdivision, ),
          NEWFN(differential_dirmag_subdivision, Differential_DirMag_subdivision, )};
}

/// Every new name equals its deprecated name bit for bit (same positions, same faces in the
/// same order), or both refuse with the same status, element and level, mesh unchanged.
template <class PM>
void new_names_equal_old(itest::Tally& t, const std::string& mesh, const PM& pm0, unsigned levels) {
  const Flat in = flat_of(pm0);
  for (auto& fn : new_functions<PM>()) {
    PM a = pm0, b = pm0;
    nc::Report ra = fn.old_fn(a, levels);
    bool consistent = false;
    nc::Report rb = call_new([&](nc::Report& r) { fn.new_fn(b, levels, r); }, &consistent);
    const std::string where = "SM3::" + fn.name + " on " + mesh;
    const bool same_report = ra.status == rb.status && ra.element == rb.element && ra.level == rb.level && ra.fallbacks == rb.fallbacks;
    if (consistent && same_report && flat_of(a) == flat_of(b) && (ra.ok() || flat_of(b) == in))
      t.pass("SM3::*_subdivision = deprecated name bit for bit (or the same refusal)", 0);
    else
      t.fail(where + ": old " + ra.message() + ", new " + rb.message() + (consistent ? "" : " (exception inconsistent)") +
             (flat_of(a) == flat_of(b) ? "" : " (meshes differ)"));
  }
}

static SM make_octahedron() {
  static const double Q[6][3] = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
  static const int T[8][3] = {{0, 2, 4}, {2, 1, 4}, {1, 3, 4}, {3, 0, 4}, {2, 0, 5}, {1, 2, 5}, {3, 1, 5}, {0, 3, 5}};
  SM m;
  std::vector<SM::Vertex_index> oh;
  for (auto& q : Q) oh.push_back(m.add_vertex(K::Point_3(q[0], q[1], q[2])));
  for (auto& f : T) m.add_face(oh[f[0]], oh[f[1]], oh[f[2]]);
  return m;
}

static SM make_cube() {
  static const double P[8][3] = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, {0, 0, 1}, {1, 0, 1}, {1, 1, 1}, {0, 1, 1}};
  static const int F[6][4] = {{0, 3, 2, 1}, {4, 5, 6, 7}, {0, 1, 5, 4}, {1, 2, 6, 5}, {2, 3, 7, 6}, {3, 0, 4, 7}};
  SM cube;
  std::vector<SM::Vertex_index> vh;
  for (auto& p : P) vh.push_back(cube.add_vertex(K::Point_3(p[0], p[1], p[2])));
  for (auto& f : F) cube.add_face(vh[f[0]], vh[f[1]], vh[f[2]], vh[f[3]]);
  return cube;
}

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

/// The C ABI (nls_mesh_subdivide, or _tagged) with a spectrum weight.
static nls_status c_abi(uint32_t scheme, uint32_t flags, const Flat& in, uint32_t levels, Flat& out, double weight = 0.0,
                        const nls_tags* tags = nullptr) {
  nlsubdiv::flat::FlatMesh o;
  uint32_t el = 0, fb = 0;
  nls_status s = nlsubdiv::flat::run_levels(scheme, flags, to_fm(in), levels, o, el, fb, tags, weight);
  out = of_fm(o);
  return s;
}

/// Each named parameter has its effect, against the C ABI with the same options.
static void named_parameters(itest::Tally& t) {
  const SM oct = make_octahedron(), cube = make_cube();
  const Flat oin = flat_of(oct), cin = flat_of(cube);
  const uint32_t M = NLS_SUBDIVIDE_MOBIUS;
  auto exact = [](const SM& m, const Flat& ref) { return itest::compare(flat_of(m), ref).ok(0.0); };
  // number_of_iterations.
  {
    Flat r1, r3;
    c_abi(NLS_SCHEME_LOOP, 0, oin, 1, r1);
    c_abi(NLS_SCHEME_LOOP, 0, oin, 3, r3);
    SM a = oct, b = oct;
    SM3::Loop_subdivision(a);
    SM3::Loop_subdivision(b, NP::number_of_iterations(3));
    if (exact(a, r1) && exact(b, r3) && r1.nv() != r3.nv())
      t.pass("SM3 number_of_iterations: default 1 level, 3 levels = C ABI levels 3", 0);
    else
      t.fail("SM3 number_of_iterations");
  }
  // literal and the default fold guard (the bulk path; literal(true) alone: the star rules).
  {
    Flat g, l, lw;
    c_abi(NLS_SCHEME_LOOP, M, oin, 2, g);
    c_abi(NLS_SCHEME_LOOP, M | NLS_SUBDIVIDE_LITERAL, oin, 2, l);
    c_abi(NLS_SCHEME_LOOP, M | NLS_SUBDIVIDE_LITERAL, oin, 2, lw, 0.25);
    SM a = oct, b = oct, c = oct;
    nc::Report ra, rb, rc;
    SM3::Mobius_Loop_subdivision(a, NP::number_of_iterations(2).report(ra));
    SM3::Mobius_Loop_subdivision(b, NP::number_of_iterations(2).literal(true).report(rb));
    SM3::Mobius_Loop_subdivision(c, NP::literal(true).linear_weight(0.25).number_of_iterations(2).report(rc));
    if (exact(a, g) && std::string(ra.path) == "bulk" && itest::compare(flat_of(b), l).ok(TOL) && std::string(rb.path) == "star rules" &&
        exact(c, lw) && std::string(rc.path) == "bulk")
      t.pass("SM3 literal: default = C ABI guarded, literal(true) = C ABI NLS_SUBDIVIDE_LITERAL (star rules), with a weight = C ABI", 0);
    else
      t.fail(std::string("SM3 literal: paths ") + ra.path + "/" + rb.path + "/" + rc.path);
  }
  // linear_weight: 0 = Möbius, 1 = linear, bit for bit; 0.5 = the C ABI, strictly between;
  // 2 = NLS_STATUS_INVALID_ARGUMENT, mesh unchanged.
  {
    Flat half;
    c_abi(NLS_SCHEME_LOOP, M, oin, 2, half, 0.5);
    SM mob = oct, lin = oct, w0 = oct, w1 = oct, wh = oct, bad = oct;
    SM3::Mobius_Loop_subdivision(mob, NP::number_of_iterations(2));
    SM3::Loop_subdivision(lin, NP::number_of_iterations(2));
    SM3::Mobius_Loop_subdivision(w0, NP::number_of_iterations(2).linear_weight(0.0));
    SM3::Mobius_Loop_subdivision(w1, NP::number_of_iterations(2).linear_weight(1.0));
    SM3::Mobius_Loop_subdivision(wh, NP::number_of_iterations(2).linear_weight(0.5));
    bool consistent = false;
    nc::Report rb = call_new([&](nc::Report& r) { SM3::Mobius_Loop_subdivision(bad, NP::linear_weight(2.0).report(r)); }, &consistent);
    if (flat_of(w0) == flat_of(mob) && flat_of(w1) == flat_of(lin) && exact(wh, half) && !(flat_of(mob) == flat_of(lin)) &&
        !(flat_of(wh) == flat_of(mob)) && !(flat_of(wh) == flat_of(lin)) && consistent && rb.status == NLS_STATUS_INVALID_ARGUMENT &&
        flat_of(bad) == oin)
      t.pass("SM3 linear_weight: 0 = Möbius, 1 = linear bit for bit, 0.5 = C ABI, 2 refused", 0);
    else
      t.fail("SM3 linear_weight: " + rb.message());
    // Butterfly and Catmull-Clark too.
    SM bm = oct, bl = oct, cm = cube, cl = cube;
    SM3::Mobius_Butterfly_subdivision(bm, NP::number_of_iterations(2).linear_weight(1.0));
    SM3::Butterfly_subdivision(bl, NP::number_of_iterations(2));
    SM3::Mobius_CatmullClark_subdivision(cm, NP::number_of_iterations(2).linear_weight(1.0));
    SM3::CatmullClark_subdivision(cl, NP::number_of_iterations(2));
    if (flat_of(bm) == flat_of(bl) && flat_of(cm) == flat_of(cl))
      t.pass("SM3 linear_weight(1): Möbius Butterfly = Butterfly, Möbius Catmull-Clark = Catmull-Clark, bit for bit", 0);
    else
      t.fail("SM3 linear_weight(1) Butterfly / Catmull-Clark");
  }
  // vertex_linear_weight_map: per-vertex weights u of the linear result. Equal values =
  // linear_weight of that value bit for bit; mixed values = the C ABI with the same array
  // (Loop and Kobbelt, whose default paths are masks, take the bulk path then); NaN at a
  // vertex = NLS_STATUS_INVALID_ARGUMENT naming it, mesh unchanged.
  {
    SM eq = oct, g = oct, mixed = oct, bad = oct, cm = cube;
    auto wq = eq.add_property_map<SM::Vertex_index, double>("v:u", 0.3).first;
    SM3::Mobius_Loop_subdivision(eq, NP::number_of_iterations(2).vertex_linear_weight_map(wq));
    SM3::Mobius_Loop_subdivision(g, NP::number_of_iterations(2).linear_weight(0.3));
    auto wm = mixed.add_property_map<SM::Vertex_index, double>("v:u", 0.0).first;
    std::vector<double> u;
    for (auto v : vertices(mixed)) {
      wm[v] = (v.idx() % 3) / 2.0;
      u.push_back(wm[v]);
    }
    SM3::Mobius_Loop_subdivision(mixed, NP::number_of_iterations(2).vertex_linear_weight_map(wm));
    nlsubdiv::flat::FlatMesh o;
    uint32_t el = 0, fb = 0;
    const nls_status cs = nlsubdiv::flat::run_levels(NLS_SCHEME_LOOP, M, to_fm(oin), 2, o, el, fb, nullptr, 0.0, u.data());
    auto wc = cm.add_property_map<SM::Vertex_index, double>("v:u", 0.0).first;
    std::vector<double> uc;
    for (auto v : vertices(cm)) {
      wc[v] = (v.idx() % 2) * 0.75;
      uc.push_back(wc[v]);
    }
    SM3::Mobius_Kobbelt_subdivision(cm, NP::number_of_iterations(2).vertex_linear_weight_map(wc));
    nlsubdiv::flat::FlatMesh oc;
    const nls_status ks = nlsubdiv::flat::run_levels(NLS_SCHEME_KOBBELT, M, to_fm(cin), 2, oc, el, fb, nullptr, 0.0, uc.data());
    auto wb = bad.add_property_map<SM::Vertex_index, double>("v:u", 0.5).first;
    wb[SM::Vertex_index(4)] = std::nan("");
    bool consistent = false;
    nc::Report rb = call_new(
        [&](nc::Report& r) { SM3::Mobius_Loop_subdivision(bad, NP::number_of_iterations(2).vertex_linear_weight_map(wb).report(r)); },
        &consistent);
    if (flat_of(eq) == flat_of(g) && cs == NLS_STATUS_OK && exact(mixed, of_fm(o)) && !(flat_of(mixed) == flat_of(g)) &&
        ks == NLS_STATUS_OK && exact(cm, of_fm(oc)) && consistent && rb.status == NLS_STATUS_INVALID_ARGUMENT && rb.element == 4 &&
        flat_of(bad) == oin)
      t.pass("SM3 vertex_linear_weight_map: equal = linear_weight bit for bit, mixed = C ABI linear_weights, NaN refused naming the vertex", 0);
    else
      t.fail("SM3 vertex_linear_weight_map: " + rb.message());
  }
  // threads: the same bits for 1, 2, 3, 7 and the hardware's thread count, on the bulk path
  // and on the driver masks (Catmull-Clark's PQQ host), and the same refusal.
  {
    SM obent = oct, cbent = cube;
    for (auto v : vertices(obent)) {
      const K::Point_3 p = obent.point(v);
      const double s = 1.0 + 0.1 * static_cast<double>(v.idx());
      obent.point(v) = K::Point_3(p.x() * s, p.y() * s, p.z() * s);
    }
    for (auto v : vertices(cbent))
      if (v.idx() == 7) cbent.point(v) = K::Point_3(0, 1, 1.3);
    bool all = true;
    std::string why;
    auto check = [&](const char* what, auto run, const SM& m0) {
      SM ref = m0;
      run(ref, 1u);
      for (unsigned n : {2u, 3u, 7u, 0u}) {
        SM m = m0;
        run(m, n);
        if (!(flat_of(m) == flat_of(ref))) {
          all = false;
          why += std::string(" ") + what + "/" + std::to_string(n);
        }
      }
    };
    check("Mobius_Loop", [](SM& m, unsigned n) { SM3::Mobius_Loop_subdivision(m, NP::number_of_iterations(4).threads(n)); }, obent);
    check("Mobius_Butterfly", [](SM& m, unsigned n) { SM3::Mobius_Butterfly_subdivision(m, NP::number_of_iterations(4).threads(n)); }, obent);
    check("Mobius_CatmullClark",
          [](SM& m, unsigned n) { SM3::Mobius_CatmullClark_subdivision(m, NP::number_of_iterations(4).threads(n)); }, cbent);
    check("Mobius_Kobbelt", [](SM& m, unsigned n) { SM3::Mobius_Kobbelt_subdivision(m, NP::number_of_iterations(3).threads(n)); }, cbent);
    check("Loop", [](SM& m, unsigned n) { SM3::Loop_subdivision(m, NP::number_of_iterations(4).threads(n)); }, obent);
    check("Mobius_Loop weight 0.5",
          [](SM& m, unsigned n) { SM3::Mobius_Loop_subdivision(m, NP::number_of_iterations(3).linear_weight(0.5).threads(n)); }, obent);
    SM bad = oct;
    bool consistent = false;
    nc::Report rb =
        call_new([&](nc::Report& r) { SM3::Mobius_Loop_subdivision(bad, NP::linear_weight(2.0).threads(3).report(r)); }, &consistent);
    if (all && consistent && rb.status == NLS_STATUS_INVALID_ARGUMENT && flat_of(bad) == oin)
      t.pass("SM3 threads: 1, 2, 3, 7 and all threads give the same bits (bulk and driver masks); refusals unchanged", 0);
    else
      t.fail("SM3 threads:" + why + " " + rb.message());
  }
  // strict: an unreferenced vertex is accepted by default and refused in strict mode
  // (NLS_STATUS_INVALID_ARGUMENT naming it), mesh unchanged.
  {
    SM a = oct;
    a.add_vertex(K::Point_3(5, 5, 5));
    const Flat before = flat_of(a);
    SM b = a;
    bool c1 = false, c2 = false;
    nc::Report r1 = call_new([&](nc::Report& r) { SM3::Loop_subdivision(a, NP::report(r)); }, &c1);
    nc::Report r2 = call_new([&](nc::Report& r) { SM3::Loop_subdivision(b, NP::strict(true).report(r)); }, &c2);
    if (c1 && c2 && r1.ok() && r2.status == NLS_STATUS_INVALID_ARGUMENT && r2.element == 6 && flat_of(b) == before)
      t.pass("SM3 strict(true): unreferenced vertex refused (vertex 6), mesh unchanged; accepted without", 0);
    else
      t.fail("SM3 strict: " + r1.message() + " / " + r2.message());
  }
  // creases: sharpness and method against the C ABI's tagged call; sharpness has effect.
  {
    static const uint32_t E[24] = {0, 1, 1, 2, 2, 3, 3, 0, 4, 5, 5, 6, 6, 7, 7, 4, 0, 4, 1, 5, 2, 6, 3, 7};
    std::vector<double> s2(12, 1.5);
    nls_tags tags{};
    tags.crease_vertices = E;
    tags.crease_sharpness = s2.data();
    tags.crease_count = 12;
    tags.method = NLS_CREASE_CHAIKIN;
    Flat want2c, want10;
    nls_status d1 = c_abi(NLS_SCHEME_CATMULL_CLARK, 0, cin, 2, want2c, 0.0, &tags);
    std::vector<double> s10(12, 10.0);
    tags.crease_sharpness = s10.data();
    tags.method = NLS_CREASE_UNIFORM;
    nls_status d2 = c_abi(NLS_SCHEME_CATMULL_CLARK, 0, cin, 2, want10, 0.0, &tags);
    SM a = cube, b = cube;
    auto ea = a.add_property_map<SM::Edge_index, bool>("e:sharp", true).first;
    auto eb = b.add_property_map<SM::Edge_index, bool>("e:sharp", true).first;
    SM3::CatmullClark_subdivision(a, NP::number_of_iterations(2).edge_is_constrained_map(ea).crease_sharpness(1.5).crease_method(NLS_CREASE_CHAIKIN));
    SM3::CatmullClark_subdivision(b, NP::number_of_iterations(2).edge_is_constrained_map(eb));
    if (d1 == NLS_STATUS_OK && d2 == NLS_STATUS_OK && exact(a, want2c) && exact(b, want10) && !(flat_of(a) == flat_of(b)))
      t.pass("SM3 crease_sharpness(1.5) + crease_method(Chaikin) and the default 10 = C ABI tags, and differ", 0);
    else
      t.fail(std::string("SM3 creases: C ABI ") + nls_status_str(d1) + "/" + nls_status_str(d2) + ", sharpness 2 Chaikin " +
             itest::compare(flat_of(a), want2c).summary() + ", default " + itest::compare(flat_of(b), want10).summary());
    // corner_sharpness: a corner of sharpness 0 is no corner (= untagged Loop); 10 keeps it.
    SM c = oct, d = oct, e = oct;
    auto vc = c.add_property_map<SM::Vertex_index, bool>("v:corner", false).first;
    auto vd = d.add_property_map<SM::Vertex_index, bool>("v:corner", false).first;
    put(vc, SM::Vertex_index(4), true);
    put(vd, SM::Vertex_index(4), true);
    SM3::Loop_subdivision(c, NP::number_of_iterations(2).vertex_is_constrained_map(vc).corner_sharpness(0.0));
    SM3::Loop_subdivision(d, NP::number_of_iterations(2).vertex_is_constrained_map(vd));
    SM3::Loop_subdivision(e, NP::number_of_iterations(2));
    const auto p4 = d.point(SM::Vertex_index(4));
    if (flat_of(c) == flat_of(e) && p4.x() == 0 && p4.y() == 0 && p4.z() == 1 && !(flat_of(d) == flat_of(e)))
      t.pass("SM3 corner_sharpness: 0 = no corner, default keeps the corner", 0);
    else
      t.fail("SM3 corner_sharpness");
  }
  // Error path: a quad for Loop throws Subdivision_error naming the face, mesh unchanged.
  {
    SM a = cube;
    bool caught = false;
    nls_status st = NLS_STATUS_OK;
    uint32_t el = 0;
    std::string what;
    try {
      SM3::Loop_subdivision(a, NP::number_of_iterations(2));
    } catch (const SM3::Subdivision_error& e) {
      caught = true;
      st = e.status();
      el = e.element();
      what = e.what();
    }
    Flat ref;
    nls_status ds = c_abi(NLS_SCHEME_LOOP, 0, cin, 2, ref);
    if (caught && st == ds && st == NLS_STATUS_UNSUPPORTED_FACE_TYPE && el == 0 && what.find("(face 0)") != std::string::npos &&
        flat_of(a) == cin)
      t.pass("SM3 error: Subdivision_error with the C ABI's status and face, what() names it, mesh unchanged", 0);
    else
      t.fail("SM3 error path: " + what);
  }
}

/// Differential editing through vertex_curvature_scale_map and vertex_normal_map = the C ABI
/// with the same arrays; a doubled curvature moves the vertex outward; a NaN scale is refused
/// naming the vertex.
static void differential_edits(itest::Tally& t) {
  const SM oct = make_octahedron();
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
  std::vector<double> scale(6, 1.0);
  scale[4] = 2.0;
  std::vector<double> normals(18, 0.0);
  normals[3 * 4 + 0] = 0.3;
  normals[3 * 4 + 2] = 1.0;
  Flat want_c, want_n, plain;
  uint32_t el = 0;
  nls_status s1 = c_diff(&scale, nullptr, want_c, el), s2 = c_diff(nullptr, &normals, want_n, el), s3 = c_diff(nullptr, nullptr, plain, el);
  SM a = oct, b = oct;
  auto cm = a.add_property_map<SM::Vertex_index, double>("v:curv", 1.0).first;
  put(cm, SM::Vertex_index(4), 2.0);
  auto nm = b.add_property_map<SM::Vertex_index, K::Vector_3>("v:n", K::Vector_3(0, 0, 0)).first;
  put(nm, SM::Vertex_index(4), K::Vector_3(0.3, 0, 1.0));
  SM3::Differential_Loop_subdivision(a, NP::number_of_iterations(2).vertex_curvature_scale_map(cm));
  SM3::Differential_Loop_subdivision(b, NP::vertex_normal_map(nm).number_of_iterations(2));
  const Flat fa = flat_of(a), fb = flat_of(b);
  if (s1 == NLS_STATUS_OK && s2 == NLS_STATUS_OK && s3 == NLS_STATUS_OK && fa == want_c && fb == want_n && !(fa == plain) && !(fb == plain))
    t.pass("SM3 differential edits (curvature map, vertex_normal_map) = C ABI arrays bit for bit", 0);
  else
    t.fail("SM3 differential edits differ from the C ABI");
  // Vertex 4 is the apex (0, 0, 1); a doubled mean curvature moves it outward.
  if (s3 == NLS_STATUS_OK && fa.pos[3 * 4 + 2] > plain.pos[3 * 4 + 2])
    t.pass("SM3 doubled curvature on the apex moves it outward", 0);
  else
    t.fail("SM3 doubled curvature: z " + std::to_string(fa.pos[3 * 4 + 2]) + " vs " + std::to_string(plain.pos[3 * 4 + 2]));
  // NaN scale: the C ABI's status naming vertex 4, mesh unchanged.
  scale[4] = NAN;
  Flat dummy;
  uint32_t cel = 0;
  nls_status cs = c_diff(&scale, nullptr, dummy, cel);
  SM c = oct;
  auto cn = c.add_property_map<SM::Vertex_index, double>("v:curv", 1.0).first;
  put(cn, SM::Vertex_index(4), NAN);
  bool consistent = false;
  nc::Report r = call_new(
      [&](nc::Report& rr) { SM3::Differential_Loop_subdivision(c, NP::number_of_iterations(2).vertex_curvature_scale_map(cn).report(rr)); },
      &consistent);
  if (consistent && cs != NLS_STATUS_OK && r.status == cs && r.element == 4 && cel == 4 && flat_of(c) == in)
    t.pass(std::string("SM3 NaN curvature scale refused: ") + r.message(), 0);
  else
    t.fail("SM3 NaN curvature scale: " + r.message() + " (C ABI " + nls_status_str(cs) + " element " + std::to_string(cel) + ")");
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
    SM pm;
    if (!load(dir + "/" + f, pm)) {
      std::printf("skip %s: CGAL's OFF reader does not load it whole into a Surface_mesh\n", f.c_str());
      ++t.skipped;
      continue;
    }
    check_functions(t, f, pm, "Surface_mesh");
    if (num_faces(pm) <= 400) new_names_equal_old(t, f, pm, 2);
    if (itest::all_faces(flat_of(pm), 3) && num_faces(pm) <= 3000) check_differential(t, f, pm);
    if (num_faces(pm) <= 3000 && CGAL::is_valid_polygon_mesh(pm)) check_masks_with_cgal_hosts(t, f, pm);
    if (num_faces(pm) <= 400) {
      Poly ph;
      if (load(dir + "/" + f, ph)) check_functions(t, f, ph, "Polyhedron_3");
    }
  }
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
    const bool valid = f.rfind("format_", 0) == 0;  // layout variants of a valid mesh
    pid_t pid = fork();
    if (pid == 0) {
      close(fds[0]);
      std::printf("  bad/%s:\n", f.c_str());
      std::fflush(stdout);
      _exit(bad_child(dir + "/bad/" + f, fds[1], valid));
    }
    close(fds[1]);
    char mark = 0;
    ssize_t got = read(fds[0], &mark, 1);
    close(fds[0]);
    int st = 0;
    waitpid(pid, &st, 0);
    if (got != 1 || mark != 'L') {
      std::printf("    CGAL does not load it as it is (%s)\n", WIFSIGNALED(st) ? "its reader aborted" : "read_OFF failed or changed the counts");
      ++t.skipped;
      continue;
    }
    ++loaded;
    if (WIFEXITED(st) && WEXITSTATUS(st) == 0) {
      if (!valid) ++refused;
      t.pass(valid ? "bad/format_* (valid layout variants) accepted" : "bad mesh refused (strict), unchanged, host alive", 0);
    } else {
      t.fail("bad/" + f + (WIFSIGNALED(st) ? ": the host process died" : valid ? ": a valid mesh was refused" : ": accepted or changed"));
    }
  }
  std::printf("bad meshes: %zu files, %d loaded as they are by CGAL (format_* included), %d broken ones refused by every function with the mesh unchanged\n",
              bad.size(), loaded, refused);
  differential_refuses_non_triangles(t);
  sharp_features(t);
  new_names_equal_old(t, "octahedron", make_octahedron(), 2);
  new_names_equal_old(t, "cube", make_cube(), 2);
  try {
    named_parameters(t);
    differential_edits(t);
  } catch (const std::exception& e) {
    t.fail(std::string("SM3 named parameters: unexpected exception: ") + e.what());
  }
  for (const auto& w : t.worst) std::printf("  %-70s worst max_rel_dist %.3e\n", w.first.c_str(), w.second);
  double secs = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  std::printf("test_cgal: %d passed, %d failed, %d skipped (%.1f s)\n", t.passed, t.failed, t.skipped, secs);
  return t.failed ? 1 : 0;
}
