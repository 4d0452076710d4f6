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

/// What kind of element a status names, for messages ("face 3", "vertex 7"): the statuses of
/// validation name a face or a vertex, those of the computation an output vertex of the
/// level, the tag statuses a tag; "element" where the status can name either.
inline const char* element_kind(nls_status s) {
  switch (s) {
    case NLS_STATUS_BAD_OFFSETS:
    case NLS_STATUS_FACE_TOO_SMALL:
    case NLS_STATUS_INDEX_OUT_OF_RANGE:
    case NLS_STATUS_REPEATED_VERTEX:
    case NLS_STATUS_NON_MANIFOLD_EDGE:
    case NLS_STATUS_INCONSISTENT_ORIENTATION:
    case NLS_STATUS_DUPLICATE_FACE:
    case NLS_STATUS_UNSUPPORTED_FACE_TYPE:
      return "face";
    case NLS_STATUS_NON_MANIFOLD_VERTEX:
    case NLS_STATUS_NON_FINITE_INPUT:
      return "vertex";
    case NLS_STATUS_FALLBACK_IN_STRICT_MODE:
    case NLS_STATUS_NUMERICAL_FAILURE:
      return "output vertex";
    case NLS_STATUS_TAG_NOT_AN_EDGE:
    case NLS_STATUS_REPEATED_TAG:
    case NLS_STATUS_INVALID_SHARPNESS:
      return "tag";
    default:
      return "element";
  }
}

/// A polygon mesh as the C ABI takes it (positions, CSR offsets and indices).
struct FlatMesh {
  std::vector<double> positions;   ///< 3 per vertex
  std::vector<uint32_t> offsets;   ///< face_count + 1
  std::vector<uint32_t> indices;   ///< corners, faces counter-clockwise
  std::size_t vertex_count() const { return positions.size() / 3; }
  std::size_t face_count() const { return offsets.empty() ? 0 : offsets.size() - 1; }
};

/// The C ABI's view of `flat` (packed positions).
inline nls_mesh_view view_of(const FlatMesh& flat) {
  nls_mesh_view v{};
  v.positions = flat.positions.data();
  v.vertex_count = flat.vertex_count();
  v.positions_stride = 0;
  v.offsets = flat.offsets.data();
  v.face_count = flat.face_count();
  v.indices = flat.indices.data();
  v.index_count = flat.indices.size();
  return v;
}

/// The C ABI's view of a vertex star: centre `v`, `n` neighbours packed in `ring`, closed or
/// open, and (Catmull–Clark) the corners of its faces.
inline nls_star_view star_of(const double* v, const double* ring, std::size_t n, bool closed, const uint32_t* face_offsets = nullptr,
                             std::size_t face_count = 0, const double* face_corners = nullptr, std::size_t corner_count = 0) {
  nls_star_view s{};
  s.v = v;
  s.ring = ring;
  s.ring_count = n;
  s.closed = closed ? 1u : 0u;
  s.face_offsets = face_offsets;
  s.face_count = face_count;
  s.face_corners = face_corners;
  s.corner_count = corner_count;
  return s;
}

/// Options for `levels` levels of `scheme` with `flags`, from the library's defaults.
inline nls_subdivide_options options_of(uint32_t scheme, uint32_t flags, uint32_t levels) {
  nls_subdivide_options o{};
  nls_subdivide_default_options(&o);
  o.scheme = scheme;
  o.flags = flags;
  o.levels = levels;
  return o;
}

/// Validates `flat` for one level of `scheme` with `flags` (nls_mesh_plan).
inline nls_status validate(uint32_t scheme, uint32_t flags, const FlatMesh& flat, uint32_t& element) {
  const nls_mesh_view v = view_of(flat);
  const nls_subdivide_options o = options_of(scheme, flags, 1);
  std::size_t su = 0;
  nls_status s = nls_mesh_plan_scratch_size(&v, &su);
  if (s != NLS_STATUS_OK) return s;
  std::vector<uint32_t> scratch(su + 1);
  nls_plan plan{};
  return nls_mesh_plan(&v, &o, scratch.data(), scratch.size(), &plan, &element);
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

/// `levels` levels of `scheme` with `flags` on `in` through nls_mesh_plan and
/// nls_mesh_subdivide (exact sizes first, then one call); `out` receives the result.
/// `element` the element of a failure, `fallbacks` the report's count. With `tags` (sharp
/// features: crease edges as vertex pairs, corners) the _tagged calls, which carry the tags
/// level by level inside the one call. `linear_weight` is nls_subdivide_options::linear_weight
/// (the Möbius–linear spectrum, seed 000 §7.2: 0 Möbius, 1 linear; read with
/// NLS_SUBDIVIDE_MOBIUS); `linear_weights` (NULL, or one per vertex of `in`) is
/// nls_subdivide_options::linear_weights, the same weight per input vertex, replacing it.
/// `executor` is nls_subdivide_options::executor (NULL: the calling thread; a ThreadPool's,
/// nlsubdiv_pool.hh: the same bits on its threads).
inline nls_status run_levels(uint32_t scheme, uint32_t flags, const FlatMesh& in, uint32_t levels, FlatMesh& out, uint32_t& element,
                             uint32_t& fallbacks, const nls_tags* tags = nullptr, double linear_weight = 0.0,
                             const double* linear_weights = nullptr, const nls_executor* executor = nullptr) {
  const nls_mesh_view v = view_of(in);
  nls_subdivide_options o = options_of(scheme, flags, levels);
  o.linear_weight = linear_weight;
  o.linear_weights = linear_weights;
  o.executor = executor;
  std::size_t su0 = 0;
  element = NLS_NO_ELEMENT;
  nls_status s = tags ? nls_mesh_plan_scratch_size_tagged(&v, tags, &su0) : nls_mesh_plan_scratch_size(&v, &su0);
  if (s != NLS_STATUS_OK) return s;
  std::vector<uint32_t> scratch(su0 + 1);
  nls_plan plan{};
  s = tags ? nls_mesh_plan_tagged(&v, &o, tags, scratch.data(), scratch.size(), &plan, &element)
           : nls_mesh_plan(&v, &o, scratch.data(), scratch.size(), &plan, &element);
  if (s != NLS_STATUS_OK) return s;
  const std::size_t nv = plan.output.vertex_count, nf = plan.output.face_count, ni = plan.output.index_count;
  scratch.assign(std::max(plan.scratch_u32, su0) + 1, 0);
  std::vector<double> spts(3 * plan.scratch_points + 3);
  out.positions.assign(3 * nv + 3, 0.0);
  out.offsets.assign(nf + 1, 0);
  out.indices.assign(ni + 1, 0);
  const nls_scratch sc{scratch.data(), scratch.size(), spts.data(), plan.scratch_points};
  const nls_mesh_buffers b{out.positions.data(), nv, out.offsets.data(), nf, out.indices.data(), ni};
  nls_mesh_sizes written{};
  nls_subdivide_report rep{};
  s = tags ? nls_mesh_subdivide_tagged(&v, &o, tags, &sc, &b, &written, &rep, &element)
           : nls_mesh_subdivide(&v, &o, &sc, &b, &written, &rep, &element);
  if (s != NLS_STATUS_OK) return s;
  out.positions.resize(3 * written.vertex_count);
  out.offsets.resize(written.face_count + 1);
  out.indices.resize(written.index_count);
  fallbacks = rep.fallbacks;
  return NLS_STATUS_OK;
}

/// Differential-space subdivision of `in` (triangles) with `opt` (its `levels` levels in one
/// call: the reconstruction is global, so k levels are one solve, not k solves of one level)
/// through nls_differential_plan + nls_differential_subdivide. `out` receives the result on
/// success; `rep` is written on success, on NLS_STATUS_NOT_CONVERGED and on
/// NLS_STATUS_FOLDED_SURFACE (then `out` is untouched). `element` the element of a failure.
inline nls_status run_differential(const nls_differential_options& opt, const FlatMesh& in, FlatMesh& out, uint32_t& element,
                                   nls_differential_report& rep) {
  const nls_mesh_view v = view_of(in);
  std::size_t su0 = 0;
  element = NLS_NO_ELEMENT;
  nls_status s = nls_mesh_plan_scratch_size(&v, &su0);
  if (s != NLS_STATUS_OK) return s;
  std::vector<uint32_t> scratch(su0 + 1);
  nls_plan plan{};
  s = nls_differential_plan(&v, &opt, scratch.data(), scratch.size(), &plan, &element);
  if (s != NLS_STATUS_OK) return s;
  const std::size_t nv = plan.output.vertex_count, nf = plan.output.face_count, ni = plan.output.index_count;
  scratch.assign(std::max(plan.scratch_u32, su0) + 1, 0);
  std::vector<double> spts(3 * plan.scratch_points + 3);
  std::vector<double> pos(3 * nv + 3, 0.0);
  std::vector<uint32_t> offs(nf + 1, 0), idx(ni + 1, 0);
  const nls_scratch sc{scratch.data(), scratch.size(), spts.data(), plan.scratch_points};
  const nls_mesh_buffers b{pos.data(), nv, offs.data(), nf, idx.data(), ni};
  nls_mesh_sizes written{};
  nls_differential_report r{};
  s = nls_differential_subdivide(&v, &opt, &sc, &b, &written, &r, &element);
  if (s == NLS_STATUS_OK || s == NLS_STATUS_NOT_CONVERGED || s == NLS_STATUS_FOLDED_SURFACE) rep = r;
  if (s != NLS_STATUS_OK) return s;
  pos.resize(3 * written.vertex_count);
  offs.resize(written.face_count + 1);
  idx.resize(written.index_count);
  out.positions = std::move(pos);
  out.offsets = std::move(offs);
  out.indices = std::move(idx);
  return NLS_STATUS_OK;
}

/// Sharp-feature tags built by a host from its own feature flags: crease edges as vertex
/// pairs with one sharpness each, corner vertices with theirs. `view()` is the C struct over
/// these arrays (valid while this object lives and is not changed).
struct FlatTags {
  std::vector<uint32_t> crease_vertices;  ///< 2 per crease
  std::vector<double> crease_sharpness;   ///< 1 per crease
  std::vector<uint32_t> corner_vertices;
  std::vector<double> corner_sharpness;
  uint32_t method = NLS_CREASE_UNIFORM;
  bool empty() const { return crease_sharpness.empty() && corner_sharpness.empty(); }
  nls_tags view() const {
    nls_tags t{};
    t.crease_vertices = crease_vertices.data();
    t.crease_sharpness = crease_sharpness.data();
    t.crease_count = crease_sharpness.size();
    t.corner_vertices = corner_vertices.data();
    t.corner_sharpness = corner_sharpness.data();
    t.corner_count = corner_sharpness.size();
    t.method = method;
    return t;
  }
};

}  // namespace flat
}  // namespace nlsubdiv

#endif  // NLSUBDIV_FLAT_HH
