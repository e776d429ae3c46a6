// quadsimp: adaptive quad mesh simplification. SPDX-License-Identifier: GPL-3.0-or-later
#include "quadsimp/fitmap/fitmap.h"

#include <tbb/enumerable_thread_specific.h>

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <numeric>
#include <utility>

#include "quadsimp/fitmap/cells.h"
#include "quadsimp/util/errors.h"
#include "quadsimp/util/parallel.h"

namespace qs {
namespace {

// Exact area-weighted moments of a set of triangles: enough to fit a plane by total
// least squares and to orient it.
struct Moments {
  double area = 0;
  Vec3 first = Vec3::Zero();   // integral of x
  double second[6] = {};       // integral of x x^T: xx xy xz yy yz zz
  Vec3 normal = Vec3::Zero();  // area-weighted normal sum
  Index count = 0;             // triangles
  void add(const Moments& o) {
    area += o.area;
    first += o.first;
    for (int k = 0; k < 6; ++k) second[k] += o.second[k];
    normal += o.normal;
    count += o.count;
  }
};

// A triangle's area normal (the edges' cross product), area, corner sum and first moment:
// what its moments and the cells' centroid (centroid_of()) are made from, made here once
// so that both keep the same bits.
struct TriangleBasics {
  Vec3 n, s, first;
  double area;
};
TriangleBasics triangle_basics(const Vec3& a, const Vec3& b, const Vec3& c) {
  TriangleBasics t;
  t.n = (b - a).cross(c - a);
  t.area = 0.5 * t.n.norm();
  t.s = a + b + c;
  t.first = t.area * t.s / 3.0;
  return t;
}

Moments triangle_moments(const Vec3& a, const Vec3& b, const Vec3& c) {
  Moments m;
  const TriangleBasics t = triangle_basics(a, b, c);
  const Vec3& n = t.n;
  const Vec3& s = t.s;
  m.area = t.area;
  m.first = t.first;
  // Integral of x x^T over a triangle: A/12 (a a^T + b b^T + c c^T + s s^T).
  const double w = m.area / 12.0;
  auto outer = [&](const Vec3& x) {
    m.second[0] += w * x.x() * x.x();
    m.second[1] += w * x.x() * x.y();
    m.second[2] += w * x.x() * x.z();
    m.second[3] += w * x.y() * x.y();
    m.second[4] += w * x.y() * x.z();
    m.second[5] += w * x.z() * x.z();
  };
  outer(a), outer(b), outer(c), outer(s);
  m.normal = 0.5 * n;
  m.count = 1;
  return m;
}

// The moments of triangle f about `centre` (working_origin()). The plane fit takes the
// covariance as second moments minus the mean's square, which cancels digits as the
// square of (distance from the origin / radius): a plane a million units from the origin
// (survey coordinates) lost them all and got random fitmaps.
Moments moments_of(const TriMesh& t, Index f, const Vec3& centre) {
  const auto& v = t.faces[f];
  return triangle_moments(t.positions[v[0]] - centre, t.positions[v[1]] - centre, t.positions[v[2]] - centre);
}

// Where the cells place triangle f: its centroid about `centre`, its first moment over its
// area, without the second moments. A triangle of no area takes its corners' mean, about
// `centre` too (it once took the origin's frame, and so another cell, when the mesh lay
// far from it).
Vec3 centroid_of(const TriMesh& t, Index f, const Vec3& centre) {
  const auto& v = t.faces[f];
  const TriangleBasics b =
      triangle_basics(t.positions[v[0]] - centre, t.positions[v[1]] - centre, t.positions[v[2]] - centre);
  return b.area > 0 ? Vec3(b.first / b.area) : Vec3(b.s / 3.0);
}

// Items 0..n-1 grouped by key(i) in [0, groups) (kNone: left out), each group in id order,
// as compressed rows: group g is items[start[g] .. start[g + 1]).
struct Buckets {
  std::vector<Index> start, items;
};
template <class Key>
Buckets bucket_by(Index groups, Index n, const Key& key) {
  Buckets b;
  b.start.assign(groups + 1, 0);
  for (Index i = 0; i < n; ++i)
    if (const Index k = key(i); k != kNone) ++b.start[k + 1];
  std::partial_sum(b.start.begin(), b.start.end(), b.start.begin());
  b.items.resize(b.start.back());
  std::vector<Index> fill(b.start.begin(), b.start.end() - 1);
  for (Index i = 0; i < n; ++i)
    if (const Index k = key(i); k != kNone) b.items[fill[k]++] = i;
  return b;
}

// Every triangle's moments, for the exact balls, which read each many times. The cells
// sum theirs anew (build_cells()), so the array is dropped before the cell levels: beside a
// level's cells it made the fitmaps' peak (112 bytes a triangle; bench/RESULTS.md,
// "Peak memory of large runs").
std::vector<Moments> moments_about(const TriMesh& t, const Vec3& centre) {
  std::vector<Moments> tm(t.n_faces());
  parallel_for_as_here(Index(0), t.n_faces(), [&](Index f) { tm[f] = moments_of(t, f, centre); });
  return tm;
}

struct Fit {
  bool ok = false;
  double error = 0;  // RMS distance to the plane
  Vec3 normal = Vec3::Zero();
};

Fit fit_plane(const Moments& m) {
  Fit f;
  if (m.count < 4 || m.area <= 0) return f;
  const Vec3 c = m.first / m.area;
  Eigen::Matrix3d C;
  C << m.second[0], m.second[1], m.second[2], m.second[1], m.second[3], m.second[4], m.second[2], m.second[4],
      m.second[5];
  C = C / m.area - c * c.transpose();
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> es;
  es.computeDirect(C);
  const Vec3 ev = es.eigenvalues();
  // A neighbourhood that is (nearly) a line has no well-defined plane.
  if (!(ev(1) > 1e-12 * ev(2))) return f;
  f.ok = true;
  f.error = std::sqrt(std::max(ev(0), 0.0));
  f.normal = es.eigenvectors().col(0);
  if (f.normal.dot(m.normal) < 0) f.normal = -f.normal;
  return f;
}

// Vertex -> vertex and vertex -> triangle incidence, as flat CSR arrays.
struct Incidence {
  std::vector<Index> vv_start, vv, vt_start, vt;
  explicit Incidence(const TriMesh& t) {
    const Index nv = t.n_vertices();
    vt_start.assign(nv + 1, 0);
    for (const auto& f : t.faces)
      for (Index v : f) ++vt_start[v + 1];
    std::partial_sum(vt_start.begin(), vt_start.end(), vt_start.begin());
    vt.resize(vt_start.back());
    std::vector<Index> fill(vt_start.begin(), vt_start.end() - 1);
    for (Index f = 0; f < t.n_faces(); ++f)
      for (Index v : t.faces[f]) vt[fill[v]++] = f;
    VertexRings rings = vertex_rings(t);
    vv_start = std::move(rings.start);
    vv = std::move(rings.next);
  }
};

struct Scratch {
  std::vector<Index> mark, queue, tris;
  Index stamp = 0;
  std::vector<Index> inner, around;  // cell_balls()' part shared by its points, and the cells around it
};

// Plane-fit error and inconsistent-area fraction of the connected ball (p, r), on the
// triangles themselves. Returns false when there is no usable fit.
bool exact_ball(const TriMesh& t, const Incidence& inc, const std::vector<Moments>& tm, Index p, double r,
                Scratch& s, double& error, double& frac) {
  if (s.mark.size() != t.n_vertices()) s.mark.assign(t.n_vertices(), 0);
  const Index stamp = ++s.stamp;
  const Vec3& c = t.positions[p];
  const double r2 = r * r;
  s.queue.clear();
  s.queue.push_back(p);
  s.mark[p] = stamp;
  for (std::size_t i = 0; i < s.queue.size(); ++i) {
    const Index v = s.queue[i];
    for (Index j = inc.vv_start[v]; j < inc.vv_start[v + 1]; ++j) {
      const Index x = inc.vv[j];
      if (s.mark[x] != stamp && (t.positions[x] - c).squaredNorm() < r2) {
        s.mark[x] = stamp;
        s.queue.push_back(x);
      }
    }
  }
  Moments sum;
  s.tris.clear();
  for (Index v : s.queue)
    for (Index j = inc.vt_start[v]; j < inc.vt_start[v + 1]; ++j) {
      const Index f = inc.vt[j];
      const auto& tri = t.faces[f];
      // A triangle counts when its centroid lies in the ball, as the cells count theirs
      // (once: from its lowest corner reached). On the bunny these balls cover 0.93 to
      // 1.03 of pi r^2 at r_0 to 4 r_0; counting the triangles with every corner inside
      // covered a tenth of that at r_0, half at 1.6 r_0, three quarters at 4 r_0, and put
      // the fast fitmaps' F_S 4% above this function's (bench/RESULTS.md, "The balls'
      // triangles").
      Index first = kNone;
      for (Index x : tri)
        if (s.mark[x] == stamp) first = std::min(first, x);
      if (first != v) continue;
      const Vec3 corner_sum = t.positions[tri[0]] + t.positions[tri[1]] + t.positions[tri[2]];
      if ((corner_sum - 3 * c).squaredNorm() >= 9 * r2) continue;
      sum.add(tm[f]);
      s.tris.push_back(f);
    }
  const Fit fit = fit_plane(sum);
  if (!fit.ok) return false;
  double bad = 0;
  for (Index f : s.tris)
    if (tm[f].normal.dot(fit.normal) <= 0) bad += tm[f].area;
  error = fit.error;
  frac = bad / sum.area;
  return true;
}

// The mesh clustered into cubic cells of one size: each cell keeps the summed moments
// of the triangles whose centroid falls in it, and the area of those of its triangles
// that face against the cell's mean normal. Cells touching through a mesh edge are
// neighbours, so a BFS over cells follows the surface like the exact BFS does.
struct CellLevel {
  detail::CellGrid grid;
  std::vector<Moments> moments;
  std::vector<Vec3> centre;
  std::vector<double> against;  // area facing against the cell's own mean normal
};

CellLevel build_cells(const TriMesh& t, const Vec3& centre, const std::vector<std::array<Index, 3>>& tri_adj,
                      double size) {
  std::vector<Vec3> centroid(t.n_faces());
  parallel_for_as_here(Index(0), t.n_faces(), [&](Index f) { centroid[f] = centroid_of(t, f, centre); });
  CellLevel L;
  L.grid = detail::cluster_triangles(centroid, tri_adj, size);
  const detail::CellGrid& grid = L.grid;
  const Index nc = grid.n_cells();
  // Each cell's triangles in id order, the order its sums took when made in one loop over
  // the triangles: summed cell by cell in parallel, they come out the same to the bit.
  const Buckets in_cell = bucket_by(nc, t.n_faces(), [&](Index f) { return grid.cell_of_triangle[f]; });
  L.moments.resize(nc);
  L.centre.resize(nc);
  L.against.assign(nc, 0.0);
  tbb::enumerable_thread_specific<std::vector<std::pair<Vec3, double>>> facing;  // a cell's normals and areas
  parallel_for_as_here(Index(0), nc, [&](Index c) {
    auto& own = facing.local();
    own.clear();
    Moments sum;
    for (Index i = in_cell.start[c]; i < in_cell.start[c + 1]; ++i) {
      const Moments m = moments_of(t, in_cell.items[i], centre);
      sum.add(m);
      own.emplace_back(m.normal, m.area);
    }
    L.moments[c] = sum;
    L.centre[c] = sum.first / std::max(sum.area, 1e-300);
    for (const auto& [normal, area] : own)
      if (normal.dot(sum.normal) <= 0) L.against[c] += area;
  });
  return L;
}

// Takes cell x into the ball around p if its centre lies within r (r2 = r * r):
// stamps, appends and sums it.
inline void take_if_within(const CellLevel& L, Index x, const Vec3& p, double r2, Index stamp,
                           std::vector<Index>& cells, std::vector<Index>& mark, Moments& sum) {
  if ((L.centre[x] - p).squaredNorm() < r2) {
    mark[x] = stamp;
    cells.push_back(x);
    sum.add(L.moments[x]);
  }
}

// Grows a cell ball: expands `cells` through neighbours within r of p that are not
// stamped `stamp` or `shared`, appending, stamping and summing each one it adds.
void grow(const CellLevel& L, const Vec3& p, double r, std::vector<Index>& cells, std::vector<Index>& mark,
          Index stamp, Index shared, Moments& sum) {
  Moments acc = sum;  // a local the compiler may keep in registers: sum could alias L.moments
  detail::grow_ball(L.grid, L.centre, p, r * r, cells, mark, stamp, shared, [&](Index x) { acc.add(L.moments[x]); });
  sum = acc;
}

// The area of `cells` facing against `normal`, from each cell's own split of its area.
double area_against(const CellLevel& L, const std::vector<Index>& cells, const Vec3& normal) {
  double bad = 0;
  for (Index c : cells) bad += L.moments[c].normal.dot(normal) <= 0 ? L.moments[c].area - L.against[c] : L.against[c];
  return bad;
}

// Groups of fewer points than this search one by one: sharing costs a search of its own.
constexpr std::size_t kShareFrom = 8;

// The cell balls of radius r around points that all start from one cell: each ball is the
// cells connected to the start through cells whose centre is within r of the point.
// Every cell within r - spread of the points' mean, connected to the start through such
// cells, lies in each of these balls. That inner part is gathered and summed once, and
// each point's search only grows it through the cells around it: the same cells as a
// search per point.
// At the largest radii hundreds of vertices share a start cell (bench/RESULTS.md,
// "Fitmaps: one search per cell"). store(m, ok, error, frac) takes the m-th point's result.
template <class Store>
void cell_balls(const CellLevel& L, Index start, const Index* members, std::size_t n, const TriMesh& t,
                const Vec3& centre, double r, bool share, Scratch& s, const Store& store) {
  if (s.mark.size() < L.moments.size()) s.mark.assign(L.moments.size(), 0);
  // The m-th point's fit, over the queue's cells and the inner part when shared.
  const auto fit_and_store = [&](std::size_t m, const Moments& sum, bool with_inner) {
    const Fit fit = fit_plane(sum);
    if (!fit.ok) return store(m, false, 0.0, 0.0);
    double bad = with_inner ? area_against(L, s.inner, fit.normal) : 0.0;
    bad += area_against(L, s.queue, fit.normal);
    store(m, true, fit.error, bad / sum.area);
  };
  if (!share || n < kShareFrom) {
    for (std::size_t m = 0; m < n; ++m) {
      const Index stamp = ++s.stamp;
      s.queue.assign(1, start);
      s.mark[start] = stamp;
      Moments sum = L.moments[start];
      grow(L, t.positions[members[m]] - centre, r, s.queue, s.mark, stamp, stamp, sum);
      fit_and_store(m, sum, false);
    }
    return;
  }
  Vec3 mean = Vec3::Zero();
  for (std::size_t j = 0; j < n; ++j) mean += t.positions[members[j]] - centre;
  mean /= double(n);
  double spread = 0;
  for (std::size_t j = 0; j < n; ++j) spread = std::max(spread, (t.positions[members[j]] - centre - mean).norm());

  const Index inner = ++s.stamp;
  s.inner.assign(1, start);
  s.mark[start] = inner;
  Moments inner_sum = L.moments[start];
  // A hair inside r - spread, so that rounding cannot put a cell in the inner part that a
  // point's own test would find on the far side of r.
  const double inner_r = std::max(r - spread, 0.0) * (1 - 1e-9);
  grow(L, mean, inner_r, s.inner, s.mark, inner, inner, inner_sum);
  // The cells just outside the inner part: a point's ball leaves it through them.
  const Index outside = ++s.stamp;
  s.around.clear();
  for (Index c : s.inner)
    for (Index j = L.grid.adj_start[c]; j < L.grid.adj_start[c + 1]; ++j) {
      const Index x = L.grid.adj[j];
      if (s.mark[x] != inner && s.mark[x] != outside) {
        s.mark[x] = outside;
        s.around.push_back(x);
      }
    }
  const double r2 = r * r;
  for (std::size_t m = 0; m < n; ++m) {
    const Vec3 p = t.positions[members[m]] - centre;
    const Index stamp = ++s.stamp;
    Moments sum = inner_sum;
    s.queue.clear();
    for (Index x : s.around) take_if_within(L, x, p, r2, stamp, s.queue, s.mark, sum);
    grow(L, p, r, s.queue, s.mark, stamp, inner, sum);
    fit_and_store(m, sum, true);
  }
}

// F_S takes at least this many radii, even past the first failure of the M test.
constexpr std::size_t kLeastRadiiForS = 3;

// F_S and F_M from the per-radius errors and fractions of one vertex.
void summarise(const std::vector<double>& radii, const double* error, const double* frac, const char* ok,
               const FitmapOptions& opt, float& fs, float& fm) {
  double m = radii.front();
  std::size_t last = 0;  // radii up to here are used for F_S
  bool failed = false;
  for (std::size_t i = 0; i < radii.size(); ++i) {
    if (!ok[i]) continue;
    if (!failed) {
      if (frac[i] < opt.tau) m = radii[i], last = i;
      else failed = true;
    }
  }
  if (!opt.local_s) last = radii.size() - 1;
  last = std::max<std::size_t>(last, std::min<std::size_t>(kLeastRadiiForS - 1, radii.size() - 1));
  double a = 0;
  if (opt.local_s) {
    // The median over radii of E_i / r_i^2: each radius votes for a, so one large
    // neighbourhood reaching a distant feature does not decide for a flat point.
    double votes[32];
    int n = 0;
    for (std::size_t i = 0; i <= last && n < 32; ++i)
      if (ok[i]) votes[n++] = error[i] / (radii[i] * radii[i]);
    if (n) {
      std::nth_element(votes, votes + n / 2, votes + n);
      a = votes[n / 2];
    }
  } else {
    double num = 0, den = 0;  // the paper's least-squares fit of E(r) = a r^2
    for (std::size_t i = 0; i <= last; ++i) {
      if (!ok[i]) continue;
      const double r2 = radii[i] * radii[i];
      num += r2 * error[i];
      den += r2 * r2;
    }
    a = den > 0 ? num / den : 0.0;
  }
  fs = float(std::sqrt(a));
  fm = float(m);
}

void laplacian(const Incidence& inc, std::vector<float>& f, int passes) {
  std::vector<float> g(f.size());
  for (int it = 0; it < passes; ++it) {
    for (Index v = 0; v < f.size(); ++v) {
      double s = f[v];
      for (Index j = inc.vv_start[v]; j < inc.vv_start[v + 1]; ++j) s += f[inc.vv[j]];
      g[v] = float(s / (1 + inc.vv_start[v + 1] - inc.vv_start[v]));
    }
    f.swap(g);
  }
}

Fitmaps compute(const TriMesh& t, const FitmapOptions& opt, bool smooth) {
  if (t.n_faces() == 0) throw InvalidInput("fitmaps: the mesh has no faces");
  const std::vector<double> radii = fitmap_radii(t, opt.levels);
  const Index nv = t.n_vertices(), nl = Index(radii.size());
  const Incidence inc(t);
  const Vec3 centre = working_origin(t.positions);  // cell balls take points about it too
  std::vector<Moments> tm = moments_about(t, centre);
  std::vector<double> error(std::size_t(nv) * nl, 0), frac(std::size_t(nv) * nl, 0);
  std::vector<char> ok(std::size_t(nv) * nl, 0);
  tbb::enumerable_thread_specific<Scratch> scratch;
  const auto adj = triangle_adjacency(t);

  // With the local S, summarise() reads none of a vertex's radii past its first failure
  // of the M test but the first kLeastRadiiForS: those balls, the largest and costliest,
  // are not evaluated (bench/RESULTS.md, "Fitmaps: balls nobody reads").
  std::vector<char> settled(nv, 0);  // stays 0 without the local S
  const auto needed = [&](Index v, Index i) {
    return inc.vt_start[v] != inc.vt_start[v + 1] && !(i >= kLeastRadiiForS && settled[v]);
  };
  for (Index i = 0; i < nl; ++i) {
    const double r = radii[i];
    if (r <= opt.exact_up_to * radii[0]) {
      parallel_for_as_here(Index(0), nv, [&](Index v) {
        if (!needed(v, i)) return;
        const std::size_t k = std::size_t(v) * nl + i;
        ok[k] = exact_ball(t, inc, tm, v, r, scratch.local(), error[k], frac[k]);
      });
    } else {
      std::vector<Moments>().swap(tm);  // the cells sum their own
      const CellLevel L = build_cells(t, centre, adj, r / opt.cells_per_radius);
      for (auto& s : scratch) s.mark.clear();
      // The vertices still needed, grouped by the cell their search starts from.
      const Index nc = Index(L.moments.size());
      const Buckets starting = bucket_by(
          nc, nv, [&](Index v) { return needed(v, i) ? L.grid.cell_of_triangle[inc.vt[inc.vt_start[v]]] : kNone; });
      parallel_for_as_here(Index(0), nc, [&](Index c) {
        const Index *group = starting.items.data() + starting.start[c],
                    *end = starting.items.data() + starting.start[c + 1];
        cell_balls(L, c, group, end - group, t, centre, r, opt.share_cell_searches, scratch.local(),
                   [&](std::size_t m, bool good, double e, double f) {
                     const std::size_t k = std::size_t(group[m]) * nl + i;
                     ok[k] = good, error[k] = e, frac[k] = f;
                   });
      });
      for (auto& s : scratch) s.mark.clear();
    }
    for (Index v = 0; v < nv && opt.local_s; ++v) {
      const std::size_t k = std::size_t(v) * nl + i;
      if (ok[k] && frac[k] >= opt.tau) settled[v] = 1;
    }
    if (opt.progress && !opt.progress(float(i + 1) / float(nl), "fitmaps")) throw Cancelled();
  }
  Fitmaps out;
  out.s.assign(nv, 0.f);
  out.m.assign(nv, float(radii.back()));
  for (Index v = 0; v < nv; ++v) {
    const std::size_t k = std::size_t(v) * nl;
    summarise(radii, &error[k], &frac[k], &ok[k], opt, out.s[v], out.m[v]);
  }
  if (smooth) {
    laplacian(inc, out.s, opt.smooth_s);
    laplacian(inc, out.m, opt.smooth_m);
  }
  return out;
}

}  // namespace

std::vector<double> fitmap_radii(const TriMesh& t, int levels) {
  const double r0 = mean_edge_length(t);
  const double rh = std::max(bbox_diagonal(t.positions) / 4.0, r0);
  std::vector<double> r(levels + 1);
  for (int i = 0; i <= levels; ++i) r[i] = r0 * std::pow(rh / r0, double(i) / levels);
  return r;
}

Fitmaps compute_fitmaps(const TriMesh& mesh, const FitmapOptions& options) { return compute(mesh, options, true); }

Fitmaps compute_fitmaps_unsmoothed(const TriMesh& mesh, const FitmapOptions& options) {
  return compute(mesh, options, false);
}

Fitmaps fitmaps_brute_force(const TriMesh& t, const std::vector<Index>& vertices, const FitmapOptions& opt) {
  const std::vector<double> radii = fitmap_radii(t, opt.levels);
  const Incidence inc(t);
  const std::vector<Moments> tm = moments_about(t, working_origin(t.positions));
  Fitmaps out;
  out.s.assign(vertices.size(), 0.f);
  out.m.assign(vertices.size(), 0.f);
  tbb::enumerable_thread_specific<Scratch> scratch;
  parallel_for_as_here(std::size_t(0), vertices.size(), [&](std::size_t j) {
    std::vector<double> e(radii.size()), fr(radii.size());
    std::vector<char> ok(radii.size());
    for (std::size_t i = 0; i < radii.size(); ++i)
      ok[i] = exact_ball(t, inc, tm, vertices[j], radii[i], scratch.local(), e[i], fr[i]);
    summarise(radii, e.data(), fr.data(), ok.data(), opt, out.s[j], out.m[j]);
  });
  return out;
}

}  // namespace qs
