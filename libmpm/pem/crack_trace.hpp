// Crack paths traced through the broken pairs (docs/pem.md, "Cracks"): a broken pair is cut where
// it crosses its elements, so each (pair, element) gives a piece of the crack inside that element.
// 2D: the segment from the pair's midpoint to the element's centroid; pieces of neighbouring broken
// pairs meet at the centroids and form the path. 3D (tetrahedra): the quadrangle midpoint - centroid
// of one face holding the pair - element centroid - centroid of the other face, as two triangles.
// Written on the current positions, so the path opens with the body.
#pragma once
#include <vector>

#include "libmpm/io/point_set.hpp"
#include "libmpm/pem/pem_model.hpp"

namespace cleave::pem {

template <int Dim>
class CrackTracer {
 public:
  explicit CrackTracer(const PemSystem<Dim>& m);
  // The pieces of every pair not intact now, at positions y (one per particle). Arrays: "initial"
  // (1: cut by a pre-crack, 0: broken during the run).
  io::PointSet trace(const std::vector<Vec<Dim>>& y, const PemPairs& pairs) const;

 private:
  const PemSystem<Dim>& m_;
  // Canonical entry (the copy in the list of the pair's lower particle) and the elements holding
  // the pair: elements_[start_[c] .. start_[c+1]).
  std::vector<int64_t> entry_;
  std::vector<int64_t> start_;
  std::vector<int32_t> elements_;
};

}  // namespace cleave::pem
