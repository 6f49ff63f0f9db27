#pragma once
/// @file
/// What the polygon blocks share (ZMP polygon, footstep feasibility, capture point): a convex
/// polygon {p : A p ≤ b} (thesis eq. 2.61–2.64, unit normals) held in the frame of a foot of
/// yaw θ, applied to w = p − F: the rows a_eᵀ R(θ)ᵀ w ≤ b_e, their values for any scalar (Jets
/// included) and their Gauss–Newton rows.

#include <Eigen/Core>
#include <array>
#include <cmath>
#include <limits>

#include "walkgen/core/foot.hpp"
#include "walkgen/model/support_polygon.hpp"
#include "walkgen/mpc/walking_layout.hpp"

namespace walkgen {

/// The half-planes of a left foot's polygon and of the right foot's (fixed-size when Edges is).
template <typename Scalar, int Edges>
struct FootPolygons {
  using Normals = Eigen::Matrix<Scalar, Edges, 2>;
  using Offsets = Eigen::Matrix<Scalar, Edges, 1>;
  std::array<Normals, 2> A;  ///< outward unit normals, [0] left foot, [1] right foot
  std::array<Offsets, 2> b;

  /// From the vertices (E × 2) of each foot's polygon in its own frame.
  /// @throws walkgen::invalid_argument if a polygon is not convex.
  template <typename Vertices>
  FootPolygons(const Vertices& left, const Vertices& right) {
    for (int f = 0; f < 2; ++f) {
      const auto& vertices = f == 0 ? left : right;
      A[std::size_t(f)].resize(vertices.rows(), 2);
      b[std::size_t(f)].resize(vertices.rows());
      polygon_halfplanes(vertices, A[std::size_t(f)], b[std::size_t(f)]);
    }
  }
  const Normals& normals(Foot f) const { return A[f == Foot::left ? 0 : 1]; }
  const Offsets& offsets(Foot f) const { return b[f == Foot::left ? 0 : 1]; }
  Eigen::Index edges() const { return A[0].rows(); }
};

/// One edge a of a polygon in a frame rotated by θ, applied to w: value aᵀR(θ)ᵀw, the row
/// ρ = R(θ)a (∂/∂w) and dq = ∂value/∂θ (the rotation's derivative, different in every row).
template <typename T>
struct RotatedEdge {
  T rx, ry, dq, value;
};
template <typename Scalar, typename T>
RotatedEdge<T> rotated_edge(Scalar ax, Scalar ay, const T& cq, const T& sq, const T& wx,
                            const T& wy) {
  const T rx = ax * cq - ay * sq, ry = ax * sq + ay * cq;
  const T dq = (-ax * sq - ay * cq) * wx + (ax * cq - ay * sq) * wy;
  return {rx, ry, dq, rx * wx + ry * wy};
}

/// Values c[r + e] = a_eᵀ R(q)ᵀ (wx, wy) of one polygon's rows, for any scalar T.
template <typename Normals, typename T, typename VectorC>
void rotated_polygon_values(const Normals& A, const T& q, const T& wx, const T& wy, VectorC& c,
                            Eigen::Index r) {
  using std::cos;
  using std::sin;
  const T cq = cos(q), sq = sin(q);
  for (Eigen::Index e = 0; e < A.rows(); ++e) {
    c[r + e] = rotated_edge(A(e, 0), A(e, 1), cq, sq, wx, wy).value;
  }
}

/// Bounds −∞ ≤ c ≤ b_e of one polygon's rows from row r on.
template <typename Offsets, typename Scalar>
void rotated_polygon_bounds(const Offsets& b, MpcVector<Scalar>& lower, MpcVector<Scalar>& upper,
                            Eigen::Index r) {
  for (Eigen::Index e = 0; e < b.size(); ++e) {
    lower[r + e] = -std::numeric_limits<Scalar>::infinity();
    upper[r + e] = b[e];
  }
}

/// Gauss–Newton rows J of one polygon from row r on, at the iterate where w = (wx, wy) and the
/// yaw is q: `columns(edge, row)` writes the Jacobian columns of w (and θ) into the row and
/// returns their part of J U; the upper bound becomes b − (c(U) − J U).
template <typename Normals, typename Offsets, typename Scalar, typename Matrix, typename Columns>
void rotated_polygon_rows(const Normals& A, const Offsets& b, Scalar q, Scalar wx, Scalar wy,
                          Matrix& J, MpcVector<Scalar>& lower, MpcVector<Scalar>& upper,
                          Eigen::Index r, Columns&& columns) {
  using std::cos;
  using std::sin;
  const Scalar cq = cos(q), sq = sin(q);
  rotated_polygon_bounds(b, lower, upper, r);
  for (Eigen::Index e = 0; e < A.rows(); ++e) {
    const RotatedEdge<Scalar> ed = rotated_edge(A(e, 0), A(e, 1), cq, sq, wx, wy);
    auto row = J.row(r + e);
    upper[r + e] -= ed.value - columns(ed, row);  // J U' ≤ b − (c(U) − J U)
  }
}

/// Writes the columns of footstep i ≥ 1 (w = … − F_i, rotated by θ_i) into a row: −ρ for x and
/// y, dq for θ_i. Returns their part of J U.
template <typename Scalar, typename Row>
Scalar footstep_columns(const WalkingLayout& L, const RotatedEdge<Scalar>& ed, Eigen::Index i,
                        const MpcVector<Scalar>& U, Row& row) {
  row[L.step_x() + i - 1] = -ed.rx;
  row[L.step_y() + i - 1] = -ed.ry;
  row[L.step_q() + i - 1] = ed.dq;
  return -ed.rx * U[L.step_x() + i - 1] - ed.ry * U[L.step_y() + i - 1] +
         ed.dq * U[L.step_q() + i - 1];
}

}  // namespace walkgen
