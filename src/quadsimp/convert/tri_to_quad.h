// quadsimp: adaptive quad mesh simplification. SPDX-License-Identifier: GPL-3.0-or-later
#pragma once

#include "quadsimp/mesh/quad_mesh.h"
#include "quadsimp/mesh/tri_mesh.h"

namespace qs {

struct ConvertOptions {
  //! Greedy pairing refuses to merge two triangles bent by more than this (degrees).
  double max_dihedral_deg = 60.0;
  //! Breadth limit of the searches for a path that re-pairs a leftover triangle: the
  //! triangles they reach, over all of the leftover's moves (about four searches of a
  //! million-triangle part; Edmonds' algorithm pairs what they leave).
  Index max_search = 1u << 22;
  //! Times a leftover triangle is moved to a neighbour to retry the search.
  Index max_moves = 64;
  //! Triangles are never paired across an edge sharper than this (degrees; 0: no such
  //! edges), so that every crease (reference/creases.h, the same angle) is an edge of the
  //! quads, and the simplifier can keep it.
  double crease_angle_deg = 0;
  //! Pairs that greedy pairing would not make (non-convex, or bent past max_dihedral_deg;
  //! the searches below make them where they must) are avoided where the pairing allows:
  //! the leftovers are first paired only along paths of pairs it would make, and once every
  //! triangle is paired each other pair is re-paired along such a path where one joins its
  //! two triangles; each search within `convex_search` triangles. On for the conversion as
  //! a result of its own (`quadsimp convert`, the conversion filter); off for the
  //! simplifier's input, where it gave adaptive mode no gain over uniform mode (a lower
  //! one at the twelve fixed counts: bench/RESULTS.md, "Convex quads from the
  //! conversion").
  bool convex_pairs = false;
  Index convex_search = 4096;
};

struct ConvertReport {
  Index input_triangles = 0;   //!< after the parity splits
  Index parity_splits = 0;     //!< border edges split so that every component is even
  Index crease_splits = 0;     //!< crease edges split so that every part between creases is even
  //! Rim edges split, one per closed component that is a bipyramid of an odd number of rim
  //! vertices (a CAD cone with its base a fan), which pairs only with doublets otherwise.
  Index rim_splits = 0;
  //! Pairs left across a crease, where a part between creases had no pairing of its own,
  //! split at their crease edge's midpoint into two flat quads, one on either side.
  Index crease_midpoints = 0;
  Index paired_greedy = 0;     //!< triangles paired by the greedy pass (and bipyramids' by construction)
  Index paired_augmented = 0;  //!< triangles paired by re-pairing along paths
  Index paired_blossoms = 0;   //!< of those, paired by Edmonds' algorithm after the searches
  Index border_splits = 0;     //!< border edges split where no pairing existed
  //! With ConvertOptions::convex_pairs: pairs re-paired at the end, and the pairs greedy
  //! pairing would not make that are left (non-convex, or bent past max_dihedral_deg).
  Index mended = 0, not_mended = 0;
  //! Triangles the searches for paths reached, all leftovers together: the pairing's work.
  std::size_t searched = 0;
  bool refined = false;        //!< fell back to one refinement step
  Index quads = 0;
  //! Share of triangles that ended up in a pair (1 unless the fallback ran).
  double pairing_rate() const {
    return input_triangles ? double(paired_greedy + paired_augmented) / input_triangles : 0.0;
  }
};

//! Converts a clean triangle mesh (see clean()) into a pure quad mesh.
//!
//! 1. Per component with an odd triangle count, its longest border edge is split at
//!    its midpoint (a closed component is always even). With creases, the parts between
//!    them are made even first, by splitting crease edges between parts (the triangles
//!    on both sides), so that the only odd part left is the one holding that border edge;
//!    no pair is then made across a crease. Where a part has no pairing of its own even
//!    so, its leftovers pair across creases, and each such pair is split at its crease
//!    edge's midpoint into two quads, one on either side, flat with a straight angle there.
//! 2. Bipyramids of five or more rim vertices (CAD cones) are paired by construction, one
//!    spoke of each rim vertex removed, from the tip's fan and the base's in turn; an odd
//!    rim has its longest edge split at its midpoint first. Greedy pairing and the searches
//!    below left doublets at rim vertices, which the simplifier merged down to two quads.
//!    Then greedy matching of adjacent triangles, best quad first (score: mean over the
//!    corners of 1-|cos angle|; non-convex or strongly bent pairs are not merged).
//! 3. Each leftover triangle is paired by re-pairing along the shortest alternating
//!    path to another leftover (TPC*10's triangle migration, as an augmenting path);
//!    what those searches miss (paths through odd cycles), Edmonds' blossom algorithm
//!    pairs. Where no pairing exists, the leftover is carried to the border instead and
//!    a border edge is split at its midpoint. With ConvertOptions::convex_pairs, the
//!    leftovers first search through pairs the greedy pass would make, and the pairs left
//!    that it would not make are re-paired through such pairs where they can be.
//! 4. If anything is still unpaired, one refinement step splits every quad into four
//!    and every triangle into three quads (edge midpoints, triangle centroids, quad
//!    diagonal midpoints: all on the input surface).
//! Original vertices never move. \pre `tri` is clean (oriented, manifold).
QuadMesh tri_to_quad(const TriMesh& tri, const ConvertOptions& options = {},
                     ConvertReport* report = nullptr);

}  // namespace qs
