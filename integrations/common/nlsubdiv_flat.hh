// nlsubdiv_flat.hh: what the C++ integrations share: a polygon mesh as flat arrays (the C
// ABI's layout), its validation by the kernel, the strict input checks, and the bulk driver
// call. Header-only, C++17, over include/nlsubdiv.h.
#ifndef NLSUBDIV_FLAT_HH
#define NLSUBDIV_FLAT_HH

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <utility>
#include <vector>

#include "nlsubdiv.h"

namespace nlsubdiv {
namespace flat {

/// A polygon mesh as the C ABI takes it (positions, CSR offsets and indices).
struct FlatMesh {
  std::vector<double> positions;   ///< 3 per vertex
  std::vector<uint32_t> offsets;   ///< face_count + 1
  std::vector<uint32_t> indices;   ///< corners, faces counter-clockwise
  std::size_t vertex_count() const { return positions.size() / 3; }
  std::size_t face_count() const { return offsets.empty() ? 0 : offsets.size() - 1; }
};

/// Validates `flat` for one level of `scheme` with `flags` (nls_mesh_subdivide_size).
inline nls_status validate(uint32_t scheme, uint32_t flags, const FlatMesh& flat, uint32_t& element) {
  std::size_t su = 0, sp = 0, nv = 0, nf = 0, ni = 0;
  nls_status s = nls_mesh_scratch_size(scheme, flags, flat.vertex_count(), flat.indices.size(), &su, &sp);
  if (s != NLS_STATUS_OK) return s;
  std::vector<uint32_t> scratch(su + 1);
  return nls_mesh_subdivide_size(scheme, flags, flat.positions.data(), flat.vertex_count(), flat.offsets.data(),
                                 flat.face_count(), flat.indices.data(), flat.indices.size(), scratch.data(), scratch.size(), &nv,
                                 &nf, &ni, &element);
}

/// The input checks of strict mode beyond the kernel's validation, the same as the
/// `nlsubdiv check` warnings that `--strict` turns into errors: an unreferenced vertex
/// (NLS_STATUS_INVALID_ARGUMENT naming the vertex; the kernel carries it through), two
/// referenced vertices at bit-identical positions (NLS_STATUS_DEGENERATE_GEOMETRY naming the
/// later vertex: a duplicated vertex leaves a crack), a face of zero area relative to its
/// longest edge (1e-14, NLS_STATUS_DEGENERATE_GEOMETRY naming the face).
inline nls_status strict_check(const FlatMesh& flat, uint32_t& element) {
  const std::size_t nv = flat.vertex_count();
  std::vector<char> used(nv, 0);
  for (uint32_t i : flat.indices)
    if (i < nv) used[i] = 1;
  for (std::size_t v = 0; v < nv; ++v)
    if (!used[v]) {
      element = static_cast<uint32_t>(v);
      return NLS_STATUS_INVALID_ARGUMENT;
    }
  std::vector<std::pair<std::array<double, 3>, uint32_t>> keys;
  keys.reserve(nv);
  for (std::size_t v = 0; v < nv; ++v)
    keys.push_back({{flat.positions[3 * v], flat.positions[3 * v + 1], flat.positions[3 * v + 2]}, static_cast<uint32_t>(v)});
  std::sort(keys.begin(), keys.end());
  for (std::size_t k = 1; k < keys.size(); ++k)
    if (keys[k].first == keys[k - 1].first) {
      element = std::max(keys[k].second, keys[k - 1].second);
      return NLS_STATUS_DEGENERATE_GEOMETRY;
    }
  for (std::size_t f = 0; f + 1 < flat.offsets.size(); ++f) {
    const uint32_t a = flat.offsets[f], b = flat.offsets[f + 1];
    double n[3] = {0, 0, 0}, longest = 0;
    for (uint32_t c = a; c < b; ++c) {
      const double* p = &flat.positions[3 * flat.indices[c]];
      const double* q = &flat.positions[3 * flat.indices[c + 1 < b ? c + 1 : a]];
      n[0] += p[1] * q[2] - p[2] * q[1];
      n[1] += p[2] * q[0] - p[0] * q[2];
      n[2] += p[0] * q[1] - p[1] * q[0];
      const double d = std::sqrt((q[0] - p[0]) * (q[0] - p[0]) + (q[1] - p[1]) * (q[1] - p[1]) + (q[2] - p[2]) * (q[2] - p[2]));
      longest = std::max(longest, d);
    }
    const double area2 = std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
    if (area2 * 0.5 <= 1e-14 * longest * longest) {
      element = static_cast<uint32_t>(f);
      return NLS_STATUS_DEGENERATE_GEOMETRY;
    }
  }
  return NLS_STATUS_OK;
}

/// `levels` levels of `scheme` with `flags` on `in` through nls_mesh_subdivide_levels (exact
/// sizes first, then one call); `out` receives the result. `element` the element of a
/// failure, `fallbacks` the report's count.
inline nls_status run_levels(uint32_t scheme, uint32_t flags, const FlatMesh& in, uint32_t levels, FlatMesh& out, uint32_t& element,
                             uint32_t& fallbacks) {
  std::size_t su0 = 0, sp0 = 0, nv = 0, nf = 0, ni = 0, su = 0, sp = 0;
  element = NLS_NO_ELEMENT;
  nls_status s = nls_mesh_scratch_size(scheme, flags, in.vertex_count(), in.indices.size(), &su0, &sp0);
  if (s != NLS_STATUS_OK) return s;
  std::vector<uint32_t> scratch(su0 + 1);
  s = nls_mesh_subdivide_levels_size(scheme, flags, in.positions.data(), in.vertex_count(), in.offsets.data(), in.face_count(),
                                     in.indices.data(), in.indices.size(), levels, scratch.data(), scratch.size(), &nv, &nf, &ni, &su, &sp,
                                     &element);
  if (s != NLS_STATUS_OK) return s;
  scratch.assign(std::max(su, su0) + 1, 0);
  std::vector<double> spts(3 * sp + 3);
  out.positions.assign(3 * nv + 3, 0.0);
  out.offsets.assign(nf + 1, 0);
  out.indices.assign(ni + 1, 0);
  nls_subdivide_report rep{};
  s = nls_mesh_subdivide_levels(scheme, flags, in.positions.data(), in.vertex_count(), in.offsets.data(), in.face_count(), in.indices.data(),
                                in.indices.size(), levels, scratch.data(), scratch.size(), spts.data(), sp, out.positions.data(), nv,
                                out.offsets.data(), nf, out.indices.data(), ni, &nv, &nf, &ni, &rep, &element);
  if (s != NLS_STATUS_OK) return s;
  out.positions.resize(3 * nv);
  out.offsets.resize(nf + 1);
  out.indices.resize(ni);
  fallbacks = rep.fallbacks;
  return NLS_STATUS_OK;
}

/// Differential-space subdivision of `in` (triangles) with `opt` (its `levels` levels in one
/// call: the reconstruction is global, so k levels are one solve, not k solves of one level)
/// through nls_differential_plan + nls_differential_subdivide. `out` receives the result on
/// success; `rep` is written on success and on NLS_STATUS_NOT_CONVERGED (then `out` is
/// untouched). `element` the element of a failure.
inline nls_status run_differential(const nls_differential_options& opt, const FlatMesh& in, FlatMesh& out, uint32_t& element,
                                   nls_differential_report& rep) {
  std::size_t su0 = 0, nv = 0, nf = 0, ni = 0, su = 0, sp = 0;
  element = NLS_NO_ELEMENT;
  nls_status s = nls_differential_scratch_size(in.vertex_count(), in.indices.size(), &su0);
  if (s != NLS_STATUS_OK) return s;
  std::vector<uint32_t> scratch(su0 + 1);
  s = nls_differential_plan(in.positions.data(), in.vertex_count(), in.offsets.data(), in.face_count(), in.indices.data(), in.indices.size(),
                            &opt, scratch.data(), scratch.size(), &nv, &nf, &ni, &su, &sp, &element);
  if (s != NLS_STATUS_OK) return s;
  scratch.assign(std::max(su, su0) + 1, 0);
  std::vector<double> spts(3 * sp + 3);
  std::vector<double> pos(3 * nv + 3, 0.0);
  std::vector<uint32_t> offs(nf + 1, 0), idx(ni + 1, 0);
  nls_differential_report r{};
  s = nls_differential_subdivide(in.positions.data(), in.vertex_count(), in.offsets.data(), in.face_count(), in.indices.data(),
                                 in.indices.size(), &opt, scratch.data(), scratch.size(), spts.data(), sp, pos.data(), nv, offs.data(), nf,
                                 idx.data(), ni, &nv, &nf, &ni, &r, &element);
  if (s == NLS_STATUS_OK || s == NLS_STATUS_NOT_CONVERGED) rep = r;
  if (s != NLS_STATUS_OK) return s;
  pos.resize(3 * nv);
  offs.resize(nf + 1);
  idx.resize(ni);
  out.positions = std::move(pos);
  out.offsets = std::move(offs);
  out.indices = std::move(idx);
  return NLS_STATUS_OK;
}

}  // namespace flat
}  // namespace nlsubdiv

#endif  // NLSUBDIV_FLAT_HH
