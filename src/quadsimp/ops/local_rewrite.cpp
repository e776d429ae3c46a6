// quadsimp: adaptive quad mesh simplification. SPDX-License-Identifier: GPL-3.0-or-later
#include "quadsimp/ops/local_rewrite.h"

#include <algorithm>

namespace qs::detail {

void rewrite_faces(QuadMesh& m, const Index* faces, const std::array<Index, 4>* quads, int n,
                   const Index* outer, int n_outer) {
  for (int i = 0; i < n; ++i)
    for (Index k = 0; k < 4; ++k) {
      const Index h = QuadMesh::halfedge(faces[i], k);
      m.set_origin(h, quads[i][k]);
      m.set_twin(h, kNone);
    }
  for (int i = 0; i < n; ++i)
    for (Index k = 0; k < 4; ++k) {
      const Index h = QuadMesh::halfedge(faces[i], k);
      const Index a = m.from(h), b = m.to(h);
      Index partner = kNone;
      for (int j = 0; j < n && partner == kNone; ++j)
        for (Index l = 0; l < 4; ++l) {
          const Index g = QuadMesh::halfedge(faces[j], l);
          if (m.from(g) == b && m.to(g) == a) partner = g;
        }
      for (int j = 0; j < n_outer && partner == kNone; ++j)
        if (outer[j] != kNone && m.from(outer[j]) == b && m.to(outer[j]) == a) partner = outer[j];
      if (partner != kNone)
        m.set_twin(h, partner);
    }
  for (int i = 0; i < n; ++i)
    for (Index k = 0; k < 4; ++k) {
      const Index h = QuadMesh::halfedge(faces[i], k);
      m.set_out(m.from(h), h);
    }
  for (int i = 0; i < n; ++i)
    for (Index k = 0; k < 4; ++k) m.repair_out(quads[i][k]);
}

void face_neighbours(const QuadMesh& m, Index v, std::vector<Index>& out) {
  out.clear();
  m.for_each_outgoing(v, [&](Index h) {
    out.push_back(m.to(h));
    out.push_back(m.to(QuadMesh::next(h)));
    out.push_back(m.to(QuadMesh::next(QuadMesh::next(h))));
  });
  std::sort(out.begin(), out.end());
  out.erase(std::unique(out.begin(), out.end()), out.end());
}

bool link_condition(const QuadMesh& m, Index a, Index c, Index b, Index d, Index e) {
  thread_local std::vector<Index> na, nc;
  face_neighbours(m, a, na);
  face_neighbours(m, c, nc);
  std::size_t common = 0;
  for (std::size_t i = 0, j = 0; i < na.size() && j < nc.size();) {
    if (na[i] < nc[j]) {
      ++i;
    } else if (nc[j] < na[i]) {
      ++j;
    } else {
      if (na[i] != b && na[i] != d && na[i] != e) return false;
      ++common, ++i, ++j;
    }
  }
  return common == (e == kNone ? 2u : 3u);
}

}  // namespace qs::detail
