#include "physics/surface_binding.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <string>

#include <glm/geometric.hpp>
#include <glm/vec3.hpp>

#include "physics/sdf.hpp"

namespace mane::physics {
namespace {

bool finite(const glm::vec3& v) {
  return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}

std::string describe(const glm::vec3& v) {
  std::string text = "(";
  text += std::to_string(v.x) + ", " + std::to_string(v.y) + ", " + std::to_string(v.z) + ")";
  return text;
}

// A triangle that takes part in the search, corners in double (the closest-point routine's
// precision) and its index in the input.
struct SearchTriangle {
  glm::dvec3 a, b, c;
  std::uint32_t index = 0;
};

// A node of the bounding-volume hierarchy: a box and either two children (`left`, `left + 1`)
// or, for a leaf (`count` > 0), the triangles order[first, first + count).
struct Node {
  glm::dvec3 lower{0.0};
  glm::dvec3 upper{0.0};
  std::uint32_t left = 0;
  std::uint32_t first = 0;
  std::uint32_t count = 0;
};

constexpr std::uint32_t kLeafSize = 4;
// Deeper than any tree built here: splits at the median halve the triangles, so the depth is
// about log2(triangles / kLeafSize), and the search holds at most one pending sibling per level.
constexpr std::size_t kSearchStackSize = 96;

// A tree over the triangles, split at the median centroid along the box's longest axis.
class TriangleTree {
public:
  explicit TriangleTree(std::vector<SearchTriangle> triangles) : triangles_(std::move(triangles)) {
    order_.resize(triangles_.size());
    for (std::uint32_t i = 0; i < order_.size(); ++i) order_[i] = i;
    nodes_.reserve(2 * triangles_.size() / kLeafSize + 2);
    nodes_.emplace_back();
    build(0, 0, static_cast<std::uint32_t>(order_.size()));
  }

  // The closest triangle to `p` (lowest index among equals) and the squared distance to it.
  std::pair<const SearchTriangle*, double> closest(const glm::dvec3& p) const {
    double best = std::numeric_limits<double>::infinity();
    const SearchTriangle* found = nullptr;
    std::array<std::uint32_t, kSearchStackSize> stack{};
    std::size_t top = 0;
    stack[top++] = 0;
    while (top > 0) {
      const Node& node = nodes_[stack[--top]];
      // Strictly farther boxes only: a triangle at exactly `best` may still win on its index.
      if (boxDistance2(node, p) > best) continue;
      if (node.count > 0) {
        for (std::uint32_t i = node.first; i < node.first + node.count; ++i) {
          const SearchTriangle& t = triangles_[order_[i]];
          int feature = 0;
          const glm::dvec3 d = p - closestPointOnTriangle(p, t.a, t.b, t.c, feature);
          const double distance2 = glm::dot(d, d);
          if (distance2 < best || (distance2 == best && found && t.index < found->index)) {
            best = distance2;
            found = &t;
          }
        }
        continue;
      }
      // The nearer child goes on top, so it is searched first and prunes the other.
      const double toLeft = boxDistance2(nodes_[node.left], p), toRight = boxDistance2(nodes_[node.left + 1], p);
      const bool leftFirst = toLeft <= toRight;
      stack[top++] = leftFirst ? node.left + 1 : node.left;
      stack[top++] = leftFirst ? node.left : node.left + 1;
    }
    return {found, best};
  }

private:
  static double boxDistance2(const Node& node, const glm::dvec3& p) {
    const glm::dvec3 outside = glm::max(glm::max(node.lower - p, p - node.upper), glm::dvec3(0.0));
    return glm::dot(outside, outside);
  }

  void build(std::uint32_t at, std::uint32_t first, std::uint32_t end) {
    glm::dvec3 lower(std::numeric_limits<double>::infinity()), upper(-std::numeric_limits<double>::infinity());
    glm::dvec3 centreLower = lower, centreUpper = upper;
    for (std::uint32_t i = first; i < end; ++i) {
      const SearchTriangle& t = triangles_[order_[i]];
      lower = glm::min(glm::min(lower, t.a), glm::min(t.b, t.c));
      upper = glm::max(glm::max(upper, t.a), glm::max(t.b, t.c));
      const glm::dvec3 centre = centroid(t);
      centreLower = glm::min(centreLower, centre);
      centreUpper = glm::max(centreUpper, centre);
    }
    nodes_[at].lower = lower;
    nodes_[at].upper = upper;
    if (end - first <= kLeafSize) {
      nodes_[at].first = first;
      nodes_[at].count = end - first;
      return;
    }
    const glm::dvec3 extent = centreUpper - centreLower;
    const int axis = extent.x >= extent.y && extent.x >= extent.z ? 0 : (extent.y >= extent.z ? 1 : 2);
    const std::uint32_t middle = first + (end - first) / 2;
    // Ties on the axis are ordered by index, so the split does not depend on the library's
    // partitioning order.
    std::nth_element(order_.begin() + first, order_.begin() + middle, order_.begin() + end,
                     [&](std::uint32_t x, std::uint32_t y) {
                       const double cx = centroid(triangles_[x])[axis], cy = centroid(triangles_[y])[axis];
                       return cx < cy || (cx == cy && x < y);
                     });
    const auto left = static_cast<std::uint32_t>(nodes_.size());
    nodes_[at].left = left;
    nodes_.emplace_back();
    nodes_.emplace_back();
    build(left, first, middle);
    build(left + 1, middle, end);
  }

  static glm::dvec3 centroid(const SearchTriangle& t) { return (t.a + t.b + t.c) / 3.0; }

  std::vector<SearchTriangle> triangles_;
  std::vector<std::uint32_t> order_;
  std::vector<Node> nodes_;
};

// Any unit vector perpendicular to unit `n`: n crossed with the axis it is least aligned with.
glm::vec3 anyPerpendicular(const glm::vec3& n) {
  const glm::vec3 a = glm::abs(n);
  const glm::vec3 axis =
      a.x <= a.y && a.x <= a.z ? glm::vec3(1, 0, 0) : (a.y <= a.z ? glm::vec3(0, 1, 0) : glm::vec3(0, 0, 1));
  return glm::normalize(glm::cross(n, axis));
}

}  // namespace

Result<SurfaceBinding> SurfaceBinding::create(std::span<const glm::vec3> positions,
                                              std::span<const std::uint32_t> indices,
                                              std::span<const glm::vec3> points) {
  if (positions.empty() || indices.empty()) return fail("Surface binding: the mesh is empty.");
  if (indices.size() % 3 != 0)
    return fail("Surface binding: the mesh has " + std::to_string(indices.size()) +
                " triangle indices, which is not a multiple of 3.");
  for (std::size_t v = 0; v < positions.size(); ++v)
    if (!finite(positions[v]))
      return fail("Surface binding: mesh vertex " + std::to_string(v) + " is NaN or infinite " +
                  describe(positions[v]) + ".");
  for (std::size_t i = 0; i < points.size(); ++i)
    if (!finite(points[i]))
      return fail("Surface binding: point " + std::to_string(i) + " is NaN or infinite " + describe(points[i]) + ".");

  std::vector<SearchTriangle> triangles;
  triangles.reserve(indices.size() / 3);
  for (std::size_t t = 0; t < indices.size() / 3; ++t) {
    for (int k = 0; k < 3; ++k)
      if (indices[3 * t + k] >= positions.size())
        return fail("Surface binding: triangle " + std::to_string(t) + " uses vertex " +
                    std::to_string(indices[3 * t + k]) + " but the mesh has " + std::to_string(positions.size()) +
                    " vertices.");
    const SearchTriangle triangle{glm::dvec3(positions[indices[3 * t]]), glm::dvec3(positions[indices[3 * t + 1]]),
                                  glm::dvec3(positions[indices[3 * t + 2]]), static_cast<std::uint32_t>(t)};
    const glm::dvec3 normal = glm::cross(triangle.b - triangle.a, triangle.c - triangle.a);
    if (glm::dot(normal, normal) > 0.0) triangles.push_back(triangle);  // zero area: no plane, skipped
  }
  if (triangles.empty())
    return fail("Surface binding: all " + std::to_string(indices.size() / 3) +
                " triangles of the mesh have zero area.");

  SurfaceBinding binding;
  binding.vertexCount_ = positions.size();
  binding.points_.resize(points.size());
  binding.corners_.resize(3 * points.size());
  binding.restNormals_.resize(points.size());
  const TriangleTree tree(std::move(triangles));
  double largest2 = 0.0;
  for (std::size_t i = 0; i < points.size(); ++i) {
    const glm::dvec3 p(points[i]);
    const auto [t, distance2] = tree.closest(p);
    largest2 = std::max(largest2, distance2);
    // Barycentrics of p's projection onto the plane (Ericson 2005, §3.4), height along the
    // unit normal: Σ b·corner + height·n is p again.
    const glm::dvec3 e0 = t->b - t->a, e1 = t->c - t->a, ap = p - t->a;
    const double d00 = glm::dot(e0, e0), d01 = glm::dot(e0, e1), d11 = glm::dot(e1, e1);
    const double d20 = glm::dot(ap, e0), d21 = glm::dot(ap, e1);
    const double denominator = d00 * d11 - d01 * d01;
    const double v = (d11 * d20 - d01 * d21) / denominator, w = (d00 * d21 - d01 * d20) / denominator;
    const glm::dvec3 normal = glm::normalize(glm::cross(e0, e1));
    binding.points_[i] = {t->index,
                          glm::vec3(static_cast<float>(1.0 - v - w), static_cast<float>(v), static_cast<float>(w)),
                          static_cast<float>(glm::dot(ap, normal))};
    for (int k = 0; k < 3; ++k) binding.corners_[3 * i + k] = indices[3 * t->index + k];
    binding.restNormals_[i] = glm::vec3(normal);
  }
  binding.largestHeight_ = static_cast<float>(std::sqrt(largest2));
  return binding;
}

Result<void> SurfaceBinding::evaluate(std::span<const glm::vec3> positions, std::span<const glm::vec3> vertexNormals,
                                      std::span<glm::vec3> outPositions, std::span<glm::vec3> outNormals,
                                      std::span<glm::vec3> outTangents) const {
  if (positions.size() != vertexCount_)
    return fail("Surface binding: the deformed mesh has " + std::to_string(positions.size()) +
                " vertices, the binding was made on " + std::to_string(vertexCount_) + ".");
  if (!vertexNormals.empty() && vertexNormals.size() != vertexCount_)
    return fail("Surface binding: " + std::to_string(vertexNormals.size()) + " vertex normals for " +
                std::to_string(vertexCount_) + " vertices.");
  const auto checkOutput = [&](std::size_t size, const char* what, bool optional) -> Result<void> {
    if (size == points_.size() || (optional && size == 0)) return {};
    return fail("Surface binding: the output " + std::string(what) + " span holds " + std::to_string(size) +
                " entries for " + std::to_string(points_.size()) + " bound points.");
  };
  if (auto ok = checkOutput(outPositions.size(), "positions", false); !ok) return ok;
  if (auto ok = checkOutput(outNormals.size(), "normals", true); !ok) return ok;
  if (auto ok = checkOutput(outTangents.size(), "tangents", true); !ok) return ok;

  // Components are read one float at a time and combined as scalars: built from whole vec3
  // loads, g++ packs the gathered corners through the stack into vector registers, and the
  // partial stores and wide reloads that takes stall far longer than the arithmetic.
  const float* x = &positions.data()->x;
  const float* vn = vertexNormals.empty() ? nullptr : &vertexNormals.data()->x;
  for (std::size_t i = 0; i < points_.size(); ++i) {
    const SurfacePoint& point = points_[i];
    const float* a = x + 3 * std::size_t{corners_[3 * i]};
    const float* b = x + 3 * std::size_t{corners_[3 * i + 1]};
    const float* c = x + 3 * std::size_t{corners_[3 * i + 2]};
    const float e0 = b[0] - a[0], e1 = b[1] - a[1], e2 = b[2] - a[2];  // first edge, a → b
    const float f0 = c[0] - a[0], f1 = c[1] - a[1], f2 = c[2] - a[2];  // second edge, a → c
    const glm::vec3 cross(e1 * f2 - e2 * f1, e2 * f0 - e0 * f2, e0 * f1 - e1 * f0);
    const float twiceArea = std::sqrt(cross.x * cross.x + cross.y * cross.y + cross.z * cross.z);
    const glm::vec3 face = twiceArea > 0.0f ? cross * (1.0f / twiceArea) : restNormals_[i];
    const float wa = point.barycentric.x, wb = point.barycentric.y, wc = point.barycentric.z, h = point.height;
    outPositions[i] =
        glm::vec3(a[0] * wa + b[0] * wb + c[0] * wc + face.x * h, a[1] * wa + b[1] * wb + c[1] * wc + face.y * h,
                  a[2] * wa + b[2] * wb + c[2] * wc + face.z * h);
    if (outNormals.empty() && outTangents.empty()) continue;

    glm::vec3 normal = face;
    if (vn) {
      const float* na = vn + 3 * std::size_t{corners_[3 * i]};
      const float* nb = vn + 3 * std::size_t{corners_[3 * i + 1]};
      const float* nc = vn + 3 * std::size_t{corners_[3 * i + 2]};
      const glm::vec3 blend(na[0] * wa + nb[0] * wb + nc[0] * wc, na[1] * wa + nb[1] * wb + nc[1] * wc,
                            na[2] * wa + nb[2] * wb + nc[2] * wc);
      const float length = std::sqrt(blend.x * blend.x + blend.y * blend.y + blend.z * blend.z);
      if (length > 0.0f) normal = blend * (1.0f / length);
    }
    if (!outNormals.empty()) outNormals[i] = normal;
    if (outTangents.empty()) continue;
    const glm::vec3 edge(e0, e1, e2);
    glm::vec3 tangent = edge - normal * glm::dot(edge, normal);
    float length = glm::length(tangent);
    if (!(length > 0.0f)) {
      const glm::vec3 second(f0, f1, f2);
      tangent = second - normal * glm::dot(second, normal);
      length = glm::length(tangent);
    }
    outTangents[i] = length > 0.0f ? tangent * (1.0f / length) : anyPerpendicular(normal);
  }
  return {};
}

}  // namespace mane::physics
