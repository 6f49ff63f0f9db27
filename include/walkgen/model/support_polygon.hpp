#pragma once
/// @file
/// Convex polygons as half-planes (thesis eq. 2.61–2.64): the ZMP support polygon and the
/// footstep feasibility regions. Vertices may be given clockwise or counter-clockwise; the
/// signs are fixed so that the polygon's centroid satisfies A p ≤ b (docs/design.md §5 erratum:
/// the thesis's sign depends on the vertex order).

#include <Eigen/Core>
#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <string>

#include "walkgen/core/exceptions.hpp"
#include "walkgen/core/foot.hpp"
#include "walkgen/core/math.hpp"

namespace walkgen {

/// Why a vertex list is not a usable convex polygon, or nullptr when it is: at least three
/// finite vertices, no repeated vertex, every turn in the same direction and one full turn in
/// all (which rules out self-intersecting "stars").
template <typename Derived>
const char* convex_polygon_problem(const Eigen::MatrixBase<Derived>& vertices) {
  using Scalar = typename Derived::Scalar;
  const Eigen::Index n = vertices.rows();
  if (vertices.cols() != 2) return "vertices must be an (n x 2) matrix";
  if (n < 3) return "a polygon needs at least 3 vertices";
  if (!vertices.allFinite()) return "a vertex is NaN or infinite";
  int sign = 0;
  Scalar turning = Scalar(0);
  for (Eigen::Index i = 0; i < n; ++i) {
    const auto p0 = vertices.row(i);
    const auto p1 = vertices.row((i + 1) % n);
    const auto p2 = vertices.row((i + 2) % n);
    const Scalar ex = p1(0) - p0(0), ey = p1(1) - p0(1);
    const Scalar fx = p2(0) - p1(0), fy = p2(1) - p1(1);
    if (ex == Scalar(0) && ey == Scalar(0)) return "two consecutive vertices coincide";
    const Scalar cross = ex * fy - ey * fx;
    const Scalar scale = std::sqrt((ex * ex + ey * ey) * (fx * fx + fy * fy));
    if (std::abs(cross) <= Scalar(1e-12) * scale) return "three consecutive vertices are collinear";
    const int s = cross > Scalar(0) ? 1 : -1;
    if (sign != 0 && s != sign) return "the polygon is not convex";
    sign = s;
    turning += std::atan2(cross, ex * fx + ey * fy);
  }
  if (std::abs(std::abs(turning) - Scalar(2.0 * kPi)) > Scalar(1e-6)) {
    return "the polygon winds more than once (self-intersecting)";
  }
  return nullptr;
}

/// @throws walkgen::invalid_argument naming `where` if vertices are not a convex polygon.
template <typename Derived>
void check_convex_polygon(const char* where, const Eigen::MatrixBase<Derived>& vertices) {
  if (const char* why = convex_polygon_problem(vertices)) {
    throw invalid_argument(std::string(where) +
                           ": expected the vertices of a convex polygon, got " +
                           std::to_string(vertices.rows()) + " vertices: " + why);
  }
}

/// Half-plane form {p : A p ≤ b} of a convex polygon with E vertices (rows of `vertices`):
/// row e of A is the outward unit normal of the edge from vertex e to vertex e+1, so that
/// a_eᵀp − b_e is the signed distance of p beyond that edge.
/// @throws walkgen::invalid_argument if the vertices are not a convex polygon.
template <typename Derived, typename DA, typename Db>
void polygon_halfplanes(const Eigen::MatrixBase<Derived>& vertices, Eigen::MatrixBase<DA>& A,
                        Eigen::MatrixBase<Db>& b) {
  using Scalar = typename Derived::Scalar;
  check_convex_polygon("polygon_halfplanes", vertices);
  const Eigen::Index n = vertices.rows();
  check_argument(A.rows() == n && A.cols() == 2 && b.size() == n, "polygon_halfplanes: A, b",
                 "(E x 2) and (E) for E vertices",
                 std::to_string(A.rows()) + " x " + std::to_string(A.cols()) + ", " +
                     std::to_string(b.size()));
  const Scalar cx = vertices.col(0).mean(), cy = vertices.col(1).mean();
  for (Eigen::Index e = 0; e < n; ++e) {
    const auto p0 = vertices.row(e);
    const auto p1 = vertices.row((e + 1) % n);
    Scalar nx = p1(1) - p0(1), ny = p0(0) - p1(0);
    Scalar be = nx * p0(0) + ny * p0(1);
    if (nx * cx + ny * cy > be) {  // the centroid must be inside: flip the edge's orientation
      nx = -nx;
      ny = -ny;
      be = -be;
    }
    const Scalar length = std::sqrt(nx * nx + ny * ny);  // unit normals: a value is a distance
    A(e, 0) = nx / length;
    A(e, 1) = ny / length;
    b(e) = be / length;
  }
}

/// Distance [m] between two soles, `length` × `width` rectangles centred on the foot frames
/// `a` and `b`; 0 when they touch or overlap. For checking the foot separation
/// (mpc/constraints/foot_separation.hpp) on plans and trajectories.
template <typename Scalar>
Scalar sole_distance(const FootPose<Scalar>& a, const FootPose<Scalar>& b, Scalar length,
                     Scalar width) {
  using V = Eigen::Matrix<Scalar, 2, 1>;
  const auto corners = [&](const FootPose<Scalar>& p) {
    const Scalar c = std::cos(p.q), s = std::sin(p.q), hx = length / 2, hy = width / 2;
    std::array<V, 4> k;
    const Scalar xs[4] = {hx, -hx, -hx, hx}, ys[4] = {hy, hy, -hy, -hy};
    for (int i = 0; i < 4; ++i) k[i] = V(p.x + c * xs[i] - s * ys[i], p.y + s * xs[i] + c * ys[i]);
    return k;
  };
  const std::array<V, 4> A = corners(a), B = corners(b);
  // The corners run counter-clockwise, so (e_y, −e_x) is edge e's outward normal. Convex
  // polygons are apart exactly when an edge of one has the other wholly beyond it; then their
  // distance is the least corner-to-edge distance either way.
  const auto separated = [](const std::array<V, 4>& P, const std::array<V, 4>& Q) {
    for (int e = 0; e < 4; ++e) {
      const V edge = P[(e + 1) % 4] - P[e], normal(edge.y(), -edge.x());
      bool beyond = true;
      for (int i = 0; i < 4 && beyond; ++i) beyond = normal.dot(Q[i] - P[e]) > Scalar(0);
      if (beyond) return true;
    }
    return false;
  };
  if (!separated(A, B) && !separated(B, A)) return Scalar(0);
  const auto to_segment = [](const V& p, const V& s0, const V& s1) {
    const V d = s1 - s0;
    const Scalar t = std::clamp((p - s0).dot(d) / d.squaredNorm(), Scalar(0), Scalar(1));
    return (s0 + t * d - p).norm();
  };
  Scalar best = std::numeric_limits<Scalar>::infinity();
  for (int i = 0; i < 4; ++i) {
    for (int e = 0; e < 4; ++e) {
      best = std::min(
          {best, to_segment(A[i], B[e], B[(e + 1) % 4]), to_segment(B[i], A[e], A[(e + 1) % 4])});
    }
  }
  return best;
}

}  // namespace walkgen
