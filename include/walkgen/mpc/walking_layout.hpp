#pragma once
/// @file
/// The NMPC's one layout: where each group of variables sits in the decision vector U, where
/// each constraint block sits among the QP's rows, and how both follow the receding horizon.
/// Counting (num_rows), assembly (every block writes the rows at its offset) and the warm-start
/// shift (DenseQp::rename_warm_start) all read this one table.
///
/// Decision vector (n = 2(N + N_f) + N_f; thesis eq. 2.51–2.53, footstep yaws as variables):
///   U = ( jerk_x[0..N) | F_x[1..N_f] | jerk_y[0..N) | F_y[1..N_f] | F_q[1..N_f] )
/// Rows: the constraint blocks in the order WalkingModel lists them (mpc/walking_model.hpp).

#include <Eigen/Core>
#include <array>
#include <cstdint>

#include "walkgen/core/exceptions.hpp"
#include "walkgen/core/foot.hpp"

namespace walkgen {

/// The formulation's vectors and matrices (dynamic: sized once from the layout), for any scalar
/// T of U (Jets included).
template <typename T>
using MpcVector = Eigen::Matrix<T, Eigen::Dynamic, 1>;
template <typename T>
using MpcMatrix = Eigen::Matrix<T, Eigen::Dynamic, Eigen::Dynamic>;
template <typename T>
using MpcRowMatrix = Eigen::Matrix<T, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;

/// How a group of rows or variables follows the receding horizon when the state moves on.
enum class ShiftRule : std::uint8_t {
  per_sample,  ///< one unit per horizon sample: moves back by the samples advanced
  per_step,    ///< one unit per planned footstep: moves back by the landings
  fixed,       ///< stays (the terminal capture point)
};

/// The enumerator's name ("per_sample", ...), e.g. for logs; "unknown" for a value out of range.
constexpr const char* to_string(ShiftRule rule) noexcept {
  switch (rule) {
    case ShiftRule::per_sample:
      return "per_sample";
    case ShiftRule::per_step:
      return "per_step";
    case ShiftRule::fixed:
      return "fixed";
  }
  return "unknown";
}

/// `repeats` groups of `units` units (samples or steps) of `width` entries each, in that order:
/// local index ((repeat · units) + unit) · width + k.
struct BlockShape {
  Eigen::Index repeats = 1, units = 0, width = 1;
  ShiftRule shift = ShiftRule::fixed;
  Eigen::Index count() const { return repeats * units * width; }
};

/// A block placed among the rows (or in U): name, first index and shape.
struct LayoutBlock {
  const char* name = "";
  Eigen::Index offset = 0;
  BlockShape shape;

  Eigen::Index count() const { return shape.count(); }
  bool contains(Eigen::Index i) const { return i >= offset && i < offset + count(); }
  /// Index that entry i (contained) takes once the horizon moved by `samples` samples and
  /// `steps` landings: the entry of unit u moves to unit u − samples (or u − steps); −1 when
  /// its unit left the horizon.
  Eigen::Index moved(Eigen::Index i, Eigen::Index samples, Eigen::Index steps) const {
    if (shape.shift == ShiftRule::fixed) return i;
    const Eigen::Index by = shape.shift == ShiftRule::per_sample ? samples : steps;
    const Eigen::Index unit = ((i - offset) / shape.width) % shape.units;
    return unit >= by && unit - by < shape.units ? i - by * shape.width : -1;
  }
};

/// The sizes a layout is built from.
struct WalkingDims {
  Eigen::Index N = 0;                           ///< preview samples
  Eigen::Index nf = 0;                          ///< planned footsteps N_f
  Eigen::Index S = 0;                           ///< samples per step, t_step / t
  Eigen::Index foot_edges = 0, hull_edges = 0;  ///< edges of the ZMP and feasibility polygons
  Eigen::Index obstacles = 0;                   ///< obstacle capacity (rows reserved)
};

/// Variables and rows of the QP. Immutable once the model has added its row blocks.
class WalkingLayout {
 public:
  using Index = Eigen::Index;
  static constexpr int kMaxRowBlocks = 8;
  enum Variables { kJerkX, kStepX, kJerkY, kStepY, kStepQ };

  explicit WalkingLayout(const WalkingDims& d) : dims_(d) {
    const BlockShape jerks{1, d.N, 1, ShiftRule::per_sample},
        steps{1, d.nf, 1, ShiftRule::per_step};
    variables_ = {{{"jerk_x", 0, jerks},
                   {"F_x", d.N, steps},
                   {"jerk_y", d.N + d.nf, jerks},
                   {"F_y", 2 * d.N + d.nf, steps},
                   {"F_q", 2 * (d.N + d.nf), steps}}};
  }

  /// Appends a row block after the others (the model, once per block, in its order).
  void add_rows(const char* name, const BlockShape& shape) {
    check_argument(num_row_blocks_ < kMaxRowBlocks, "WalkingLayout::add_rows",
                   "at most kMaxRowBlocks blocks", num_row_blocks_ + 1);
    rows_[std::size_t(num_row_blocks_++)] = {name, num_rows_, shape};
    num_rows_ += shape.count();
  }

  const WalkingDims& dims() const { return dims_; }
  Index num_vars() const { return 2 * (dims_.N + dims_.nf) + dims_.nf; }
  Index num_rows() const { return num_rows_; }
  // Variable offsets.
  Index jerk_x() const { return variables_[kJerkX].offset; }
  Index step_x() const { return variables_[kStepX].offset; }
  Index jerk_y() const { return variables_[kJerkY].offset; }
  Index step_y() const { return variables_[kStepY].offset; }
  Index step_q() const { return variables_[kStepQ].offset; }
  const std::array<LayoutBlock, 5>& variables() const { return variables_; }
  /// Row block k (0-based, in the model's order).
  const LayoutBlock& rows(int k) const { return rows_[std::size_t(k)]; }
  int num_row_blocks() const { return num_row_blocks_; }
  /// Name of the block row r belongs to ("" out of range), e.g. for diagnostics.
  const char* block_of_row(Index r) const {
    for (int k = 0; k < num_row_blocks_; ++k) {
      if (rows(k).contains(r)) return rows(k).name;
    }
    return "";
  }

  /// DenseQp's constraint c (rows 0..m−1, then bounds m..m+n−1) after the horizon moved by
  /// `samples` samples and `steps` landings, or −1 when it left the horizon: the renaming that
  /// DenseQp::rename_warm_start applies to the active set.
  Index renamed(Index c, Index samples, Index steps) const {
    if (c < num_rows_) {
      for (int k = 0; k < num_row_blocks_; ++k) {
        if (rows(k).contains(c)) return rows(k).moved(c, samples, steps);
      }
      return -1;
    }
    const Index v = c - num_rows_;
    for (const LayoutBlock& b : variables_) {
      if (!b.contains(v)) continue;
      const Index w = b.moved(v, samples, steps);
      return w < 0 ? -1 : num_rows_ + w;
    }
    return -1;
  }

 private:
  WalkingDims dims_;
  std::array<LayoutBlock, 5> variables_;
  std::array<LayoutBlock, kMaxRowBlocks> rows_{};
  int num_row_blocks_ = 0;
  Index num_rows_ = 0;
};

/// The plan of the last solve(): the decision vector U and views on its parts.
template <typename Scalar = double>
struct WalkingPlan {
  using VectorX = Eigen::Matrix<Scalar, Eigen::Dynamic, 1>;
  VectorX U;  ///< see the file comment for the layout
  int N = 0, nf = 0;

  Scalar jerk_x(int j) const { return U[j]; }
  Scalar jerk_y(int j) const { return U[N + nf + j]; }
  /// Planned footstep i = 1..nf.
  FootPose<Scalar> footstep(int i) const {
    return {U[N + i - 1], U[2 * N + nf + i - 1], U[2 * (N + nf) + i - 1]};
  }
};

}  // namespace walkgen
