#pragma once
/// @file
/// walkgen's built-in dense QP solver.
///
///   minimise    ½ xᵀ H x + gᵀ x
///   subject to  lb ≤ A x ≤ ub      (m general rows; lb_i = ub_i makes row i an equality)
///               l  ≤  x  ≤ u       (n bounds; l_j = u_j fixes variable j)
///
/// Method: the dual active-set method of Goldfarb and Idnani (Math. Programming 27, 1983),
/// which suits the small, dense, strictly convex QPs of walking pattern generation
/// (thesis eq. 2.83–2.84). With H = L Lᵀ and the q active normals N (n × q) it keeps
/// J = L⁻ᵀ Q and an upper-triangular R such that L⁻¹ N = Q [R; 0], i.e. J₁ᵀ N = R for the first
/// q columns J₁ of J. Each active-set change updates J and R by one Householder reflection per
/// added constraint or Givens rotations per dropped one: O(n²) work per active-set change.
///
/// Warm start: solve() begins from the previous solve's active set. After update(), which
/// changes only g and the bounds, the factorisation of H *and* of that active set are reused, so
/// a solve whose active set did not change costs a few matrix–vector products.
///
/// Allocation: the constructor sizes every buffer. init(), update() and solve() never touch the
/// heap afterwards (tests/qp/test_dense_qp_no_alloc.cpp proves it).
///
/// Errors: wrong sizes throw walkgen::invalid_argument (a programming error). Bad numbers
/// (NaN/Inf, lb > ub, H not symmetric positive definite) make init()/update() return
/// QpStatus::invalid_input with a message, and solve() then returns that status without
/// touching NaNs. An infeasible problem is reported as QpStatus::infeasible, never as solved.

#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <type_traits>

#include "walkgen/core/assert.hpp"
#include "walkgen/core/exceptions.hpp"

namespace walkgen {

/// Outcome of a QP solve (or of the validation in init()/update()).
enum class QpStatus : std::uint8_t {
  unsolved,  ///< solve() has not run since the last init()/update().
  /// KKT conditions hold within the tolerances: every constraint, active ones included, is
  /// checked before this is returned (see QpSettings::primal_tolerance).
  solved,
  infeasible,      ///< the constraints admit no point (x is the last iterate, not a solution).
  max_iterations,  ///< the iteration limit was reached (x is the last iterate, not a solution).
  invalid_input,   ///< the data are unusable (see QpResult::message); x is zero.
  /// Rounding left a constraint violated beyond the tolerance, e.g. H tiny against g, so that
  /// −H⁻¹g is huge or overflows (x is the last iterate, or zero if not finite; not a solution).
  inaccurate,
};

/// The enumerator's name ("solved", ...), e.g. for logs; "unknown" for a value out of range.
constexpr const char* to_string(QpStatus status) noexcept {
  switch (status) {
    case QpStatus::unsolved:
      return "unsolved";
    case QpStatus::solved:
      return "solved";
    case QpStatus::infeasible:
      return "infeasible";
    case QpStatus::max_iterations:
      return "max_iterations";
    case QpStatus::invalid_input:
      return "invalid_input";
    case QpStatus::inaccurate:
      return "inaccurate";
  }
  return "unknown";
}

/// Solver settings. Plain struct, in-class defaults; change them before init() or between solves.
template <typename Scalar = double>
struct QpSettings {
  /// Limit on active-set changes (one constraint added or dropped each) per solve.
  /// 0 picks max(100, 5 (n + m)). Reaching it returns QpStatus::max_iterations.
  int max_iterations = 0;
  /// Start from the previous solve's active set (it is always kept; this only decides whether it
  /// is used). Cold and warm solves of the same problem agree to rounding.
  bool warm_start = true;
  /// Tikhonov regularisation ε ≥ 0: H + εI is factorised and the solver then minimises
  /// ½xᵀ(H + εI)x + gᵀx. Makes positive *semi*definite H usable; shifts the solution by O(ε‖x‖)
  /// and the residuals are those of the regularised problem. Keep 0 for definite H.
  Scalar regularization = Scalar(0);
  /// A row is violated when its distance to the feasible half-space, (lb_i − a_iᵀx)/‖a_i‖ or
  /// (a_iᵀx − ub_i)/‖a_i‖, exceeds primal_tolerance · (1 + |bound|/‖a_i‖ + ‖x‖∞). Bounds alike.
  /// QpStatus::solved promises that no constraint, active or not, is violated by more than
  /// 100 × this (the rounding level that the active-set loop tolerates in degenerate corners).
  Scalar primal_tolerance = Scalar(1e4) * Eigen::NumTraits<Scalar>::epsilon();
  /// A constraint normal whose component outside the span of the active normals is below
  /// dependency_tolerance times its length (in the metric of H⁻¹) counts as linearly dependent.
  Scalar dependency_tolerance = Scalar(1e-2) * std::sqrt(Eigen::NumTraits<Scalar>::epsilon());
  /// Fill QpResult's residuals and objective (O(n² + q n) extra work per solve).
  bool compute_residuals = true;
};

/// Result of solve(). Multipliers follow H x + g + Aᵀ y + z = 0 with y_i ≤ 0 where the lower
/// side of row i is active, y_i ≥ 0 where its upper side is, 0 where inactive (z alike for bounds).
template <typename Scalar = double, int Vars = Eigen::Dynamic, int Rows = Eigen::Dynamic>
struct QpResult {
  Eigen::Matrix<Scalar, Vars, 1> x;  ///< primal solution (n)
  Eigen::Matrix<Scalar, Rows, 1> y;  ///< multipliers of the general rows (m)
  Eigen::Matrix<Scalar, Vars, 1> z;  ///< multipliers of the bounds (n)
  QpStatus status = QpStatus::unsolved;
  int iterations = 0;                  ///< active-set changes in this solve
  int active_set_size = 0;             ///< constraints active at the end (equalities included)
  bool warm_started = false;           ///< the solve began from a previous active set
  bool reused_factorization = false;   ///< ... and reused that active set's factorisation
  Scalar objective = Scalar(0);        ///< ½xᵀHx + gᵀx (if compute_residuals)
  Scalar primal_residual = Scalar(0);  ///< max violation of lb ≤ Ax ≤ ub and l ≤ x ≤ u
  Scalar dual_residual = Scalar(0);    ///< ‖Hx + g + Aᵀy + z‖∞ (if compute_residuals)
  Scalar complementarity = Scalar(0);  ///< max |multiplier · slack| (if compute_residuals)
  const char* message = "";            ///< why the input is invalid / solve failed; static string
};

namespace detail {
/// True when every entry is finite: x − x is 0 for finite x and NaN otherwise (one vector pass).
template <typename Derived>
bool all_finite(const Eigen::DenseBase<Derived>& m) {
  return m.size() == 0 || (m.derived().array() - m.derived().array()).sum() == 0;
}

/// Storage order of the constraint matrix: rows are read one at a time, so row-major, except
/// where Eigen forbids it (a single column).
constexpr int qp_constraint_layout(int vars, int rows) {
  return (vars == 1 && rows != 1) ? Eigen::ColMajor : Eigen::RowMajor;
}
}  // namespace detail

/// Dense strictly convex QP solver; see the file comment for the problem and the method.
/// @tparam Scalar  floating-point type (double recommended; float works with looser tolerances)
/// @tparam Vars    number of variables n, or Eigen::Dynamic
/// @tparam Rows    number of general constraint rows m (may be 0), or Eigen::Dynamic
template <typename Scalar = double, int Vars = Eigen::Dynamic, int Rows = Eigen::Dynamic>
class DenseQp {
  static_assert(std::is_floating_point<Scalar>::value,
                "walkgen: DenseQp needs a floating-point Scalar (float, double, long double)");
  static_assert(Vars > 0 || Vars == Eigen::Dynamic,
                "walkgen: DenseQp's number of variables must be positive or Eigen::Dynamic");
  static_assert(Rows >= 0 || Rows == Eigen::Dynamic,
                "walkgen: DenseQp's number of constraint rows must be >= 0 or Eigen::Dynamic");

 public:
  using Index = Eigen::Index;
  using Settings = QpSettings<Scalar>;
  using Result = QpResult<Scalar, Vars, Rows>;
  using MatrixN = Eigen::Matrix<Scalar, Vars, Vars>;
  using VectorN = Eigen::Matrix<Scalar, Vars, 1>;
  using VectorM = Eigen::Matrix<Scalar, Rows, 1>;
  using MatrixA = Eigen::Matrix<Scalar, Rows, Vars, detail::qp_constraint_layout(Vars, Rows)>;

  /// Fixed sizes only: allocates nothing (all storage is inside the object).
  template <int V = Vars, int R = Rows,
            typename = std::enable_if_t<V != Eigen::Dynamic && R != Eigen::Dynamic>>
  explicit DenseQp(const Settings& settings = Settings()) : DenseQp(Vars, Rows, settings) {}

  /// Sizes every buffer for n variables and m general rows.
  /// @throws walkgen::invalid_argument if n < 1, m < 0 or they contradict fixed sizes.
  DenseQp(Index num_vars, Index num_rows, const Settings& settings = Settings())
      : settings_(settings) {
    check_argument(num_vars >= 1, "DenseQp: num_vars", "n >= 1", num_vars);
    check_argument(num_rows >= 0, "DenseQp: num_rows", "m >= 0", num_rows);
    check_argument(Vars == Eigen::Dynamic || num_vars == Vars, "DenseQp: num_vars", Vars, num_vars,
                   "it must equal the compile-time Vars");
    check_argument(Rows == Eigen::Dynamic || num_rows == Rows, "DenseQp: num_rows", Rows, num_rows,
                   "it must equal the compile-time Rows");
    n_ = num_vars;
    m_ = num_rows;
    H_.setZero(n_, n_);
    J0_.setZero(n_, n_);
    J_.setZero(n_, n_);
    R_.setZero(n_, n_);
    A_.setZero(m_, n_);
    g_.setZero(n_);
    lb_.setZero(m_);
    ub_.setZero(m_);
    l_.setZero(n_);
    u_.setZero(n_);
    row_norm_.setOnes(m_);
    Ax_.setZero(m_);
    x0_.setZero(n_);
    d_.setZero(n_);
    step_.setZero(n_);
    tmp_.setZero(n_);
    hh_.setZero(n_);
    r_.setZero(n_);
    lambda_.setZero(n_);
    active_.setZero(n_);
    active_sign_.setZero(n_);
    previous_active_.setZero(n_);
    previous_sign_.setZero(n_);
    row_state_.setZero(m_);
    bound_state_.setZero(n_);
    add_count_.setZero(m_ + n_);
    row_eq_.setZero(m_);
    bound_eq_.setZero(n_);
    result_.x.setZero(n_);
    result_.y.setZero(m_);
    result_.z.setZero(n_);
  }

  Index num_vars() const { return n_; }
  Index num_rows() const { return m_; }
  Settings& settings() { return settings_; }
  const Settings& settings() const { return settings_; }
  /// The result of the last solve().
  const Result& result() const { return result_; }

  /// Sets the whole problem and factorises H. Bounds l ≤ x ≤ u absent (±∞).
  /// @return QpStatus::unsolved when the data are usable, QpStatus::invalid_input otherwise.
  /// @throws walkgen::invalid_argument on mismatched sizes.
  template <typename DH, typename Dg, typename DA, typename Dlb, typename Dub>
  QpStatus init(const Eigen::MatrixBase<DH>& H, const Eigen::MatrixBase<Dg>& g,
                const Eigen::MatrixBase<DA>& A, const Eigen::MatrixBase<Dlb>& lb,
                const Eigen::MatrixBase<Dub>& ub) {
    l_.setConstant(-kInf);
    u_.setConstant(kInf);
    return init_impl(H, g, A, lb, ub, static_cast<const VectorN*>(nullptr),
                     static_cast<const VectorN*>(nullptr));
  }

  /// Sets the whole problem, bounds included, and factorises H (see the 5-argument overload).
  template <typename DH, typename Dg, typename DA, typename Dlb, typename Dub, typename Dl,
            typename Du>
  QpStatus init(const Eigen::MatrixBase<DH>& H, const Eigen::MatrixBase<Dg>& g,
                const Eigen::MatrixBase<DA>& A, const Eigen::MatrixBase<Dlb>& lb,
                const Eigen::MatrixBase<Dub>& ub, const Eigen::MatrixBase<Dl>& l,
                const Eigen::MatrixBase<Du>& u) {
    return init_impl(H, g, A, lb, ub, &l, &u);
  }

  /// Changes only g and the row bounds: H's factorisation and, for a warm start, the previous
  /// active set's factorisation are reused. The variable bounds stay as they were.
  /// @throws walkgen::invalid_argument on mismatched sizes or if init() never succeeded in sizing.
  template <typename Dg, typename Dlb, typename Dub>
  QpStatus update(const Eigen::MatrixBase<Dg>& g, const Eigen::MatrixBase<Dlb>& lb,
                  const Eigen::MatrixBase<Dub>& ub) {
    return update_impl(g, lb, ub, static_cast<const VectorN*>(nullptr),
                       static_cast<const VectorN*>(nullptr));
  }

  /// Changes g, the row bounds and the variable bounds; H and A stay (see the 3-argument one).
  template <typename Dg, typename Dlb, typename Dub, typename Dl, typename Du>
  QpStatus update(const Eigen::MatrixBase<Dg>& g, const Eigen::MatrixBase<Dlb>& lb,
                  const Eigen::MatrixBase<Dub>& ub, const Eigen::MatrixBase<Dl>& l,
                  const Eigen::MatrixBase<Du>& u) {
    return update_impl(g, lb, ub, &l, &u);
  }

  /// Forgets the previous active set: the next solve starts cold.
  void reset_warm_start() {
    have_previous_ = false;
    cache_valid_ = false;
  }

  /// Renames the constraints of the active set that the next warm start begins from:
  /// `rename(c)` returns the new index of constraint c (rows 0..m−1, then bounds m..m+n−1), or
  /// −1 to leave it out. For receding-horizon problems, whose rows move by one sample from one
  /// solve to the next: the warm start then begins where the last solve ended. Allocation-free.
  template <typename Rename>
  void rename_warm_start(Rename&& rename) {
    if (!have_previous_) return;
    Index kept = 0;
    for (Index k = 0; k < q_; ++k) {
      const int c = rename(active_[k]);
      if (c < 0 || c >= m_ + n_) continue;
      bool duplicate = false;
      for (Index j = 0; j < kept; ++j) duplicate = duplicate || active_[j] == c;
      if (duplicate) continue;
      active_[kept] = c;
      active_sign_[kept] = active_sign_[k];
      lambda_[kept] = lambda_[k];
      ++kept;
    }
    q_ = kept;
    cache_valid_ = false;
  }

  /// Solves the problem set by init()/update(). Allocation-free.
  [[nodiscard]] const Result& solve();

 private:
  static constexpr Scalar kInf = std::numeric_limits<Scalar>::infinity();
  // Constraint codes: c < m is general row c, c >= m is the bound on variable c - m.
  // Signs: +1 lower side (normal a, bound lb), -1 upper side (normal -a, bound -ub).

  template <typename DH, typename Dg, typename DA, typename Dlb, typename Dub, typename Dl,
            typename Du>
  QpStatus init_impl(const Eigen::MatrixBase<DH>& H, const Eigen::MatrixBase<Dg>& g,
                     const Eigen::MatrixBase<DA>& A, const Eigen::MatrixBase<Dlb>& lb,
                     const Eigen::MatrixBase<Dub>& ub, const Dl* l, const Du* u);
  template <typename Dg, typename Dlb, typename Dub, typename Dl, typename Du>
  QpStatus update_impl(const Eigen::MatrixBase<Dg>& g, const Eigen::MatrixBase<Dlb>& lb,
                       const Eigen::MatrixBase<Dub>& ub, const Dl* l, const Du* u);
  template <typename Dg, typename Dlb, typename Dub, typename Dl, typename Du>
  void check_vector_sizes(const char* where, const Eigen::MatrixBase<Dg>& g,
                          const Eigen::MatrixBase<Dlb>& lb, const Eigen::MatrixBase<Dub>& ub,
                          const Dl* l, const Du* u) const;

  QpStatus invalid(const char* message) {
    data_ok_ = false;
    invalid_message_ = message;
    cache_valid_ = false;
    result_.status = QpStatus::invalid_input;
    result_.message = message;
    return QpStatus::invalid_input;
  }
  template <typename Dg, typename Dlb, typename Dub, typename Dl, typename Du>
  void store_vectors(const Eigen::MatrixBase<Dg>& g, const Eigen::MatrixBase<Dlb>& lb,
                     const Eigen::MatrixBase<Dub>& ub, const Dl* l, const Du* u) {
    g_ = g;
    lb_ = lb;
    ub_ = ub;
    if (l != nullptr) {
      l_ = *l;
      u_ = *u;
    }
  }
  const char* validate_vectors() const;
  const char* factorize();
  void refresh_equalities(bool* pattern_changed);

  bool is_row(int c) const { return c < m_; }
  bool is_equality(int c) const { return is_row(c) ? row_eq_[c] != 0 : bound_eq_[c - m_] != 0; }
  /// Bound b of constraint c on side s in the form nᵀx ≥ b.
  Scalar bound_of(int c, int s) const {
    if (is_row(c)) return s > 0 ? lb_[c] : -ub_[c];
    return s > 0 ? l_[c - m_] : -u_[c - m_];
  }
  /// nᵀv for constraint c on side s.
  template <typename V>
  Scalar normal_dot(int c, int s, const V& v) const {
    const Scalar dot = is_row(c) ? Scalar(A_.row(c).dot(v)) : Scalar(v[c - m_]);
    return s > 0 ? dot : -dot;
  }
  signed char& state_of(int c) { return is_row(c) ? row_state_[c] : bound_state_[c - m_]; }
  /// d = Jᵀ n for constraint c on side s.
  void compute_d(int c, int s) {
    if (is_row(c)) {
      d_.noalias() = J_.transpose() * A_.row(c).transpose();
    } else {
      d_ = J_.row(c - m_).transpose();
    }
    if (s < 0) d_ = -d_;
  }
  bool dependent(Index q) const {
    const Scalar tail = d_.tail(n_ - q).norm();
    return tail <= settings_.dependency_tolerance * d_.norm();
  }
  void add_to_factorization(Index q);
  void drop_from_factorization(Index k);
  void add_active(int c, int s, Scalar lambda);
  void solve_active_set();
  bool drop_negative_multipliers();
  int find_violated(int* sign, Scalar* max_violation);
  void finish(QpStatus status, const char* message);
  bool rebuild_factorization(Index count);
  bool within_tolerance(bool ax_current);
  /// A solve whose outputs overflowed: solved becomes inaccurate.
  void overflowed() {
    if (result_.status != QpStatus::solved) return;
    result_.status = QpStatus::inaccurate;
    result_.message = "the problem's scale overflows double precision (rescale H, g, A)";
  }
  void refine_active_set();
  // Copies the first count active constraints to previous_active_ for rebuild_factorization().
  // (The explicit bound keeps GCC 12 from warning falsely about fixed-size buffers.)
  void save_active_set(Index count) {
    const Index size = std::min<Index>(count, active_.size());
    for (Index k = 0; k < size; ++k) {
      previous_active_[k] = active_[k];
      previous_sign_[k] = active_sign_[k];
    }
  }
  /// Constraint c's violation is within 100 × the primal tolerance (rounding level).
  bool violation_is_rounding(int c, int s) const {
    const Scalar slack = bound_of(c, s) - normal_dot(c, s, result_.x);
    const Scalar norm = is_row(c) ? row_norm_[c] : Scalar(1);
    const Scalar loose = Scalar(100) * settings_.primal_tolerance *
                         (Scalar(1) + result_.x.template lpNorm<Eigen::Infinity>() +
                          std::abs(bound_of(c, s)) / norm);
    return slack / norm <= loose;
  }

  Settings settings_;
  Index n_ = 0;
  Index m_ = 0;
  Index q_ = 0;  // active-set size

  MatrixN H_;   // (regularised) Hessian, kept for residuals
  MatrixN J0_;  // L⁻ᵀ (upper triangular)
  MatrixN J_;   // L⁻ᵀ Q
  MatrixN R_;   // upper triangular, top-left q×q used
  MatrixA A_;
  VectorN g_, l_, u_;
  VectorM lb_, ub_, row_norm_, Ax_;
  VectorN x0_, d_, step_, tmp_, hh_, r_, lambda_;
  Eigen::Matrix<int, Vars, 1> active_;
  Eigen::Matrix<signed char, Vars, 1> active_sign_;
  Eigen::Matrix<int, Vars, 1> previous_active_;  // scratch for rebuilding a warm start
  Eigen::Matrix<signed char, Vars, 1> previous_sign_;
  // 0 inactive, +1/-1 active on the lower/upper side, 2 ignored for this solve (degenerate).
  Eigen::Matrix<signed char, Rows, 1> row_state_;
  Eigen::Matrix<signed char, Vars, 1> bound_state_;
  // Additions of each constraint in this solve (anti-cycling, see solve()).
  Eigen::Matrix<
      int, (Rows == Eigen::Dynamic || Vars == Eigen::Dynamic) ? Eigen::Dynamic : Rows + Vars, 1>
      add_count_;
  // 1 where lb_i = ub_i (l_j = u_j), as of the last init()/update().
  Eigen::Matrix<signed char, Rows, 1> row_eq_;
  Eigen::Matrix<signed char, Vars, 1> bound_eq_;
  Result result_;

  bool data_ok_ = false;
  bool factorized_ = false;
  const char* invalid_message_ = "init() has not been called";
  bool have_previous_ = false;  // active_[0..q_) holds a previous solve's active set
  bool cache_valid_ = false;    // J_, R_ factorise that set for the current H and A
  Index num_equalities_ = 0;
};

// ------------------------------------------------------------------------------------------
// Implementation

template <typename Scalar, int Vars, int Rows>
template <typename Dg, typename Dlb, typename Dub, typename Dl, typename Du>
void DenseQp<Scalar, Vars, Rows>::check_vector_sizes(const char* where,
                                                     const Eigen::MatrixBase<Dg>& g,
                                                     const Eigen::MatrixBase<Dlb>& lb,
                                                     const Eigen::MatrixBase<Dub>& ub, const Dl* l,
                                                     const Du* u) const {
  (void)where;
  check_argument(g.size() == n_ && (g.cols() == 1 || g.rows() == 1), "DenseQp: g",
                 "a vector of size n", g.size());
  check_argument(lb.size() == m_ && (lb.cols() == 1 || lb.rows() == 1), "DenseQp: lb",
                 "a vector of size m", lb.size());
  check_argument(ub.size() == m_ && (ub.cols() == 1 || ub.rows() == 1), "DenseQp: ub",
                 "a vector of size m", ub.size());
  if (l != nullptr) {
    check_argument(l->size() == n_, "DenseQp: l", "a vector of size n", l->size());
    check_argument(u->size() == n_, "DenseQp: u", "a vector of size n", u->size());
  }
}

template <typename Scalar, int Vars, int Rows>
template <typename DH, typename Dg, typename DA, typename Dlb, typename Dub, typename Dl,
          typename Du>
QpStatus DenseQp<Scalar, Vars, Rows>::init_impl(
    const Eigen::MatrixBase<DH>& H, const Eigen::MatrixBase<Dg>& g, const Eigen::MatrixBase<DA>& A,
    const Eigen::MatrixBase<Dlb>& lb, const Eigen::MatrixBase<Dub>& ub, const Dl* l, const Du* u) {
  check_argument(H.rows() == n_ && H.cols() == n_, "DenseQp::init: H", "an n x n matrix",
                 std::to_string(H.rows()) + " x " + std::to_string(H.cols()));
  check_argument(A.rows() == m_ && A.cols() == n_, "DenseQp::init: A", "an m x n matrix",
                 std::to_string(A.rows()) + " x " + std::to_string(A.cols()),
                 "m and n are fixed at construction");
  check_vector_sizes("DenseQp::init", g, lb, ub, l, u);
  cache_valid_ = false;
  result_.status = QpStatus::unsolved;
  result_.message = "";
  H_ = H;
  A_ = A;
  store_vectors(g, lb, ub, l, u);
  if (!detail::all_finite(H_)) return invalid("H has a NaN or Inf entry");
  if (!detail::all_finite(A_)) return invalid("A has a NaN or Inf entry");
  const Scalar h_scale = H_.cwiseAbs().maxCoeff();
  for (Index i = 0; i < n_; ++i) {
    for (Index j = 0; j < i; ++j) {
      if (std::abs(H_(i, j) - H_(j, i)) >
          Scalar(1e3) * Eigen::NumTraits<Scalar>::epsilon() * (Scalar(1) + h_scale)) {
        return invalid("H is not symmetric");
      }
    }
  }
  for (Index i = 0; i < m_; ++i) row_norm_[i] = A_.row(i).norm();
  if (const char* why = validate_vectors()) return invalid(why);
  if (const char* why = factorize()) return invalid(why);
  bool changed = false;
  refresh_equalities(&changed);
  data_ok_ = true;
  return QpStatus::unsolved;
}

template <typename Scalar, int Vars, int Rows>
template <typename Dg, typename Dlb, typename Dub, typename Dl, typename Du>
QpStatus DenseQp<Scalar, Vars, Rows>::update_impl(const Eigen::MatrixBase<Dg>& g,
                                                  const Eigen::MatrixBase<Dlb>& lb,
                                                  const Eigen::MatrixBase<Dub>& ub, const Dl* l,
                                                  const Du* u) {
  check_vector_sizes("DenseQp::update", g, lb, ub, l, u);
  result_.status = QpStatus::unsolved;
  result_.message = "";
  store_vectors(g, lb, ub, l, u);
  if (!factorized_) return invalid("update() needs a successful init() first");
  if (const char* why = validate_vectors()) return invalid(why);
  bool changed = false;
  refresh_equalities(&changed);
  if (changed) cache_valid_ = false;
  // An active side whose bound became infinite can no longer be active.
  for (Index k = 0; k < q_ && cache_valid_; ++k) {
    if (!std::isfinite(bound_of(active_[k], active_sign_[k]))) cache_valid_ = false;
  }
  data_ok_ = true;
  return QpStatus::unsolved;
}

template <typename Scalar, int Vars, int Rows>
const char* DenseQp<Scalar, Vars, Rows>::validate_vectors() const {
  if (!detail::all_finite(g_)) return "g has a NaN or Inf entry";
  for (Index i = 0; i < m_; ++i) {
    if (std::isnan(lb_[i]) || std::isnan(ub_[i])) return "lb or ub has a NaN entry";
    if (lb_[i] == kInf || ub_[i] == -kInf) return "lb = +inf or ub = -inf in some row";
    if (lb_[i] > ub_[i]) return "lb > ub in some row";
    if (row_norm_[i] == Scalar(0) && (lb_[i] > Scalar(0) || ub_[i] < Scalar(0))) {
      return "a zero row of A has bounds that exclude 0";
    }
  }
  for (Index j = 0; j < n_; ++j) {
    if (std::isnan(l_[j]) || std::isnan(u_[j])) return "l or u has a NaN entry";
    if (l_[j] == kInf || u_[j] == -kInf) return "l = +inf or u = -inf for some variable";
    if (l_[j] > u_[j]) return "l > u for some variable";
  }
  return nullptr;
}

template <typename Scalar, int Vars, int Rows>
const char* DenseQp<Scalar, Vars, Rows>::factorize() {
  factorized_ = false;
  if (!(settings_.regularization >= Scalar(0)) || !std::isfinite(settings_.regularization)) {
    return "settings.regularization must be finite and >= 0";
  }
  H_.diagonal().array() += settings_.regularization;
  // H is factorised block by block where it is block diagonal (contiguous blocks with exactly
  // zero coupling), as walking QPs are (x, y and yaw decouple): O(Σ b³) instead of O(n³).
  // Left-looking Cholesky H_b = L_b L_bᵀ into J_ (scratch), then J0 = L⁻ᵀ column by column.
  auto& L = J_;  // only the blocks' lower triangles are written and read
  J0_.setZero();
  Scalar max_diag = Scalar(0);
  Scalar min_diag = kInf;
  Index start = 0;
  Index reach = 0;
  for (Index i = 0; i < n_; ++i) {
    Index last = n_ - 1;  // last nonzero of row i = of column i (H is symmetric)
    while (last > reach && H_(last, i) == Scalar(0)) --last;
    reach = std::max(reach, last);
    if (reach > i) continue;
    // Block [start, i].
    const Index b = i + 1 - start;
    for (Index j = start; j <= i; ++j) {
      const Index k = j - start;
      auto col = tmp_.segment(j, i + 1 - j);
      col.noalias() = H_.col(j).segment(j, i + 1 - j) -
                      L.block(j, start, i + 1 - j, k) * L.block(j, start, 1, k).transpose();
      if (!(col[0] > Scalar(0))) {
        return "H is not positive definite (hint: set settings.regularization > 0 for PSD H)";
      }
      const Scalar diag = std::sqrt(col[0]);
      L(j, j) = diag;
      L.col(j).segment(j + 1, i - j) = col.tail(i - j) / diag;
      max_diag = std::max(max_diag, diag);
      min_diag = std::min(min_diag, diag);
    }
    for (Index j = start; j <= i; ++j) {
      const Index k = j - start + 1;
      auto y = J0_.col(j).segment(start, k);
      y.setZero();
      y[k - 1] = Scalar(1);
      L.block(start, start, k, k)
          .transpose()
          .template triangularView<Eigen::Upper>()
          .solveInPlace(y);
    }
    (void)b;
    start = i + 1;
    reach = start;
  }
  if (!(min_diag > std::sqrt(Eigen::NumTraits<Scalar>::epsilon()) * Scalar(1e-3) * max_diag)) {
    return "H is numerically singular (hint: set settings.regularization > 0 for PSD H)";
  }
  factorized_ = true;
  return nullptr;
}

template <typename Scalar, int Vars, int Rows>
void DenseQp<Scalar, Vars, Rows>::refresh_equalities(bool* pattern_changed) {
  bool changed = false;
  Index count = 0;
  for (Index i = 0; i < m_; ++i) {
    const signed char eq = lb_[i] == ub_[i] ? 1 : 0;
    changed = changed || eq != row_eq_[i];
    row_eq_[i] = eq;
    count += eq;
  }
  for (Index j = 0; j < n_; ++j) {
    const signed char eq = l_[j] == u_[j] ? 1 : 0;
    changed = changed || eq != bound_eq_[j];
    bound_eq_[j] = eq;
    count += eq;
  }
  num_equalities_ = count;
  *pattern_changed = changed;
}

// Appends the constraint whose d = Jᵀn is in d_ to the factorisation: one Householder reflection
// maps d₂ = d_[q..n) onto σ e₁ and is applied to J's trailing columns; R gets column (d₁, σ).
template <typename Scalar, int Vars, int Rows>
void DenseQp<Scalar, Vars, Rows>::add_to_factorization(Index q) {
  const Index nq = n_ - q;
  WALKGEN_ASSERT(nq >= 1);
  R_.col(q).head(q) = d_.head(q);
  if (nq == 1) {
    R_(q, q) = d_[q];
  } else {
    auto d2 = d_.tail(nq);
    const Scalar alpha = d2.norm();
    const Scalar x0 = d2[0];
    const Scalar sign = x0 >= Scalar(0) ? Scalar(1) : Scalar(-1);
    auto v = hh_.head(nq);
    v = d2;
    v[0] += sign * alpha;
    const Scalar beta = Scalar(1) / (alpha * (alpha + std::abs(x0)));  // 2 / vᵀv
    auto J2 = J_.rightCols(nq);
    auto w = tmp_.head(n_);
    w.noalias() = J2 * v;
    w *= beta;
    J2.noalias() -= w * v.transpose();
    R_(q, q) = -sign * alpha;
  }
  R_.col(q).tail(n_ - q - 1).setZero();
}

// Removes active constraint k: R loses column k and is made triangular again by Givens
// rotations on rows (j, j+1), applied alike to J's columns (j, j+1).
template <typename Scalar, int Vars, int Rows>
void DenseQp<Scalar, Vars, Rows>::drop_from_factorization(Index k) {
  for (Index j = k; j + 1 < q_; ++j) R_.col(j).head(j + 2) = R_.col(j + 1).head(j + 2);
  for (Index j = k; j + 1 < q_; ++j) {
    const Scalar a = R_(j, j);
    const Scalar b = R_(j + 1, j);
    if (b == Scalar(0)) continue;
    const Scalar rho = std::hypot(a, b);
    const Scalar c = a / rho;
    const Scalar s = b / rho;
    for (Index col = j; col + 1 < q_; ++col) {
      const Scalar r1 = R_(j, col);
      const Scalar r2 = R_(j + 1, col);
      R_(j, col) = c * r1 + s * r2;
      R_(j + 1, col) = -s * r1 + c * r2;
    }
    R_(j + 1, j) = Scalar(0);
    for (Index i = 0; i < n_; ++i) {
      const Scalar j1 = J_(i, j);
      const Scalar j2 = J_(i, j + 1);
      J_(i, j) = c * j1 + s * j2;
      J_(i, j + 1) = -s * j1 + c * j2;
    }
  }
  const int c = active_[k];
  state_of(c) = 0;
  for (Index j = k; j + 1 < q_; ++j) {
    active_[j] = active_[j + 1];
    active_sign_[j] = active_sign_[j + 1];
    lambda_[j] = lambda_[j + 1];
  }
  --q_;
  R_.col(q_).setZero();
}

template <typename Scalar, int Vars, int Rows>
void DenseQp<Scalar, Vars, Rows>::add_active(int c, int s, Scalar lambda) {
  add_to_factorization(q_);
  active_[q_] = c;
  active_sign_[q_] = static_cast<signed char>(s);
  lambda_[q_] = lambda;
  state_of(c) = static_cast<signed char>(s);
  ++q_;
}

// Primal–dual solution of the equality-constrained QP on the active set, from scratch:
// with s = b − Nᵀx₀ (x₀ = −H⁻¹g): λ = R⁻¹R⁻ᵀ s and x = x₀ + J₁R⁻ᵀ s.
template <typename Scalar, int Vars, int Rows>
void DenseQp<Scalar, Vars, Rows>::solve_active_set() {
  result_.x = x0_;
  if (q_ == 0) return;
  auto w = r_.head(q_);
  for (Index k = 0; k < q_; ++k) {
    w[k] = bound_of(active_[k], active_sign_[k]) - normal_dot(active_[k], active_sign_[k], x0_);
  }
  const auto Rq = R_.topLeftCorner(q_, q_);
  Rq.transpose().template triangularView<Eigen::Lower>().solveInPlace(w);
  result_.x.noalias() += J_.leftCols(q_) * w;
  Rq.template triangularView<Eigen::Upper>().solveInPlace(w);
  lambda_.head(q_) = w;
}

// Whether x is finite and every constraint, active and ignored ones included, holds within
// 100 × the primal tolerance (violation_is_rounding's level); sets result_.primal_residual.
// ax_current: Ax_ already holds A x (find_violated() computed it for this x).
template <typename Scalar, int Vars, int Rows>
bool DenseQp<Scalar, Vars, Rows>::within_tolerance(bool ax_current) {
  const auto& x = result_.x;
  if (!detail::all_finite(x)) return false;
  const Scalar loose = Scalar(100) * settings_.primal_tolerance;
  const Scalar xscale = Scalar(1) + x.template lpNorm<Eigen::Infinity>();
  bool ok = true;
  Scalar max_abs_viol = Scalar(0);
  if (m_ > 0 && !ax_current) Ax_.noalias() = A_ * x;
  for (Index i = 0; i < m_; ++i) {
    const Scalar viol = std::max(lb_[i] - Ax_[i], Ax_[i] - ub_[i]);
    if (!(viol > Scalar(0))) continue;
    max_abs_viol = std::max(max_abs_viol, viol);
    if (row_norm_[i] == Scalar(0)) continue;  // a zero row constrains nothing it can reach
    const Scalar bound = lb_[i] - Ax_[i] > Ax_[i] - ub_[i] ? lb_[i] : ub_[i];
    ok = ok && viol / row_norm_[i] <= loose * (xscale + std::abs(bound) / row_norm_[i]);
  }
  for (Index j = 0; j < n_; ++j) {
    const Scalar viol = std::max(l_[j] - x[j], x[j] - u_[j]);
    if (!(viol > Scalar(0))) continue;
    max_abs_viol = std::max(max_abs_viol, viol);
    const Scalar bound = l_[j] - x[j] > x[j] - u_[j] ? l_[j] : u_[j];
    ok = ok && viol <= loose * (xscale + std::abs(bound));
  }
  result_.primal_residual = max_abs_viol;
  return ok;
}

// One step of iterative refinement on the active set's equations Nᵀx = b: with r = b − Nᵀx,
// x += J₁R⁻ᵀr and λ += R⁻¹R⁻ᵀr (the KKT system's correction, which keeps Hx + g = Nλ).
template <typename Scalar, int Vars, int Rows>
void DenseQp<Scalar, Vars, Rows>::refine_active_set() {
  if (q_ == 0) return;
  auto w = r_.head(q_);
  for (Index k = 0; k < q_; ++k) {
    w[k] =
        bound_of(active_[k], active_sign_[k]) - normal_dot(active_[k], active_sign_[k], result_.x);
  }
  const auto Rq = R_.topLeftCorner(q_, q_);
  Rq.transpose().template triangularView<Eigen::Lower>().solveInPlace(w);
  result_.x.noalias() += J_.leftCols(q_) * w;
  Rq.template triangularView<Eigen::Upper>().solveInPlace(w);
  lambda_.head(q_) += w;
}

// Drops the most negative inequality multiplier until none is negative (warm start only).
template <typename Scalar, int Vars, int Rows>
bool DenseQp<Scalar, Vars, Rows>::drop_negative_multipliers() {
  bool dropped = false;
  for (;;) {
    Index worst = -1;
    Scalar most_negative = Scalar(0);
    for (Index k = 0; k < q_; ++k) {
      if (is_equality(active_[k])) continue;
      if (lambda_[k] < most_negative) {
        most_negative = lambda_[k];
        worst = k;
      }
    }
    if (worst < 0) return dropped;
    drop_from_factorization(worst);
    solve_active_set();
    dropped = true;
  }
}

// The most violated inactive constraint (scaled by its normal's length), or -1.
template <typename Scalar, int Vars, int Rows>
int DenseQp<Scalar, Vars, Rows>::find_violated(int* sign, Scalar* max_violation) {
  const auto& x = result_.x;
  const Scalar xscale = Scalar(1) + x.template lpNorm<Eigen::Infinity>();
  const Scalar tol = settings_.primal_tolerance;
  int best = -1;
  Scalar best_viol = Scalar(0);
  Scalar max_abs_viol = Scalar(0);
  if (m_ > 0) Ax_.noalias() = A_ * x;
  for (Index i = 0; i < m_; ++i) {
    const Scalar v = Ax_[i];
    const Scalar below = lb_[i] - v;
    const Scalar above = v - ub_[i];
    const Scalar viol = std::max(below, above);
    if (viol <= Scalar(0)) continue;
    max_abs_viol = std::max(max_abs_viol, viol);
    if (row_state_[i] != 0 || row_norm_[i] == Scalar(0)) continue;
    const Scalar bound = below > above ? lb_[i] : ub_[i];
    const Scalar scaled = viol / row_norm_[i];
    if (scaled > tol * (xscale + std::abs(bound) / row_norm_[i]) && scaled > best_viol) {
      best_viol = scaled;
      best = static_cast<int>(i);
      *sign = below > above ? 1 : -1;
    }
  }
  for (Index j = 0; j < n_; ++j) {
    const Scalar below = l_[j] - x[j];
    const Scalar above = x[j] - u_[j];
    const Scalar viol = std::max(below, above);
    if (viol <= Scalar(0)) continue;
    max_abs_viol = std::max(max_abs_viol, viol);
    if (bound_state_[j] != 0) continue;
    const Scalar bound = below > above ? l_[j] : u_[j];
    if (viol > tol * (xscale + std::abs(bound)) && viol > best_viol) {
      best_viol = viol;
      best = static_cast<int>(m_ + j);
      *sign = below > above ? 1 : -1;
    }
  }
  *max_violation = max_abs_viol;
  return best;
}

template <typename Scalar, int Vars, int Rows>
void DenseQp<Scalar, Vars, Rows>::finish(QpStatus status, const char* message) {
  if (!detail::all_finite(result_.x)) result_.x.setZero();  // an overflowed iterate: never NaN out
  result_.status = status;
  result_.message = message;
  result_.active_set_size = static_cast<int>(q_);
  result_.y.setZero();
  result_.z.setZero();
  for (Index k = 0; k < q_; ++k) {
    const int c = active_[k];
    // Inequality multipliers are >= 0 in exact arithmetic; clip rounding noise.
    const Scalar lam = is_equality(c) ? lambda_[k] : std::max(lambda_[k], Scalar(0));
    const Scalar signed_lam = active_sign_[k] > 0 ? -lam : lam;
    if (is_row(c)) {
      result_.y[c] = signed_lam;
    } else {
      result_.z[c - m_] = signed_lam;
    }
  }
  have_previous_ = true;
  cache_valid_ = true;
  // Finite data whose products overflow (e.g. H ~ 1e-150 against g ~ 1e150) can leave the
  // multipliers or the objective non-finite: never report those, never call them solved.
  if (!detail::all_finite(result_.y) || !detail::all_finite(result_.z)) {
    result_.y.setZero();
    result_.z.setZero();
    overflowed();
  }
  if (!settings_.compute_residuals) return;
  const auto& x = result_.x;
  step_.noalias() = H_.template selfadjointView<Eigen::Lower>() * x;  // Hx
  result_.objective = Scalar(0.5) * x.dot(step_) + g_.dot(x);
  step_ += g_;
  step_ += result_.z;
  Scalar compl_max = Scalar(0);
  for (Index k = 0; k < q_; ++k) {
    const int c = active_[k];
    const Scalar slack = normal_dot(c, active_sign_[k], x) - bound_of(c, active_sign_[k]);
    if (is_row(c)) {
      step_.noalias() += A_.row(c).transpose() * result_.y[c];
      compl_max = std::max(compl_max, std::abs(result_.y[c] * slack));
    } else {
      compl_max = std::max(compl_max, std::abs(result_.z[c - m_] * slack));
    }
  }
  result_.dual_residual = step_.template lpNorm<Eigen::Infinity>();
  result_.complementarity = compl_max;
  if (!std::isfinite(result_.objective) || !std::isfinite(result_.dual_residual) ||
      !std::isfinite(result_.complementarity)) {
    result_.objective = result_.dual_residual = result_.complementarity = kInf;
    overflowed();
  }
}

// Factorises, from J0, the equalities and then the first `count` constraints listed in
// previous_active_/previous_sign_ (skipping any that became dependent or unbounded).
// Returns whether any listed constraint was taken.
template <typename Scalar, int Vars, int Rows>
bool DenseQp<Scalar, Vars, Rows>::rebuild_factorization(Index count) {
  J_ = J0_;
  R_.setZero();
  q_ = 0;
  row_state_.setZero();
  bound_state_.setZero();
  // Equalities first: they are never dropped.
  for (Index c = 0; c < m_ + n_ && num_equalities_ > 0; ++c) {
    const int ci = static_cast<int>(c);
    if (!is_equality(ci) || q_ >= n_) continue;
    if (is_row(ci) && row_norm_[c] == Scalar(0)) continue;
    compute_d(ci, 1);
    if (dependent(q_)) continue;  // consistent or not, the main loop decides
    add_active(ci, 1, Scalar(0));
  }
  bool taken = false;
  for (Index k = 0; k < count; ++k) {
    const int c = previous_active_[k];
    const int s = previous_sign_[k];
    if (c >= m_ + n_ || is_equality(c) || state_of(c) != 0 || q_ >= n_) continue;
    if (!std::isfinite(bound_of(c, s))) continue;
    compute_d(c, s);
    if (dependent(q_)) continue;
    add_active(c, s, Scalar(0));
    taken = true;
  }
  return taken;
}

template <typename Scalar, int Vars, int Rows>
auto DenseQp<Scalar, Vars, Rows>::solve() -> const Result& {
  result_.iterations = 0;
  result_.warm_started = false;
  result_.reused_factorization = false;
  result_.objective = result_.primal_residual = Scalar(0);
  result_.dual_residual = result_.complementarity = Scalar(0);
  if (!data_ok_) {
    result_.x.setZero();
    result_.y.setZero();
    result_.z.setZero();
    result_.status = QpStatus::invalid_input;
    result_.message = invalid_message_;
    return result_;
  }
  const int max_iter = settings_.max_iterations > 0
                           ? settings_.max_iterations
                           : static_cast<int>(std::max<Index>(100, 5 * (n_ + m_)));
  // x0 = −H⁻¹g = −J0 J0ᵀ g
  tmp_.noalias() = J0_.transpose().template triangularView<Eigen::Lower>() * g_;
  x0_.noalias() = J0_.template triangularView<Eigen::Upper>() * tmp_;
  x0_ = -x0_;
  if (!detail::all_finite(x0_)) {
    // H is tiny against g: the unconstrained minimiser overflows and no step can be trusted.
    result_.x.setZero();
    q_ = 0;
    finish(QpStatus::inaccurate, "-H^-1 g overflows (H is tiny against g; rescale the problem)");
    have_previous_ = cache_valid_ = false;
    return result_;
  }

  add_count_.setZero();
  const bool warm = settings_.warm_start && have_previous_;
  if (warm && cache_valid_) {
    result_.warm_started = true;
    result_.reused_factorization = true;
    // J_, R_, active_ are those of the previous solve; refresh the state flags.
    row_state_.setZero();
    bound_state_.setZero();
    for (Index k = 0; k < q_; ++k) state_of(active_[k]) = active_sign_[k];
  } else {
    const Index previous = warm ? q_ : 0;
    save_active_set(previous);
    result_.warm_started = rebuild_factorization(previous);
  }
  solve_active_set();
  if (result_.warm_started) drop_negative_multipliers();

  bool refined = true;  // x and λ were just computed from the active set
  int refreshes = 0;
  for (;;) {
    int sign = 0;
    Scalar max_violation = Scalar(0);
    const int p = find_violated(&sign, &max_violation);
    result_.primal_residual = max_violation;
    if (p < 0) {
      // Optimal. Recompute x and λ from the active set to shed accumulated rounding; accept
      // when nothing new is violated afterwards.
      if (!refined && q_ > 0) {
        solve_active_set();
        refined = true;
        continue;
      }
      // find_violated() skips the active constraints: verify every constraint before calling
      // x a solution. Where cancellation against a huge x0 = −H⁻¹g left an active constraint
      // off its bound, refine the active set's equations (at most twice).
      // find_violated() has just computed Ax for this x.
      bool feasible = within_tolerance(true);
      for (int pass = 0; pass < 2 && !feasible; ++pass) {
        refine_active_set();
        feasible = within_tolerance(false);
      }
      if (!feasible) {
        finish(QpStatus::inaccurate, "rounding left a constraint violated beyond the tolerance");
        return result_;
      }
      finish(QpStatus::solved, "");
      return result_;
    }
    // Goldfarb–Idnani step 2: make constraint p active.
    Scalar lambda_p = Scalar(0);
    // Anti-cycling: in degenerate corners, rounding in the updated factors can make nearly
    // tight constraints evict each other forever. When a constraint comes back a fourth time,
    // refactorise the active set from scratch and recompute x and λ (5 times at most per solve);
    // after that, such a constraint violated only at rounding level (≤ 100 × the tolerance) is
    // left out for the rest of this solve.
    if (++add_count_[p] > 3) {
      if (refreshes < 5) {
        ++refreshes;
        save_active_set(q_);
        rebuild_factorization(q_);
        solve_active_set();
        drop_negative_multipliers();
        add_count_.setZero();
        refined = false;
        continue;
      }
      if (violation_is_rounding(p, sign)) {
        state_of(p) = 2;
        continue;
      }
    }
    for (;;) {
      if (result_.iterations >= max_iter) {
        finish(QpStatus::max_iterations, "iteration limit reached");
        return result_;
      }
      compute_d(p, sign);
      bool dep = q_ >= n_ || dependent(q_);
      // Dual step direction r = R⁻¹ d₁.
      auto r = r_.head(q_);
      r = d_.head(q_);
      R_.topLeftCorner(q_, q_).template triangularView<Eigen::Upper>().solveInPlace(r);
      // Partial step t1: largest step keeping the inequality multipliers >= 0.
      Scalar t1 = kInf;
      Index drop = -1;
      for (Index k = 0; k < q_; ++k) {
        if (r[k] > Scalar(0) && !is_equality(active_[k])) {
          const Scalar t = std::max(lambda_[k], Scalar(0)) / r[k];
          if (t < t1) {
            t1 = t;
            drop = k;
          }
        }
      }
      // Full step t2: makes p satisfied with equality along z = J₂d₂.
      Scalar t2 = kInf;
      if (!dep) {
        step_.noalias() = J_.rightCols(n_ - q_) * d_.tail(n_ - q_);
        const Scalar slack = bound_of(p, sign) - normal_dot(p, sign, result_.x);
        // nᵀz equals ‖d₂‖² in exact arithmetic; using the computed value makes the full step
        // land on the constraint even when the factors carry rounding.
        const Scalar ztn = normal_dot(p, sign, step_);
        if (ztn > Scalar(0.5) * d_.tail(n_ - q_).squaredNorm()) {
          t2 = std::max(slack / ztn, Scalar(0));
        } else {
          dep = true;  // the factors are too inaccurate to step along z
        }
      }
      if (dep) {
        // p lies in the span of the active normals. If it is violated only at rounding level,
        // trading it against the active constraints that span it can cycle without progress:
        // ignore it for this solve. Otherwise release a constraint (below), or, when none can
        // be released, the constraints are inconsistent.
        if (violation_is_rounding(p, sign)) {
          state_of(p) = 2;
          break;
        }
        if (drop < 0) {
          finish(QpStatus::infeasible, "the constraints are inconsistent");
          return result_;
        }
      }
      if (std::isnan(t2) || (drop < 0 && !(!dep && t2 <= t1))) {
        // Overflow made the step length NaN (e.g. inf/inf): no constraint can be added or
        // dropped safely.
        finish(QpStatus::inaccurate, "the active-set step overflowed (rescale H, g, A)");
        return result_;
      }
      const Scalar t = std::min(t1, t2);
      ++result_.iterations;
      if (!dep) result_.x.noalias() += t * step_;
      lambda_.head(q_).noalias() -= t * r;
      if (drop >= 0 && t == t1) lambda_[drop] = Scalar(0);  // exactly, not by rounding
      lambda_p += t;
      if (!dep && t2 <= t1) {
        add_active(p, sign, lambda_p);
        break;
      }
      drop_from_factorization(drop);
    }
    refined = false;
  }
}

}  // namespace walkgen
