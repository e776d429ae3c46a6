// quadsimp: adaptive quad mesh simplification. SPDX-License-Identifier: GPL-3.0-or-later
#include "quadsimp/fitmap/cells.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <numeric>
#include <unordered_map>
#include <utility>

namespace qs::detail {

CellGrid cluster_triangles(const std::vector<Vec3>& centroid, const std::vector<std::array<Index, 3>>& tri_adj,
                           double size) {
  CellGrid g;
  const Index nf = Index(centroid.size());
  g.cell_of_triangle.resize(nf);
  std::unordered_map<std::uint64_t, Index> id;
  id.reserve(nf / 2 + 16);
  const auto q = [&](double x) { return std::uint64_t(std::int64_t(std::floor(x / size)) & 0x1fffff); };
  for (Index f = 0; f < nf; ++f) {
    const Vec3& c = centroid[f];
    const std::uint64_t key = (q(c.x()) << 42) | (q(c.y()) << 21) | q(c.z());
    g.cell_of_triangle[f] = id.emplace(key, Index(id.size())).first->second;
  }
  const Index nc = Index(id.size());
  std::vector<std::pair<Index, Index>> pairs;
  for (Index f = 0; f < nf; ++f)
    for (Index h : tri_adj[f])
      if (h != kNone && g.cell_of_triangle[f] != g.cell_of_triangle[h])
        pairs.push_back({g.cell_of_triangle[f], g.cell_of_triangle[h]});
  std::sort(pairs.begin(), pairs.end());
  pairs.erase(std::unique(pairs.begin(), pairs.end()), pairs.end());
  g.adj_start.assign(nc + 1, 0);
  for (const auto& pr : pairs) ++g.adj_start[pr.first + 1];
  std::partial_sum(g.adj_start.begin(), g.adj_start.end(), g.adj_start.begin());
  g.adj.resize(pairs.size());
  for (std::size_t i = 0; i < pairs.size(); ++i) g.adj[i] = pairs[i].second;
  return g;
}

}  // namespace qs::detail
