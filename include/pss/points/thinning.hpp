// Which local polynomials the ray search needs (paper §5.2, "Initial approximation";
// docs/paper-notes.md). The paper keeps one polynomial g_i per sample, and with b = h and
// samples about h/2 apart every ray then meets some 16 overlapping balls near each
// surface point, each a ball, slab and quadratic test. The candidate a ball gives only
// starts the projection, which decides the hit; a polynomial whose sample lies on a kept
// neighbour's graph adds no candidate that the neighbour's does not give nearly as well.
#pragma once

#include <span>
#include <vector>

#include "pss/points/local_polynomials.hpp"

namespace pss {

// Keeps, in order, each polynomial that no polynomial kept before it stands for, where g_k
// stands for g_j when p_j lies within spacing·b_k of p_k and within tolerance·b_k of g_k's
// graph (along n_k), b_k > 0 its ball's radius: both lengths follow the sample's width. So
// every dropped sample is that close to a kept polynomial, and two kept ones that near each
// other are both off each other's graph (the two faces of a thin part). spacing 0 keeps
// every polynomial. Host only; O(n) expected.
std::vector<LocalPolynomial> thin_local_polynomials(std::span<const LocalPolynomial> locals, float spacing,
                                                    float tolerance);

}  // namespace pss
