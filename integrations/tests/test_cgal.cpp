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
/// one constrained corner stays put under Loop on an octahedron; a Möbius function with a
/// constrained edge is refused (NLS_STATUS_TAGS_NOT_SUPPORTED), mesh unchanged.
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
  // A scheme without tag rules refuses, mesh unchanged.
  SM b = cube;
  auto ecm2 = b.add_property_map<SM::Edge_index, bool>("e:sharp", true).first;
  nc::Report r3 = nc::mobius_catmull_clark_subdivision(b, CGAL::parameters::number_of_iterations(1).edge_is_constrained_map(ecm2));
  SM d = make_oct();
  auto vcm2 = d.add_property_map<SM::Vertex_index, bool>("v:corner", false).first;
  put(vcm2, SM::Vertex_index(4), true);
  nc::Report r4 = nc::mobius_loop_subdivision(d, CGAL::parameters::number_of_iterations(1).vertex_is_constrained_map(vcm2));
  if (r3.status == NLS_STATUS_TAGS_NOT_SUPPORTED && flat_of(b) == in && r4.status == NLS_STATUS_TAGS_NOT_SUPPORTED)
    t.pass("CGAL Möbius functions refuse constrained edges and vertices, mesh unchanged", 0);
  else
    t.fail(std::string("CGAL Möbius with features: ") + r3.message() + " / " + r4.message());
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
  for (const auto& w : t.worst) std::printf("  %-70s worst max_rel_dist %.3e\n", w.first.c_str(), w.second);
  double secs = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  std::printf("test_cgal: %d passed, %d failed, %d skipped (%.1f s)\n", t.passed, t.failed, t.skipped, secs);
  return t.failed ? 1 : 0;
}
