// quadsimp: adaptive quad mesh simplification. SPDX-License-Identifier: GPL-3.0-or-later
#include "quadsimp/ops/cleaning.h"

#include "quadsimp/ops/doublet.h"
#include "quadsimp/ops/singlet.h"

namespace qs {

void clean_from(QuadMesh& m, std::vector<Index>& work, CleanCounts& counts, std::vector<Index>* changed,
                const std::vector<char>* keep) {
  while (!work.empty()) {
    const Index v = work.back();
    work.pop_back();
    if (is_singlet(m, v)) {
      const Index h = m.out(v);
      const Index x = m.from(QuadMesh::next(QuadMesh::next(h)));
      const Index p = remove_singlet(m, v);
      ++counts.singlets;
      if (p != kNone) {
        work.push_back(p);
        work.push_back(x);
        if (changed) m.for_each_outgoing(p, [&](Index e) { changed->push_back(QuadMesh::face(e)); });
      }
    } else if (!(keep && (*keep)[v]) && can_remove_doublet(m, v)) {
      const Index h = m.out(v);
      const Index p = m.to(h), r = m.to(m.rotate(h));
      const Index f = remove_doublet(m, v);
      ++counts.doublets;
      work.push_back(p);
      work.push_back(r);
      if (changed) changed->push_back(f);
    }
  }
}

CleanCounts clean_all(QuadMesh& m, const std::vector<char>* keep) {
  CleanCounts counts;
  std::vector<Index> work;
  for (Index v = m.vertex_capacity(); v-- > 0;)
    if (m.is_vertex_live(v)) work.push_back(v);
  clean_from(m, work, counts, nullptr, keep);
  return counts;
}

}  // namespace qs
