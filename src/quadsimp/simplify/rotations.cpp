// quadsimp: adaptive quad mesh simplification. SPDX-License-Identifier: GPL-3.0-or-later
// Edge rotations [paper 3.2, step 2] around each change, towards regular valences.
#include "quadsimp/simplify/simplifier.h"

#include <algorithm>
#include <cstdint>
#include <cstdlib>
#include <limits>
#include <utility>

#include "quadsimp/mesh/quad_geometry.h"

namespace qs::detail {

// The new edge's endpoints gain one edge each: both must stay within the valence cap.
bool Simplifier::rotation_passes_cap(Index h, Rotation r) const {
  if (opt_.max_valence <= 0) return true;
  const auto [a, b] = rotated_edge(m_, h, r);
  return std::max(m_.valence(a), m_.valence(b)) < opt_.max_valence;
}

// As rotation_folds(), a rotated face with corner `except` is not checked.
bool Simplifier::rotation_follows_reference(Index h, Rotation r, Index except) const {
  for (const auto& c : rotated_faces(m_, h, r)) {
    if (except != kNone && std::find(c.begin(), c.end(), except) != c.end()) continue;
    const auto q = m_.positions_of(c);
    if (!follows_reference(quad_normal(q[0], q[1], q[2], q[3]), c, q.data(), Vec3::Zero())) return false;
  }
  return true;
}

bool Simplifier::try_rotate(Index h) {
  if (!m_.is_face_live(QuadMesh::face(h)) || m_.twin(h) == kNone) return false;
  const Index g = m_.twin(h);
  const Index u = m_.from(h), w = m_.to(h);
  if (!crease_.empty() && may_be_crease_edge(u, w)) return false;
  const Index x1 = m_.to(QuadMesh::next(h)), x2 = m_.from(QuadMesh::prev(h));
  const Index y1 = m_.to(QuadMesh::next(g)), y2 = m_.from(QuadMesh::prev(g));
  // Energy [paper]: sum over the hexagon of |D(v) - target|. Ties are broken by the sum
  // of squares (ours): a 6-4 pair becoming 5-5 keeps the paper's energy but lowers the
  // maximum valence. The pair decreases lexicographically with every rotation, so the
  // rotations still terminate.
  const Index corner[6] = {u, w, x1, y1, x2, y2};
  int dev[6];
  for (int i = 0; i < 6; ++i) dev[i] = m_.valence(corner[i]) - target_valence(corner[i]);
  auto energy = [&](int gain_a, int gain_b) {  // gain_a on x1, y1; gain_b on x2, y2
    const int d[6] = {dev[0] - 1, dev[1] - 1, dev[2] + gain_a, dev[3] + gain_a, dev[4] + gain_b, dev[5] + gain_b};
    std::pair<int, int> e{0, 0};
    for (int x : d) e.first += std::abs(x), e.second += x * x;
    return e;
  };
  std::pair<int, int> keep{0, 0};
  for (int x : dev) keep.first += std::abs(x), keep.second += x * x;
  // A direction that would raise a vertex above the valence cap is never profitable.
  const std::pair<int, int> never{std::numeric_limits<int>::max(), 0};
  const auto e_a = rotation_passes_cap(h, Rotation::Ccw) ? energy(1, 0) : never;
  const auto e_b = rotation_passes_cap(h, Rotation::Cw) ? energy(0, 1) : never;
  if (std::min(e_a, e_b) >= keep) return false;
  // Prefer the lower energy; on a tie the shorter new edge.
  Rotation first = Rotation::Ccw, second = Rotation::Cw;
  const double la = (m_.position(x1) - m_.position(y1)).squaredNorm();
  const double lb = (m_.position(x2) - m_.position(y2)).squaredNorm();
  if (e_b < e_a || (e_b == e_a && lb < la)) std::swap(first, second);
  const auto e_second = second == Rotation::Ccw ? e_a : e_b;
  for (Rotation r : {first, second}) {
    if (r == second && e_second >= keep) break;
    if (!can_rotate_edge(m_, h, r) || creates_pinned_edge(h, r) || rotation_folds(m_, h, r, kNone, refuse_folds_) ||
        !rotation_follows_reference(h, r))
      continue;
    const Index f1 = QuadMesh::face(h), f2 = QuadMesh::face(g);
    rotate_edge(m_, h, r);
    ++rep_.rotations;
    for (Index f : {f1, f2}) {
      region_faces_.push_back(f);
      for (Index k = 0; k < 4; ++k) cand_.push_back(QuadMesh::halfedge(f, k));
    }
    return true;
  }
  return false;
}

void Simplifier::rotate_in_region() {
  // Each interior edge once: the zone lists some faces more than once, and an edge has
  // two half-edges. Border edges never rotate.
  const std::uint32_t zone = ++stamp_, listed = ++stamp_;
  for (Index f : region_faces_)
    if (m_.is_face_live(f)) face_mark_[f] = zone;
  cand_.clear();
  for (Index f : region_faces_) {
    if (!m_.is_face_live(f) || face_mark_[f] != zone) continue;
    face_mark_[f] = listed;
    for (Index k = 0; k < 4; ++k) {
      const Index h = QuadMesh::halfedge(f, k), t = m_.twin(h);
      if (t != kNone && face_mark_[QuadMesh::face(t)] != listed) cand_.push_back(h);
    }
  }
  int budget = 64;  // each rotation lowers an integer energy, so this is only a guard
  for (std::size_t i = 0; i < cand_.size() && budget > 0; ++i)
    if (try_rotate(cand_[i])) --budget;
}

}  // namespace qs::detail
