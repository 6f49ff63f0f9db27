#pragma once
/// @file
/// Constraint block: circular obstacles (thesis eq. 2.79–2.82). For obstacle k and planned
/// step i = 1..N_f, ‖F_i − o_k‖ ≥ R_k + m_k. Linearising the distance (not its square, as the
/// thesis does) gives the tangent half-plane d̂ᵀ(F_i − o) ≥ R + m in the direction d̂ of the
/// iterate from the centre: an inner approximation of the outside of the circle that stays
/// feasible when the iterate (e.g. a new step's guess) lies inside the circle, where the squared
/// form asks for a half-plane beyond reach.
/// Rows: capacity · N_f, obstacle-major; rows of obstacles beyond those set are free
/// (−∞ ≤ 0 ≤ ∞). Each moves with the landings (ShiftRule::per_step).

#include <Eigen/Core>
#include <cmath>
#include <limits>
#include <string>

#include "walkgen/core/exceptions.hpp"
#include "walkgen/mpc/walking_schedule.hpp"

namespace walkgen {

template <typename Scalar>
class Obstacles {
 public:
  static constexpr const char* kName = "obstacles (eq. 2.79-2.82)";

  /// @throws walkgen::invalid_argument naming `where` for more than `capacity` obstacles (the
  ///         rows reserved) or one with a non-finite centre, radius ≤ 0 or margin < 0.
  template <typename Container>
  static void check(const char* where, const Container& obstacles, Eigen::Index capacity) {
    if (Eigen::Index(obstacles.size()) > capacity) {  // the message is built only on failure
      check_argument(false, where, "at most obstacle_capacity() = " + std::to_string(capacity),
                     obstacles.size(), "pass a larger obstacle_capacity to the constructor");
    }
    for (const auto& o : obstacles) {
      check_argument(std::isfinite(o.x) && std::isfinite(o.y) && std::isfinite(o.radius) &&
                         o.radius > Scalar(0) && std::isfinite(o.margin) && o.margin >= Scalar(0),
                     where, "finite centres, radius > 0, margin >= 0", "an invalid obstacle");
    }
  }

  BlockShape shape(const WalkingDims& d) const {
    return {d.obstacles, d.nf, 1, ShiftRule::per_step};
  }

  template <typename T, int N>
  void values(const WalkingTick<Scalar, N>& t, const LayoutBlock& rows, const MpcVector<T>& U,
              MpcVector<T>& c) const {
    using std::sqrt;
    for_each_row(t, rows, [&](Eigen::Index r, const CircleObstacle<Scalar>* ob, Eigen::Index i) {
      if (ob == nullptr) {
        c[r] = T(0);
        return;
      }
      const T dx = t.x(U, i) - ob->x, dy = t.y(U, i) - ob->y;
      c[r] = sqrt(dx * dx + dy * dy);
    });
  }

  template <int N>
  void bounds(const WalkingTick<Scalar, N>& t, const LayoutBlock& rows, MpcVector<Scalar>& lower,
              MpcVector<Scalar>& upper) const {
    for_each_row(t, rows, [&](Eigen::Index r, const CircleObstacle<Scalar>* ob, Eigen::Index) {
      lower[r] = ob == nullptr ? -kInf : ob->radius + ob->margin;
      upper[r] = kInf;
    });
  }

  template <int N>
  void linearise(const WalkingTick<Scalar, N>& t, const LayoutBlock& rows,
                 const MpcVector<Scalar>& U, MpcRowMatrix<Scalar>& J, MpcVector<Scalar>& lower,
                 MpcVector<Scalar>& upper) const {
    using std::cos;
    using std::sin;
    bounds(t, rows, lower, upper);
    for_each_row(t, rows, [&](Eigen::Index r, const CircleObstacle<Scalar>* ob, Eigen::Index i) {
      if (ob == nullptr) return;
      const Scalar fx = t.x(U, i), fy = t.y(U, i);
      Scalar dx = fx - ob->x, dy = fy - ob->y;
      const Scalar value = std::sqrt(dx * dx + dy * dy);
      if (value > Scalar(1e-9)) {
        dx /= value;
        dy /= value;
      } else {  // at the centre: leave it sideways of the support foot's heading
        dx = -sin(t.state.support.q);
        dy = cos(t.state.support.q);
      }
      J(r, t.layout.step_x() + i - 1) = dx;
      J(r, t.layout.step_y() + i - 1) = dy;
      lower[r] -= value - (dx * fx + dy * fy);
    });
  }

 private:
  static constexpr Scalar kInf = std::numeric_limits<Scalar>::infinity();
  /// Calls f(row, obstacle or nullptr beyond those set, step i) for every row.
  template <int N, typename F>
  static void for_each_row(const WalkingTick<Scalar, N>& t, const LayoutBlock& rows, F&& f) {
    const Eigen::Index nf = t.layout.dims().nf, set = Eigen::Index(t.obstacles.size());
    for (Eigen::Index k = 0, r = rows.offset; k < rows.shape.repeats; ++k) {
      for (Eigen::Index i = 1; i <= nf; ++i, ++r)
        f(r, k < set ? &t.obstacles[std::size_t(k)] : nullptr, i);
    }
  }
};

}  // namespace walkgen
