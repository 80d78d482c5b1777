#include "render/luts/gauss_legendre.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace mane::render {

std::vector<QuadratureNode> gaussLegendre(int n) {
  std::vector<QuadratureNode> nodes;
  for (int i = 0; i < n; ++i) {
    // Newton's method on the Legendre three-term recurrence from the usual cosine initial guesses.
    double z = std::cos(std::numbers::pi * (i + 0.75) / (n + 0.5));
    double derivative = 1.0;
    for (int iteration = 0; iteration < 100; ++iteration) {
      double p0 = 1.0, p1 = z;
      for (int k = 2; k <= n; ++k) {
        const double p2 = ((2.0 * k - 1.0) * z * p1 - (k - 1.0) * p0) / k;
        p0 = p1;
        p1 = p2;
      }
      derivative = n * (z * p1 - p0) / (z * z - 1.0);
      const double step = p1 / derivative;
      z -= step;
      if (std::abs(step) < 1e-15) break;
    }
    nodes.push_back({z, 2.0 / ((1.0 - z * z) * derivative * derivative)});
  }
  std::sort(nodes.begin(), nodes.end(),
            [](const QuadratureNode& a, const QuadratureNode& b) { return a.position < b.position; });
  return nodes;
}

}  // namespace mane::render
