#pragma once
/// @file
/// Obstacles as every floor sees them: the generator keeps footsteps out of them, the depth
/// adapter finds them, the navigation scenes place them.

namespace walkgen {

/// A circular obstacle the footsteps must stay out of (thesis eq. 2.79): every footstep centre
/// keeps at least radius + margin from (x, y). World frame, metres.
template <typename Scalar = double>
struct CircleObstacle {
  Scalar x = Scalar(0), y = Scalar(0);
  Scalar radius = Scalar(0);  ///< [m] > 0
  Scalar margin = Scalar(0);  ///< [m] ≥ 0, added to the radius (foot size and safety)
};

}  // namespace walkgen
