// peer_subdivide: run one peer library's linear subdivision on an OFF mesh.
//
//   peer_subdivide LIBRARY SCHEME LEVELS IN.off OUT.off
//   peer_subdivide --list
//
// LIBRARY: openmesh | cgal | osd.  SCHEME: loop | catmull-clark | butterfly |
// doo-sabin | sqrt3 (see --list for the supported pairs).  OUT.off may be "-"
// for stdout. Exit status: 0 ok, 1 usage / I/O error, 2 mesh rejected (by the
// reader, the validator or the library; reason on stderr), 3 the library does
// not implement the scheme. The program never aborts on bad input: every
// face list is validated before it reaches a library (OpenMesh 9 aborts on
// repeated-vertex faces, 2-vertex faces and closing fans).
//
// See peers/README.md.

#include "peer_common.hpp"

#include <algorithm>
#include <chrono>
#include <cerrno>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <exception>
#include <fstream>
#include <iterator>
#include <new>
#include <sstream>
#include <string>
#include <string_view>
#include <vector>

namespace peer {
namespace {

// ---------------------------------------------------------------- OFF reader
//
// Tolerant ASCII OFF: '#' comments (whole-line or trailing), blank lines,
// CRLF/CR line ends, counts on the header line or the next line, the
// OFF/COFF/NOFF/CNOFF/STOFF headers (per-vertex and per-face extras after the
// needed numbers are ignored), faces and vertices wrapped over several lines.

class LineReader {
 public:
  explicit LineReader(const std::string& text) : s_(text) {}

  // Next non-empty line (comments stripped) split into tokens; false at EOF.
  bool next(std::vector<std::string_view>& toks) {
    toks.clear();
    while (pos_ < s_.size()) {
      std::size_t end = pos_;
      while (end < s_.size() && s_[end] != '\n' && s_[end] != '\r') ++end;
      std::string_view line(s_.data() + pos_, end - pos_);
      // skip the line break (\n, \r, or \r\n)
      pos_ = end;
      if (pos_ < s_.size() && s_[pos_] == '\r') ++pos_;
      if (pos_ < s_.size() && s_[pos_] == '\n') ++pos_;
      ++lineno_;
      std::size_t hash = line.find('#');
      if (hash != std::string_view::npos) line = line.substr(0, hash);
      std::size_t i = 0;
      while (i < line.size()) {
        while (i < line.size() && is_space(line[i])) ++i;
        std::size_t j = i;
        while (j < line.size() && !is_space(line[j])) ++j;
        if (j > i) toks.push_back(line.substr(i, j - i));
        i = j;
      }
      if (!toks.empty()) return true;
    }
    return false;
  }
  std::size_t lineno() const { return lineno_; }

 private:
  static bool is_space(char c) { return c == ' ' || c == '\t' || c == '\v' || c == '\f'; }
  const std::string& s_;
  std::size_t pos_ = 0;
  std::size_t lineno_ = 0;
};

bool parse_double(std::string_view t, double& v) {
  char buf[128];
  if (t.empty() || t.size() >= sizeof buf) return false;
  std::memcpy(buf, t.data(), t.size());
  buf[t.size()] = '\0';
  char* end = nullptr;
  errno = 0;
  v = std::strtod(buf, &end);
  return end == buf + t.size();  // ERANGE (overflow to inf / underflow) is judged later
}

bool parse_int(std::string_view t, long long& v) {
  char buf[64];
  if (t.empty() || t.size() >= sizeof buf) return false;
  std::memcpy(buf, t.data(), t.size());
  buf[t.size()] = '\0';
  char* end = nullptr;
  errno = 0;
  v = std::strtoll(buf, &end, 10);
  return end == buf + t.size() && errno == 0;
}

std::string sv(std::string_view t) { return std::string(t.substr(0, 40)); }

// Collects `need` tokens starting with the tokens of the current line after
// index `from`, continuing on following lines if the record is wrapped.
bool gather(LineReader& lr, std::vector<std::string_view>& toks, std::size_t from,
            std::size_t need, std::vector<std::string_view>& out) {
  out.clear();
  for (std::size_t i = from; i < toks.size() && out.size() < need; ++i) out.push_back(toks[i]);
  while (out.size() < need) {
    if (!lr.next(toks)) return false;
    for (std::size_t i = 0; i < toks.size() && out.size() < need; ++i) out.push_back(toks[i]);
  }
  return true;
}

bool read_off(const std::string& path, Mesh& m, std::string& err) {
  m.clear();
  std::ifstream f(path, std::ios::binary);
  if (!f) { err = "cannot open '" + path + "'"; return false; }
  std::string text((std::istreambuf_iterator<char>(f)), std::istreambuf_iterator<char>());
  if (f.bad()) { err = "read error on '" + path + "'"; return false; }
  if (text.size() >= 3 && (unsigned char)text[0] == 0xEF && (unsigned char)text[1] == 0xBB &&
      (unsigned char)text[2] == 0xBF)
    text.erase(0, 3);  // UTF-8 BOM

  LineReader lr(text);
  std::vector<std::string_view> toks, rec;
  if (!lr.next(toks)) { err = "empty file"; return false; }
  std::string_view head = toks[0];
  static const char* const kHeads[] = {"OFF", "COFF", "NOFF", "CNOFF", "STOFF", "STCOFF",
                                       "STNOFF", "STCNOFF"};
  bool known = false;
  for (const char* h : kHeads) known = known || head == h;
  if (!known) { err = "not an ASCII OFF file (header '" + sv(head) + "')"; return false; }
  if (toks.size() >= 2 && toks[1] == "BINARY") { err = "binary OFF is not supported"; return false; }
  std::size_t from = 1;
  if (toks.size() < 2) {
    if (!lr.next(toks)) { err = "missing counts line"; return false; }
    from = 0;
  }
  if (!gather(lr, toks, from, 2, rec)) { err = "missing vertex/face counts"; return false; }
  long long nv = 0, nf = 0;
  if (!parse_int(rec[0], nv) || !parse_int(rec[1], nf) || nv < 0 || nf < 0) {
    err = "bad counts '" + sv(rec[0]) + " " + sv(rec[1]) + "'";
    return false;
  }
  const long long kMax = 50000000;  // refuse absurd headers instead of allocating
  if (nv > kMax || nf > kMax) { err = "counts too large"; return false; }
  m.xyz.reserve(std::size_t(std::min<long long>(nv, 1 << 22)) * 3);

  for (long long i = 0; i < nv; ++i) {
    if (!lr.next(toks) || !gather(lr, toks, 0, 3, rec)) {
      err = "file ends in vertex " + std::to_string(i) + " of " + std::to_string(nv);
      return false;
    }
    double c[3];
    for (int k = 0; k < 3; ++k) {
      if (!parse_double(rec[k], c[k])) {
        err = "vertex " + std::to_string(i) + ": bad number '" + sv(rec[k]) + "' (line " +
              std::to_string(lr.lineno()) + ")";
        return false;
      }
    }
    m.add_vertex(c[0], c[1], c[2]);
  }
  for (long long i = 0; i < nf; ++i) {
    long long n = 0;
    if (!lr.next(toks)) {
      err = "file ends in face " + std::to_string(i) + " of " + std::to_string(nf);
      return false;
    }
    if (!parse_int(toks[0], n) || n < 0 || n > 1000000) {
      err = "face " + std::to_string(i) + ": bad size '" + sv(toks[0]) + "' (line " +
            std::to_string(lr.lineno()) + ")";
      return false;
    }
    if (!gather(lr, toks, 1, std::size_t(n), rec)) {
      err = "file ends in face " + std::to_string(i) + " of " + std::to_string(nf);
      return false;
    }
    m.fsize.push_back(int(n));
    for (long long k = 0; k < n; ++k) {
      long long idx = 0;
      if (!parse_int(rec[std::size_t(k)], idx)) {
        err = "face " + std::to_string(i) + ": bad index '" + sv(rec[std::size_t(k)]) + "'";
        return false;
      }
      if (idx < 0 || idx >= nv) {
        err = "face " + std::to_string(i) + ": index " + std::to_string(idx) +
              " out of range [0, " + std::to_string(nv) + ")";
        return false;
      }
      m.fidx.push_back(int(idx));
    }
  }
  return true;
}

// ---------------------------------------------------------------- OFF writer

bool write_off(const std::string& path, const Mesh& m, std::string& err) {
  FILE* f = path == "-" ? stdout : std::fopen(path.c_str(), "wb");
  if (!f) { err = "cannot create '" + path + "': " + std::strerror(errno); return false; }
  static char buf[1 << 16];
  if (f != stdout) std::setvbuf(f, buf, _IOFBF, sizeof buf);
  std::fprintf(f, "OFF\n%zu %zu 0\n", m.nv(), m.nf());
  for (std::size_t v = 0; v < m.nv(); ++v)
    std::fprintf(f, "%.17g %.17g %.17g\n", m.xyz[3 * v], m.xyz[3 * v + 1], m.xyz[3 * v + 2]);
  std::size_t k = 0;
  for (std::size_t fi = 0; fi < m.nf(); ++fi) {
    std::fprintf(f, "%d", m.fsize[fi]);
    for (int j = 0; j < m.fsize[fi]; ++j) std::fprintf(f, " %d", m.fidx[k++]);
    std::fputc('\n', f);
  }
  bool ok = !std::ferror(f);
  if (f == stdout) ok = (std::fflush(f) == 0) && ok;
  else ok = (std::fclose(f) == 0) && ok;
  if (!ok) err = "write error on '" + path + "'";
  return ok;
}

// ---------------------------------------------------------------- validation

bool validate_basic(const Mesh& m, std::string& err) {
  if (m.nv() == 0 || m.nf() == 0) { err = "empty mesh (no vertices or no faces)"; return false; }
  for (std::size_t v = 0; v < m.nv(); ++v)
    for (int k = 0; k < 3; ++k)
      if (!std::isfinite(m.xyz[3 * v + k])) {
        err = "vertex " + std::to_string(v) + " has a non-finite coordinate";
        return false;
      }
  std::size_t s = 0;
  for (std::size_t f = 0; f < m.nf(); ++f) {
    int n = m.fsize[f];
    if (n < 3) {
      err = "face " + std::to_string(f) + " has " + std::to_string(n) + " vertices (< 3)";
      return false;
    }
    for (int i = 0; i < n; ++i)
      for (int j = i + 1; j < n; ++j)
        if (m.fidx[s + i] == m.fidx[s + j]) {
          err = "face " + std::to_string(f) + " repeats vertex " + std::to_string(m.fidx[s + i]);
          return false;
        }
    s += std::size_t(n);
  }
  return true;
}

// Library output: finite coordinates, indices in range, no repeated index in a
// face. Faces of 2 vertices are kept: CGAL's Doo-Sabin turns a valence-2
// vertex into a two-sided vertex face, which is its legitimate result.
bool validate_output(const Mesh& m, std::string& err) {
  for (std::size_t v = 0; v < m.nv(); ++v)
    for (int k = 0; k < 3; ++k)
      if (!std::isfinite(m.xyz[3 * v + k])) {
        err = "vertex " + std::to_string(v) + " has a non-finite coordinate";
        return false;
      }
  std::size_t s = 0;
  for (std::size_t f = 0; f < m.nf(); ++f) {
    int n = m.fsize[f];
    if (n < 2) { err = "face " + std::to_string(f) + " has < 2 vertices"; return false; }
    for (int i = 0; i < n; ++i) {
      int a = m.fidx[s + i];
      if (a < 0 || std::size_t(a) >= m.nv()) {
        err = "face " + std::to_string(f) + " has index " + std::to_string(a) + " out of range";
        return false;
      }
      for (int j = i + 1; j < n; ++j)
        if (a == m.fidx[s + j]) {
          err = "face " + std::to_string(f) + " repeats vertex " + std::to_string(a);
          return false;
        }
    }
    s += std::size_t(n);
  }
  return true;
}

bool all_triangles(const Mesh& m) {
  return std::all_of(m.fsize.begin(), m.fsize.end(), [](int n) { return n == 3; });
}

// Removes vertices that no face uses (every peer mishandles them: OpenMesh
// moves them to garbage, CGAL's hosts expect a halfedge). Returns the count.
std::size_t drop_unreferenced(Mesh& m) {
  std::vector<int> remap(m.nv(), -1);
  for (int i : m.fidx) remap[std::size_t(i)] = 0;
  std::size_t n = 0;
  std::vector<double> xyz;
  xyz.reserve(m.xyz.size());
  for (std::size_t v = 0; v < m.nv(); ++v)
    if (remap[v] == 0) {
      remap[v] = int(n++);
      xyz.insert(xyz.end(), m.xyz.begin() + 3 * v, m.xyz.begin() + 3 * v + 3);
    }
  std::size_t dropped = m.nv() - n;
  if (dropped) {
    for (int& i : m.fidx) i = remap[std::size_t(i)];
    m.xyz.swap(xyz);
  }
  return dropped;
}

// Oriented 2-manifold with boundary: every directed edge used once (this
// also excludes edges with > 2 faces and inconsistent orientation), and the
// faces around every vertex form one fan (a disk or a half-disk).
bool validate_manifold(const Mesh& m, std::string& err) {
  const std::uint64_t nv = m.nv();
  std::vector<std::uint64_t> dir;
  dir.reserve(m.fidx.size());
  // corners per vertex: (next, prev) = a link edge from next to prev
  std::vector<std::size_t> cstart(nv + 1, 0);
  for (int i : m.fidx) ++cstart[std::size_t(i) + 1];
  for (std::size_t v = 0; v < nv; ++v) cstart[v + 1] += cstart[v];
  std::vector<std::size_t> fill(cstart.begin(), cstart.end() - 1);
  std::vector<std::pair<int, int>> link(m.fidx.size());
  std::size_t s = 0;
  for (std::size_t f = 0; f < m.nf(); ++f) {
    int n = m.fsize[f];
    for (int i = 0; i < n; ++i) {
      int a = m.fidx[s + i], b = m.fidx[s + (i + 1) % n], p = m.fidx[s + (i + n - 1) % n];
      dir.push_back(std::uint64_t(a) * nv + std::uint64_t(b));
      link[fill[std::size_t(a)]++] = {b, p};
    }
    s += std::size_t(n);
  }
  std::sort(dir.begin(), dir.end());
  auto dup = std::adjacent_find(dir.begin(), dir.end());
  if (dup != dir.end()) {
    err = "edge (" + std::to_string(*dup / nv) + "," + std::to_string(*dup % nv) +
          ") is used twice in the same direction (edge with > 2 faces, duplicate face or "
          "inconsistent orientation)";
    return false;
  }
  std::vector<std::pair<int, int>> cs;
  std::vector<int> tos;
  for (std::size_t v = 0; v < nv; ++v) {
    cs.assign(link.begin() + cstart[v], link.begin() + cstart[v + 1]);
    std::size_t k = cs.size();
    if (k == 0) continue;
    std::sort(cs.begin(), cs.end());  // by 'from' (unique, since directed edges are)
    tos.clear();
    for (auto& c : cs) tos.push_back(c.second);
    std::sort(tos.begin(), tos.end());
    // starts: 'from' nodes that are nobody's 'to'
    int start = cs[0].first;
    std::size_t nstarts = 0;
    for (auto& c : cs)
      if (!std::binary_search(tos.begin(), tos.end(), c.first)) { ++nstarts; start = c.first; }
    if (nstarts > 1) {
      err = "vertex " + std::to_string(v) + " is non-manifold (" + std::to_string(nstarts) +
            " separate face fans)";
      return false;
    }
    std::size_t steps = 0;
    int cur = start;
    while (steps <= k) {
      auto it = std::lower_bound(cs.begin(), cs.end(), std::make_pair(cur, INT32_MIN));
      if (it == cs.end() || it->first != cur) break;
      cur = it->second;
      ++steps;
      if (nstarts == 0 && cur == start) break;
    }
    if (steps != k) {
      err = "vertex " + std::to_string(v) + " is non-manifold (its faces form several fans)";
      return false;
    }
  }
  return true;
}

// ---------------------------------------------------------------- dispatch

struct SchemeName { const char* name; Scheme s; };
const SchemeName kSchemes[] = {{"loop", Scheme::Loop},
                               {"catmull-clark", Scheme::CatmullClark},
                               {"butterfly", Scheme::Butterfly},
                               {"doo-sabin", Scheme::DooSabin},
                               {"sqrt3", Scheme::Sqrt3}};

bool supported(const std::string& lib, Scheme s) {
  if (lib == "openmesh")
    return s == Scheme::Loop || s == Scheme::CatmullClark || s == Scheme::Butterfly ||
           s == Scheme::Sqrt3;
  if (lib == "cgal")
    return s == Scheme::Loop || s == Scheme::CatmullClark || s == Scheme::DooSabin ||
           s == Scheme::Sqrt3;
  if (lib == "osd") return s == Scheme::Loop || s == Scheme::CatmullClark;
  return false;
}

const char* kWhat[] = {
    "openmesh loop           OpenMesh::Subdivider::Uniform::LoopT (TriMesh, double)",
    "openmesh catmull-clark  OpenMesh::Subdivider::Uniform::CatmullClarkT (PolyMesh, double)",
    "openmesh butterfly      OpenMesh::Subdivider::Uniform::ModifiedButterflyT (TriMesh, double)",
    "openmesh sqrt3          OpenMesh::Subdivider::Uniform::Sqrt3T (TriMesh, double)",
    "cgal loop               CGAL::Subdivision_method_3::Loop_subdivision (Surface_mesh)",
    "cgal catmull-clark      CGAL::Subdivision_method_3::CatmullClark_subdivision",
    "cgal doo-sabin          CGAL::Subdivision_method_3::DooSabin_subdivision",
    "cgal sqrt3              CGAL::Subdivision_method_3::Sqrt3_subdivision",
    "osd loop                Far::TopologyRefiner SCHEME_LOOP, VTX_BOUNDARY_EDGE_ONLY",
    "osd catmull-clark       Far::TopologyRefiner SCHEME_CATMARK, VTX_BOUNDARY_EDGE_ONLY",
};

int usage(const char* argv0) {
  std::fprintf(stderr,
               "usage: %s LIBRARY SCHEME LEVELS IN.off OUT.off   (OUT '-' = stdout)\n"
               "       %s --list\n"
               "LIBRARY: openmesh | cgal | osd; SCHEME: loop | catmull-clark | butterfly | "
               "doo-sabin | sqrt3; LEVELS: 0..8\n"
               "exit: 0 ok, 1 usage/IO error, 2 mesh rejected, 3 scheme not in library\n",
               argv0, argv0);
  return EXIT_USAGE;
}

int run(int argc, char** argv) {
  if (argc == 2 && (std::strcmp(argv[1], "--list") == 0)) {
    for (const char* w : kWhat) std::printf("%s\n", w);
    return EXIT_OK;
  }
  if (argc == 2 && (std::strcmp(argv[1], "--help") == 0 || std::strcmp(argv[1], "-h") == 0)) {
    usage(argv[0]);
    return EXIT_OK;
  }
  if (argc != 6) return usage(argv[0]);
  const std::string lib = argv[1], scheme_name = argv[2], in_path = argv[4], out_path = argv[5];
  if (lib != "openmesh" && lib != "cgal" && lib != "osd") {
    std::fprintf(stderr, "peer_subdivide: unknown library '%s'\n", lib.c_str());
    return usage(argv[0]);
  }
  const SchemeName* sn = nullptr;
  for (const auto& x : kSchemes)
    if (scheme_name == x.name) sn = &x;
  if (!sn) {
    std::fprintf(stderr, "peer_subdivide: unknown scheme '%s'\n", scheme_name.c_str());
    return usage(argv[0]);
  }
  long long levels = -1;
  if (!parse_int(argv[3], levels) || levels < 0 || levels > 8) {
    std::fprintf(stderr, "peer_subdivide: LEVELS must be an integer in 0..8\n");
    return usage(argv[0]);
  }
  if (!supported(lib, sn->s)) {
    std::fprintf(stderr, "peer_subdivide: %s does not implement %s\n", lib.c_str(), sn->name);
    return EXIT_UNSUPPORTED;
  }

  Mesh in;
  std::string err;
  if (!read_off(in_path, in, err)) {
    std::fprintf(stderr, "peer_subdivide: rejected: %s: %s\n", in_path.c_str(), err.c_str());
    // a missing file is an I/O error, a malformed one a rejected mesh
    return err.rfind("cannot open", 0) == 0 ? EXIT_USAGE : EXIT_REJECTED;
  }
  if (!validate_basic(in, err)) {
    std::fprintf(stderr, "peer_subdivide: rejected: %s\n", err.c_str());
    return EXIT_REJECTED;
  }
  if (std::size_t d = drop_unreferenced(in))
    std::fprintf(stderr, "peer_subdivide: note: dropped %zu unreferenced vertices\n", d);
  const bool tri_only =
      sn->s == Scheme::Loop || sn->s == Scheme::Butterfly || sn->s == Scheme::Sqrt3;
  if (tri_only && !all_triangles(in)) {
    std::fprintf(stderr, "peer_subdivide: rejected: %s needs a triangle mesh\n", sn->name);
    return EXIT_REJECTED;
  }
  // CGAL checks the soup itself first (so its own verdict is reported), then
  // this validator; OpenMesh 9 must never see a non-manifold face list.
  if (lib == "openmesh" && !validate_manifold(in, err)) {
    std::fprintf(stderr, "peer_subdivide: rejected: %s\n", err.c_str());
    return EXIT_REJECTED;
  }
  // Output size guard: faces grow by <= 4x per level after the first
  // (first level: sum of face sizes, or 3x for sqrt3 / n+... for Doo-Sabin).
  {
    double faces = double(in.fidx.size()) + double(in.nv());
    for (long long l = 1; l < levels; ++l) faces *= 4.0;
    if (levels > 0 && faces > 6.0e7) {
      std::fprintf(stderr, "peer_subdivide: output would have ~%.3g faces; refusing\n", faces);
      return EXIT_USAGE;
    }
  }

  Mesh out;
  Outcome o;
  // Wall time of the library's part (building its mesh, subdividing, reading the result
  // back), printed for scripts/bench_peers.py; file I/O is not included.
  const auto t0 = std::chrono::steady_clock::now();
  try {
    if (lib == "openmesh") o = run_openmesh(sn->s, int(levels), in, out);
    else if (lib == "cgal") o = run_cgal(sn->s, int(levels), in, out);
    else o = run_osd(sn->s, int(levels), in, out);
    const double ms =
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
    std::fprintf(stderr, "peer_subdivide: time_ms=%.3f\n", ms);
  } catch (const std::bad_alloc&) {
    std::fprintf(stderr, "peer_subdivide: out of memory in %s\n", lib.c_str());
    return EXIT_USAGE;
  } catch (const std::exception& e) {
    o = Outcome::reject(std::string("error: ") + lib + " threw: " + e.what());
  } catch (...) {
    o = Outcome::reject("error: " + lib + " threw an unknown exception");
  }
  if (o.status != EXIT_OK) {
    std::fprintf(stderr, "peer_subdivide: rejected: %s\n", o.msg.c_str());
    return o.status;
  }
  if (!validate_output(out, err)) {  // a peer result we cannot trust
    std::fprintf(stderr, "peer_subdivide: rejected: %s produced an invalid mesh: %s\n",
                 lib.c_str(), err.c_str());
    return EXIT_REJECTED;
  }
  if (std::size_t d = std::count(out.fsize.begin(), out.fsize.end(), 2))
    std::fprintf(stderr,
                 "peer_subdivide: note: output has %zu two-vertex faces (Doo-Sabin vertex faces "
                 "of valence-2 vertices)\n", d);
  if (!write_off(out_path, out, err)) {
    std::fprintf(stderr, "peer_subdivide: %s\n", err.c_str());
    return EXIT_USAGE;
  }
  return EXIT_OK;
}

}  // namespace

// Validation entry points used by the CGAL backend as a safety net.
bool validate_manifold_mesh(const Mesh& m, std::string& err) { return validate_manifold(m, err); }

}  // namespace peer

int main(int argc, char** argv) {
  try {
    return peer::run(argc, argv);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "peer_subdivide: fatal: %s\n", e.what());
  } catch (...) {
    std::fprintf(stderr, "peer_subdivide: fatal: unknown exception\n");
  }
  return peer::EXIT_USAGE;
}
