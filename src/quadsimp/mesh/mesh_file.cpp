// quadsimp: adaptive quad mesh simplification. SPDX-License-Identifier: GPL-3.0-or-later
#include "quadsimp/mesh/mesh_file.h"

#include <unordered_map>

namespace qs {

MeshFile pair_faux_triangles(std::vector<Vec3> positions, std::vector<std::array<Index, 3>> tris,
                             const std::vector<std::uint8_t>& faux) {
  MeshFile out;
  out.positions = std::move(positions);
  std::unordered_map<std::uint64_t, Index> dir;
  dir.reserve(3 * tris.size());
  for (Index t = 0; t < tris.size(); ++t)
    for (int k = 0; k < 3; ++k) dir[(std::uint64_t(tris[t][k]) << 32) | tris[t][(k + 1) % 3]] = t;
  bool pure = !tris.empty() && faux.size() == tris.size();
  std::vector<std::array<Index, 4>> quads;
  for (Index t = 0; t < tris.size() && pure; ++t) {
    const unsigned b = faux[t] & 7u;
    if (b != 1 && b != 2 && b != 4) {
      pure = false;
      break;
    }
    const int k = b == 1 ? 0 : b == 2 ? 1 : 2;
    const Index a = tris[t][k], c = tris[t][(k + 1) % 3], apex = tris[t][(k + 2) % 3];
    const auto it = dir.find((std::uint64_t(c) << 32) | a);
    if (it == dir.end()) {
      pure = false;
      break;
    }
    const Index u = it->second;
    const auto& o = tris[u];
    int j = 0;
    while (!(o[j] == c && o[(j + 1) % 3] == a)) ++j;
    if (!(faux[u] & (1u << j))) {
      pure = false;
      break;
    }
    if (t < u) quads.push_back({apex, a, o[(j + 2) % 3], c});
  }
  if (pure && 2 * quads.size() == tris.size())
    out.quads = std::move(quads);
  else
    out.triangles = std::move(tris);
  return out;
}

void split_quad(const std::vector<Vec3>& p, const std::array<Index, 4>& q, std::vector<std::array<Index, 3>>& out) {
  if ((p[q[0]] - p[q[2]]).squaredNorm() <= (p[q[1]] - p[q[3]]).squaredNorm()) {
    out.push_back({q[0], q[1], q[2]});
    out.push_back({q[0], q[2], q[3]});
  } else {
    out.push_back({q[0], q[1], q[3]});
    out.push_back({q[1], q[2], q[3]});
  }
}

TriMesh triangles_of(const MeshFile& file) {
  TriMesh t;
  t.positions = file.positions;
  t.faces = file.triangles;
  for (const auto& q : file.quads) split_quad(file.positions, q, t.faces);
  return t;
}

}  // namespace qs
