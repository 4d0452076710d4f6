// Shared helpers of the integration tests: the driver (nls_mesh_subdivide) on flat
// meshes, an order-independent comparison of two meshes, and the test bookkeeping.
#ifndef NLSUBDIV_INTEGRATION_TESTS_COMMON_HPP
#define NLSUBDIV_INTEGRATION_TESTS_COMMON_HPP

#include <dirent.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <map>
#include <string>
#include <unordered_map>
#include <vector>

#include "nlsubdiv.h"

namespace itest {

struct Flat {
  std::vector<double> pos;
  std::vector<uint32_t> off{0};
  std::vector<uint32_t> idx;
  std::size_t nv() const { return pos.size() / 3; }
  std::size_t nf() const { return off.size() - 1; }
  bool operator==(const Flat& o) const { return pos == o.pos && off == o.off && idx == o.idx; }
};

/// The C ABI's view of `in` (packed positions).
inline nls_mesh_view view_of(const Flat& in) {
  nls_mesh_view v{};
  v.positions = in.pos.data();
  v.vertex_count = in.nv();
  v.offsets = in.off.data();
  v.face_count = in.nf();
  v.indices = in.idx.data();
  v.index_count = in.idx.size();
  return v;
}

/// The driver: `levels` levels of `scheme` with `flags`; status, and the result in `out`.
inline nls_status driver(uint32_t scheme, uint32_t flags, const Flat& in, uint32_t levels, Flat& out) {
  const nls_mesh_view v = view_of(in);
  nls_subdivide_options o{};
  nls_subdivide_default_options(&o);
  o.scheme = scheme;
  o.flags = flags;
  o.levels = levels;
  std::size_t su0 = 0;
  uint32_t el = 0;
  nls_status s = nls_mesh_plan_scratch_size(&v, &su0);
  if (s) return s;
  std::vector<uint32_t> scratch(su0 + 1);
  nls_plan plan{};
  s = nls_mesh_plan(&v, &o, scratch.data(), scratch.size(), &plan, &el);
  if (s) return s;
  const std::size_t nv = plan.output.vertex_count, nf = plan.output.face_count, ni = plan.output.index_count;
  scratch.assign(std::max(plan.scratch_u32, su0) + 1, 0);
  std::vector<double> spts(3 * plan.scratch_points + 3);
  out.pos.assign(3 * nv + 3, 0);
  out.off.assign(nf + 1, 0);
  out.idx.assign(ni + 1, 0);
  const nls_scratch sc{scratch.data(), scratch.size(), spts.data(), plan.scratch_points};
  const nls_mesh_buffers b{out.pos.data(), nv, out.off.data(), nf, out.idx.data(), ni};
  nls_mesh_sizes w{};
  nls_subdivide_report rep{};
  s = nls_mesh_subdivide(&v, &o, &sc, &b, &w, &rep, &el);
  if (s) return s;
  out.pos.resize(3 * w.vertex_count);
  out.off.resize(w.face_count + 1);
  out.idx.resize(w.index_count);
  return NLS_STATUS_OK;
}

/// The differential driver (nls_differential_plan + nls_differential_subdivide, called here
/// directly): `levels` levels with `stencil` (NLS_DIFFERENTIAL_*), DirMag levels, iteration
/// cap and tolerance; status, the result in `out`, the solver report in `rep`.
inline nls_status driver_differential(uint32_t stencil, uint32_t dirmag, uint32_t max_it, double tol, const Flat& in, uint32_t levels, Flat& out,
                                      nls_differential_report& rep) {
  const nls_mesh_view v = view_of(in);
  nls_differential_options o{};
  nls_differential_default_options(&o);
  o.scheme = stencil;
  o.levels = levels;
  o.dirmag_levels = dirmag;
  o.max_iterations = max_it;
  o.tolerance = tol;
  std::size_t su0 = 0;
  uint32_t el = 0;
  nls_status s = nls_mesh_plan_scratch_size(&v, &su0);
  if (s) return s;
  std::vector<uint32_t> scratch(su0 + 1);
  nls_plan plan{};
  s = nls_differential_plan(&v, &o, scratch.data(), scratch.size(), &plan, &el);
  if (s) return s;
  const std::size_t nv = plan.output.vertex_count, nf = plan.output.face_count, ni = plan.output.index_count;
  scratch.assign(std::max(plan.scratch_u32, su0) + 1, 0);
  std::vector<double> spts(3 * plan.scratch_points + 3);
  out.pos.assign(3 * nv + 3, 0);
  out.off.assign(nf + 1, 0);
  out.idx.assign(ni + 1, 0);
  const nls_scratch sc{scratch.data(), scratch.size(), spts.data(), plan.scratch_points};
  const nls_mesh_buffers b{out.pos.data(), nv, out.off.data(), nf, out.idx.data(), ni};
  nls_mesh_sizes w{};
  rep = nls_differential_report{};
  s = nls_differential_subdivide(&v, &o, &sc, &b, &w, &rep, &el);
  if (s) return s;
  out.pos.resize(3 * w.vertex_count);
  out.off.resize(w.face_count + 1);
  out.idx.resize(w.index_count);
  return NLS_STATUS_OK;
}

struct Cmp {
  double max_rel = 0.0;
  bool counts = true, faces = true, bits = false;
  bool ok(double tol) const { return counts && faces && max_rel <= tol; }
  std::string summary() const {
    char b[160];
    std::snprintf(b, sizeof b, "max_rel_dist=%.3e faces=%s%s%s", max_rel, faces ? "identical" : "DIFFER", counts ? "" : " COUNTS DIFFER",
                  bits ? " (bit-identical layout)" : "");
    return b;
  }
};

/// Order-independent comparison (as peers/compare_off.py): every vertex of `a` matched to
/// its nearest vertex of `b`; the largest distance over the diagonal of a's bounding box;
/// the faces of `a` mapped through the matching must be the faces of `b` as a multiset, each
/// up to rotation, orientation kept.
inline Cmp compare(const Flat& a, const Flat& b) {
  Cmp r;
  if (a == b) {
    r.bits = true;
    return r;
  }
  if (a.nv() != b.nv() || a.nf() != b.nf() || a.idx.size() != b.idx.size()) {
    r.counts = false;
    r.faces = false;
    r.max_rel = INFINITY;
    return r;
  }
  double lo[3] = {INFINITY, INFINITY, INFINITY}, hi[3] = {-INFINITY, -INFINITY, -INFINITY};
  for (std::size_t i = 0; i < a.nv(); ++i)
    for (int k = 0; k < 3; ++k) {
      lo[k] = std::min(lo[k], a.pos[3 * i + k]);
      hi[k] = std::max(hi[k], a.pos[3 * i + k]);
    }
  double diag = std::sqrt((hi[0] - lo[0]) * (hi[0] - lo[0]) + (hi[1] - lo[1]) * (hi[1] - lo[1]) + (hi[2] - lo[2]) * (hi[2] - lo[2]));
  if (!(diag > 0)) diag = 1;
  const double cell = diag * 1e-6;
  auto key = [&](const double* p, int dx, int dy, int dz) {
    long long x = (long long)std::floor((p[0] - lo[0]) / cell) + dx, y = (long long)std::floor((p[1] - lo[1]) / cell) + dy,
              z = (long long)std::floor((p[2] - lo[2]) / cell) + dz;
    return (uint64_t)((x * 73856093LL) ^ (y * 19349663LL) ^ (z * 83492791LL));
  };
  std::unordered_multimap<uint64_t, uint32_t> grid;
  grid.reserve(b.nv() * 2);
  for (std::size_t i = 0; i < b.nv(); ++i) grid.emplace(key(&b.pos[3 * i], 0, 0, 0), (uint32_t)i);
  std::vector<uint32_t> match(a.nv());
  auto d2 = [&](const double* p, std::size_t j) {
    double s = 0;
    for (int k = 0; k < 3; ++k) s += (p[k] - b.pos[3 * j + k]) * (p[k] - b.pos[3 * j + k]);
    return s;
  };
  std::size_t brute = 0;
  for (std::size_t i = 0; i < a.nv(); ++i) {
    const double* p = &a.pos[3 * i];
    double best = INFINITY;
    uint32_t bj = 0;
    for (int dx = -1; dx <= 1; ++dx)
      for (int dy = -1; dy <= 1; ++dy)
        for (int dz = -1; dz <= 1; ++dz) {
          auto range = grid.equal_range(key(p, dx, dy, dz));
          for (auto it = range.first; it != range.second; ++it) {
            double d = d2(p, it->second);
            if (d < best) best = d, bj = it->second;
          }
        }
    if (!(best <= cell * cell)) {  // not within a cell: exact search (only on a failure)
      if (++brute > 200) {
        r.max_rel = std::max(r.max_rel, 1e-6);
        r.faces = false;
        continue;
      }
      for (std::size_t j = 0; j < b.nv(); ++j) {
        double d = d2(p, j);
        if (d < best) best = d, bj = (uint32_t)j;
      }
    }
    match[i] = bj;
    r.max_rel = std::max(r.max_rel, std::sqrt(best) / diag);
  }
  // Vertices of b at bit-identical positions are one vertex for the face comparison (the
  // nearest-point match cannot tell them apart).
  std::vector<uint32_t> cls(b.nv());
  {
    std::vector<uint32_t> ord(b.nv());
    for (std::size_t i = 0; i < ord.size(); ++i) ord[i] = (uint32_t)i;
    auto P = [&](uint32_t i) { return std::array<double, 3>{b.pos[3 * i], b.pos[3 * i + 1], b.pos[3 * i + 2]}; };
    std::sort(ord.begin(), ord.end(), [&](uint32_t x, uint32_t y) { return P(x) < P(y) || (P(x) == P(y) && x < y); });
    for (std::size_t k = 0; k < ord.size(); ++k) cls[ord[k]] = (k > 0 && P(ord[k]) == P(ord[k - 1])) ? cls[ord[k - 1]] : ord[k];
  }
  for (auto& mj : match) mj = cls[mj];
  auto canon = [](std::vector<uint32_t> f) {
    auto m = std::min_element(f.begin(), f.end());
    std::rotate(f.begin(), m, f.end());
    return f;
  };
  std::vector<std::vector<uint32_t>> fa, fb;
  for (std::size_t f = 0; f < a.nf(); ++f) {
    std::vector<uint32_t> x;
    for (uint32_t c = a.off[f]; c < a.off[f + 1]; ++c) x.push_back(match[a.idx[c]]);
    fa.push_back(canon(x));
  }
  for (std::size_t f = 0; f < b.nf(); ++f) {
    std::vector<uint32_t> x;
    for (uint32_t c = b.off[f]; c < b.off[f + 1]; ++c) x.push_back(cls[b.idx[c]]);
    fb.push_back(canon(x));
  }
  std::sort(fa.begin(), fa.end());
  std::sort(fb.begin(), fb.end());
  r.faces = r.faces && fa == fb;
  return r;
}

/// The .off files of a directory, sorted.
inline std::vector<std::string> off_files(const std::string& dir) {
  std::vector<std::string> out;
  DIR* d = opendir(dir.c_str());
  if (!d) return out;
  while (dirent* e = readdir(d)) {
    std::string n = e->d_name;
    if (n.size() > 4 && n.substr(n.size() - 4) == ".off") out.push_back(n);
  }
  closedir(d);
  std::sort(out.begin(), out.end());
  return out;
}

struct Tally {
  int passed = 0, failed = 0, skipped = 0;
  std::map<std::string, double> worst;  // per check name: the largest max_rel seen
  void pass(const std::string& what, double rel) {
    ++passed;
    double& w = worst[what];
    w = std::max(w, rel);
  }
  void fail(const std::string& line) {
    ++failed;
    std::printf("FAIL %s\n", line.c_str());
  }
};

inline bool all_faces(const Flat& m, std::size_t n) {
  for (std::size_t f = 0; f < m.nf(); ++f)
    if (m.off[f + 1] - m.off[f] != n) return false;
  return m.nf() > 0;
}

}  // namespace itest

#endif
