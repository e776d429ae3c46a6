// quadsimp: adaptive quad mesh simplification. SPDX-License-Identifier: GPL-3.0-or-later
#include "quadsimp/mesh/mesh_file.h"

#include <algorithm>
#include <stdexcept>
#include <unordered_map>

namespace qs {

FileTexture kept_texture(FileTexture t) {
  const auto coloured = [](int image) { return image < 0; };
  if (std::all_of(t.image.begin(), t.image.end(), coloured)) return {};
  if (std::none_of(t.image.begin(), t.image.end(), coloured)) t.colours.clear();
  return t;
}

MeshFile texture_colours_as_faces(const MeshFile& file) {
  if (file.texture.colours.size() != file.texture.triangles.size())
    throw std::invalid_argument("texture_colours_as_faces: the texture has no colour for each triangle");
  MeshFile out;
  out.positions = file.positions;
  out.colours = file.colours;
  out.triangles = file.texture.triangles;
  out.triangle_colours = file.texture.colours;
  return out;
}

MeshFile pair_faux_triangles(std::vector<Vec3> positions, std::vector<std::array<Index, 3>> tris,
                             const std::vector<std::uint8_t>& faux, const std::vector<Colour>& colours) {
  MeshFile out;
  out.positions = std::move(positions);
  const Index n = Index(tris.size());
  const bool coloured = !colours.empty() && colours.size() == tris.size();
  auto faux_edge = [&](Index t) {
    const unsigned b = faux[t] & 7u;
    return b == 1 ? 0 : b == 2 ? 1 : b == 4 ? 2 : -1;
  };
  const auto any_faux = [&] {
    for (Index t = 0; t < n; ++t)
      if (faux_edge(t) >= 0) return true;
    return false;
  };
  if (faux.size() != tris.size() || !any_faux()) {
    out.triangles = std::move(tris);
    if (coloured) out.triangle_colours = colours;
    return out;
  }
  // u's faux edge is t's faux edge reversed.
  auto partners = [&](Index t, Index u) {
    const int k = faux_edge(t), j = faux_edge(u);
    return j >= 0 && tris[t][k] == tris[u][(j + 1) % 3] && tris[t][(k + 1) % 3] == tris[u][j];
  };
  // vcglib and MeshLab put a polygon's two triangles next to each other, so the next
  // triangle is tried first. Otherwise: every triangle holding the reversed edge. Two
  // quads may touch at opposite corners, both split along that diagonal, so a directed
  // edge can have two holders.
  auto key = [](Index a, Index b) { return (std::uint64_t(a) << 32) | b; };
  std::unordered_multimap<std::uint64_t, Index> dir;  // built on first need
  std::vector<char> done(n, 0);
  // The partner of t, whose faux edge is k, or n.
  const auto partner = [&](Index t, int k) {
    if (t + 1 < n && !done[t + 1] && partners(t, t + 1)) return t + 1;
    if (dir.empty()) {
      dir.reserve(3 * std::size_t(n));
      for (Index x = 0; x < n; ++x)
        for (int i = 0; i < 3; ++i) dir.emplace(key(tris[x][i], tris[x][(i + 1) % 3]), x);
    }
    const auto range = dir.equal_range(key(tris[t][(k + 1) % 3], tris[t][k]));
    for (auto it = range.first; it != range.second; ++it)
      if (!done[it->second] && partners(t, it->second)) return it->second;
    return n;
  };
  for (Index t = 0; t < n; ++t) {
    if (done[t]) continue;
    done[t] = 1;
    const int k = faux_edge(t);
    const Index u = k >= 0 ? partner(t, k) : n;
    // A file of triangles and quads keeps its quads: fanned from their first corner, a
    // skewed quad was a cap, and a doublet (two quads on three corners, which MeshLab's
    // pairing leaves) two copies of one triangle once the other quad was split onto it.
    // triangles_of() splits them along their shorter diagonal, around doublets.
    if (u == n) {
      out.triangles.push_back(tris[t]);
      if (coloured) out.triangle_colours.push_back(colours[t]);
      continue;
    }
    done[u] = 1;
    const int j = faux_edge(u);
    out.quads.push_back({tris[t][(k + 2) % 3], tris[t][k], tris[u][(j + 2) % 3], tris[t][(k + 1) % 3]});
    if (coloured) out.quad_colours.push_back(colours[t]);
  }
  return out;
}

namespace {

// The two triangles of q split along corners 0-2, or 1-3 if `odd`.
void split_along(const std::array<Index, 4>& q, bool odd, std::vector<std::array<Index, 3>>& out) {
  if (!odd) {
    out.push_back({q[0], q[1], q[2]});
    out.push_back({q[0], q[2], q[3]});
  } else {
    out.push_back({q[0], q[1], q[3]});
    out.push_back({q[1], q[2], q[3]});
  }
}

// A set of 64-bit keys in one flat table (linear probing): the quads of a large input
// put millions of edges in it, and a node per key cost a fifth of the load time.
class KeySet {
 public:
  explicit KeySet(std::size_t n) {
    std::size_t size = 16;
    while (size < 2 * n) size *= 2;
    slots_.assign(size, kEmpty);
  }
  bool contains(std::uint64_t k) const { return slots_[find(k)] == k; }
  void insert(std::uint64_t k) { slots_[find(k)] = k; }

 private:
  static constexpr std::uint64_t kEmpty = ~std::uint64_t(0);  // no edge joins vertex kNone to itself
  std::size_t find(std::uint64_t k) const {
    const std::size_t mask = slots_.size() - 1;
    std::size_t i = std::size_t((k * 0x9E3779B97F4A7C15ull) >> 20) & mask;
    while (slots_[i] != kEmpty && slots_[i] != k) i = (i + 1) & mask;
    return i;
  }
  std::vector<std::uint64_t> slots_;
};

bool shorter_is_odd(const std::vector<Vec3>& p, const std::array<Index, 4>& q) {
  return (p[q[0]] - p[q[2]]).squaredNorm() > (p[q[1]] - p[q[3]]).squaredNorm();
}

}  // namespace

void split_quad(const std::vector<Vec3>& p, const std::array<Index, 4>& q, std::vector<std::array<Index, 3>>& out) {
  split_along(q, shorter_is_odd(p, q), out);
}

TriMesh triangles_of(const MeshFile& file) {
  TriMesh t;
  t.positions = file.positions;
  t.faces = file.triangles;
  // Two quads sharing two edges (a doublet, which MeshLab's own triangle pairing leaves)
  // were both split along the same corners: an edge of four triangles, which cleaning
  // refused as non-manifold. A file's own triangles count too: where a doublet had one
  // quad written as two triangles, the other was split onto them (MeshLab's pairing of the
  // moai with every seventh quad as triangles: 61 duplicate triangles, 447 caps and 72
  // folds to mend, 60% regular vertices at 200 quads against 85%). Vertices at one
  // position count as one because cleaning merges them where they are on a border: a quad
  // file whose slit has touching sides (our own output of a mesh that MeshLab's
  // subdivision had pinched) got the same split on both sides.
  if (file.quads.empty()) return t;
  const Index n = Index(file.positions.size());
  const std::vector<Index> same = first_equal_positions(file.positions);
  // A corner out of range is for cleaning to refuse with its message, not to be read here.
  const auto in_range = [&](const auto& face) {
    return std::all_of(face.begin(), face.end(), [&](Index v) { return v < n; });
  };
  auto key = [&](Index a, Index b) {
    a = same[a], b = same[b];
    return a < b ? std::uint64_t(a) << 32 | b : std::uint64_t(b) << 32 | a;
  };
  // At most 4 edges and 1 split per quad, under the 6 slots per quad KeySet makes of this;
  // 3 edges per triangle, under its 4.
  KeySet used(3 * file.quads.size() + 2 * file.triangles.size());
  for (const auto& q : file.quads)
    if (in_range(q))
      for (int k = 0; k < 4; ++k) used.insert(key(q[k], q[(k + 1) % 4]));
  for (const auto& f : file.triangles)
    if (in_range(f))
      for (int k = 0; k < 3; ++k) used.insert(key(f[k], f[(k + 1) % 3]));
  for (const auto& q : file.quads) {
    if (!in_range(q)) {
      split_along(q, false, t.faces);
      continue;
    }
    bool odd = shorter_is_odd(file.positions, q);
    const auto diagonal = [&](bool o) { return o ? key(q[1], q[3]) : key(q[0], q[2]); };
    if (used.contains(diagonal(odd)) && !used.contains(diagonal(!odd))) odd = !odd;
    used.insert(diagonal(odd));
    split_along(q, odd, t.faces);
  }
  return t;
}

std::vector<Colour> triangle_colours_of(const MeshFile& file) {
  if (file.triangle_colours.size() != file.triangles.size() || file.quad_colours.size() != file.quads.size() ||
      (file.triangle_colours.empty() && file.quad_colours.empty()))
    return {};
  // triangles_of() lists the file's triangles, then each quad's two.
  std::vector<Colour> out = file.triangle_colours;
  out.reserve(file.triangles.size() + 2 * file.quads.size());
  for (const Colour& c : file.quad_colours) out.insert(out.end(), 2, c);
  return out;
}

}  // namespace qs
