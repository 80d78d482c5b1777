#pragma once
// Gauss-Legendre quadrature on [−1, 1], for the CPU references of the lookup tables and their
// tests: n nodes integrate polynomials of degree 2n − 1 exactly.

#include <vector>

namespace mane::render {

struct QuadratureNode {
  double position = 0.0;  ///< in [−1, 1]
  double weight = 0.0;
};

/// The n-point rule (n ≥ 1), nodes ascending from −1 … to 1; weights sum to 2.
std::vector<QuadratureNode> gaussLegendre(int n);

}  // namespace mane::render
