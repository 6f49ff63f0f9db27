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
/// (thesis eq. 2.83–2.84). With H = L Lᵀ and the q active normals N (n × q) it keeps an
/// orthogonal Q and an upper-triangular R such that L⁻¹ N = Q [R; 0], i.e. J₁ᵀ N = R for the
/// first q columns J₁ of J = L⁻ᵀ Q. Each active-set change updates Q and R by one Householder
/// reflection per added constraint or Givens rotations per dropped one: O(n²) work per change.
///
/// Every solve that cannot reuse the previous factorisation (after init(): H and A changed)
/// refactorises its warm-start active set from scratch, and there J is not formed: Q is kept in
/// product form, Q = P₀ P₁ ⋯ P_{r−1} W, the reflections P_k = I − β_k v_k v_kᵀ (v_k zero above
/// row k) of a left-looking Householder QR of L⁻¹N, then the explicit orthogonal
/// W = diag(I, W̃) that collects the changes made since (W̃ covers the columns from the first one
/// that a later change touched; W = I until a constraint is dropped, and additions until then
/// join the product as further P_k). Applying J or Jᵀ to a vector costs a triangular solve with
/// L (block by block where H is block diagonal) and one pass over the v_k, about what a product
/// with an explicit J costs, while the refactorisation of q constraints costs ≈ 2nq² − ⅔q³
/// flops plus q solves instead of ≈ 4nq(n − q/2) for the updates of an explicit J and 2n²q for
/// the products Jᵀn (walking MPC, N = 64: n = 152, q = 119, three blocks of H: 3.2 + 1.2 Mflop
/// instead of 6.7 + 5.5). Cold starts (fewer than n/4 constraints to refactorise) and small
/// problems (n < 32) keep J = L⁻ᵀQ explicitly instead: the many changes that follow a cold start
/// cost less with it.
///
/// Warm start: solve() begins from the previous solve's active set. After update(), which
/// changes only g and the bounds, the factorisation of H *and* of that active set are reused, so
/// a solve whose active set did not change costs a few matrix–vector products.
///
/// Data: the solver owns the problem's data (problem(), a QpData). init(H, g, A, ...) copies
/// into them; a caller that assembles its QP every tick writes into problem() in place and calls
/// init() (or update()) without arguments, so the data are never copied.
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
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <string>
#include <type_traits>

#include "walkgen/core/assert.hpp"
#include "walkgen/core/exceptions.hpp"
#include "walkgen/qp/detail/dense_qp_kernels.hpp"

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

namespace detail {
/// One QpSettings field's check: its name, the range it must be in, whether it is, its value and
/// the same as one static message (for QpResult::message).
template <typename Scalar>
struct QpSettingsCheck {
  const char* field;
  const char* expected;
  const char* message;
  bool ok;
  Scalar value;
};

template <typename Scalar>
std::array<QpSettingsCheck<Scalar>, 4> qp_settings_checks(const QpSettings<Scalar>& s) {
  using std::isfinite;
  const Scalar dep = s.dependency_tolerance;
  return {
      {{"QpSettings.max_iterations", "an integer >= 0 (0 picks a default)",
        "QpSettings.max_iterations must be >= 0", s.max_iterations >= 0, Scalar(s.max_iterations)},
       {"QpSettings.regularization", "a finite value >= 0",
        "QpSettings.regularization must be finite and >= 0",
        isfinite(s.regularization) && s.regularization >= Scalar(0), s.regularization},
       {"QpSettings.primal_tolerance", "a finite value > 0",
        "QpSettings.primal_tolerance must be finite and > 0",
        isfinite(s.primal_tolerance) && s.primal_tolerance > Scalar(0), s.primal_tolerance},
       {"QpSettings.dependency_tolerance", "a value in (0, 1)",
        "QpSettings.dependency_tolerance must be in (0, 1)", dep > Scalar(0) && dep < Scalar(1),
        dep}}};
}

/// The message of the first unusable QpSettings field, or nullptr.
template <typename Scalar>
const char* qp_settings_problem(const QpSettings<Scalar>& s) {
  for (const auto& c : qp_settings_checks(s)) {
    if (!c.ok) return c.message;
  }
  return nullptr;
}
}  // namespace detail

/// Checks the solver's settings (DenseQp's constructor calls it; init() reports settings changed
/// since through settings() as QpStatus::invalid_input, naming the field).
/// @throws walkgen::invalid_argument naming the first bad field, its range and its value.
template <typename Scalar>
void validate(const QpSettings<Scalar>& s) {
  for (const auto& c : detail::qp_settings_checks(s)) {
    check_argument(c.ok, c.field, c.expected, c.value);
  }
}

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

/// A QP's data, minimise ½xᵀHx + gᵀx subject to lb ≤ Ax ≤ ub and l ≤ x ≤ u (file comment).
/// DenseQp owns one (DenseQp::problem()): a caller that assembles its QP every tick writes into
/// it in place and calls init() / update() without arguments, so the data exist once. DenseQp's
/// constructor sizes them with H, g and A zero and every bound absent (±∞).
template <typename Scalar = double, int Vars = Eigen::Dynamic, int Rows = Eigen::Dynamic>
struct QpData {
  Eigen::Matrix<Scalar, Vars, Vars> H;  ///< n × n, symmetric positive definite
  Eigen::Matrix<Scalar, Vars, 1> g;     ///< n
  Eigen::Matrix<Scalar, Rows, Vars, detail::qp_constraint_layout(Vars, Rows)> A;  ///< m × n
  Eigen::Matrix<Scalar, Rows, 1> lb, ub;  ///< m; ±∞ where a side is absent
  Eigen::Matrix<Scalar, Vars, 1> l, u;    ///< n; ±∞ where a side is absent
};

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
  using Problem = QpData<Scalar, Vars, Rows>;
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
    validate(settings_);
    check_argument(num_vars >= 1, "DenseQp: num_vars", "n >= 1", num_vars);
    check_argument(num_rows >= 0, "DenseQp: num_rows", "m >= 0", num_rows);
    check_argument(Vars == Eigen::Dynamic || num_vars == Vars, "DenseQp: num_vars", Vars, num_vars,
                   "it must equal the compile-time Vars");
    check_argument(Rows == Eigen::Dynamic || num_rows == Rows, "DenseQp: num_rows", Rows, num_rows,
                   "it must equal the compile-time Rows");
    n_ = num_vars;
    m_ = num_rows;
    w0_ = n_;
    p_.H.setZero(n_, n_);
    L_.setZero(n_, n_);
    H_factored_.setZero(n_, n_);
    inv_diag_.setZero(n_);
    rhs_.setZero(n_);
    V_.setZero(n_, n_);
    W_.setZero(n_, n_);
    beta_.setZero(n_);
    T_.setZero(n_ + kBlock, kBlock);
    block_end_.setConstant(n_, static_cast<int>(n_));
    R_.setZero(n_, n_);
    p_.A.setZero(m_, n_);
    p_.g.setZero(n_);
    // Absent sides until written (problem() in place): no row or variable is bounded.
    p_.lb.setConstant(m_, -kInf);
    p_.ub.setConstant(m_, kInf);
    p_.l.setConstant(n_, -kInf);
    p_.u.setConstant(n_, kInf);
    row_norm_.setOnes(m_);
    Ax_.setZero(m_);
    x0_.setZero(n_);
    d_.setZero(n_);
    step_.setZero(n_);
    tmp_.setZero(n_);
    hh_.setZero(n_);
    work_.setZero(n_);
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

  /// The problem's data, sized n and m at construction. Write them in place, then call init()
  /// (or update() if only g and the bounds changed): no copy. Keep their sizes.
  Problem& problem() { return p_; }
  const Problem& problem() const { return p_; }

  /// Validates and factorises problem() as it stands (see init(H, g, A, lb, ub, l, u)).
  /// @throws walkgen::invalid_argument if problem()'s sizes were changed.
  QpStatus init();
  /// problem()'s g and bounds changed, H and A did not: keeps the factorisations (see
  /// update(g, lb, ub)). H and A must be exactly those of the last init().
  /// @throws walkgen::invalid_argument if problem()'s sizes were changed.
  QpStatus update();

  /// Sets the whole problem and factorises H. Bounds l ≤ x ≤ u absent (±∞).
  /// @return QpStatus::unsolved when the data are usable, QpStatus::invalid_input otherwise.
  /// @throws walkgen::invalid_argument on mismatched sizes.
  template <typename DH, typename Dg, typename DA, typename Dlb, typename Dub>
  QpStatus init(const Eigen::MatrixBase<DH>& H, const Eigen::MatrixBase<Dg>& g,
                const Eigen::MatrixBase<DA>& A, const Eigen::MatrixBase<Dlb>& lb,
                const Eigen::MatrixBase<Dub>& ub) {
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
  // Reflections applied together (append_reflection()), columns of L per pass in the solves
  // with L (detail::lower_solve()): the fastest of 3, 4, 6, 8 (and 2, 4, 6, 8) on the walking
  // MPC's QPs, N = 8 to 64.
  static constexpr int kBlock = 6;
  static constexpr int kPanel = 4;
  // The product form is used for problems of at least kProductMinVars variables when a
  // refactorisation from scratch takes at least n / 4 constraints (rebuild_factorization()):
  // on the walking MPC's QPs, n = 19 (N = 8) is faster with J explicit, n = 38 (N = 16) in
  // product form.
  static constexpr Index kProductMinVars = 32;
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
  void check_problem_sizes(const char* where) const;
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
    p_.g = g;
    p_.lb = lb;
    p_.ub = ub;
    if (l != nullptr) {
      p_.l = *l;
      p_.u = *u;
    }
  }
  const char* validate_vectors() const;
  const char* factorize();
  void refresh_equalities(bool* pattern_changed);

  bool is_row(int c) const { return c < m_; }
  bool is_equality(int c) const { return is_row(c) ? row_eq_[c] != 0 : bound_eq_[c - m_] != 0; }
  /// Bound b of constraint c on side s in the form nᵀx ≥ b.
  Scalar bound_of(int c, int s) const {
    if (is_row(c)) return s > 0 ? p_.lb[c] : -p_.ub[c];
    return s > 0 ? p_.l[c - m_] : -p_.u[c - m_];
  }
  /// nᵀv for constraint c on side s.
  template <typename V>
  Scalar normal_dot(int c, int s, const V& v) const {
    const Scalar dot = is_row(c) ? Scalar(p_.A.row(c).dot(v)) : Scalar(v[c - m_]);
    return s > 0 ? dot : -dot;
  }
  signed char& state_of(int c) { return is_row(c) ? row_state_[c] : bound_state_[c - m_]; }
  /// d = Jᵀ n (= Qᵀ L⁻¹ n in product form) for constraint c on side s.
  void compute_d(int c, int s) {
    if (explicit_j_) {
      if (is_row(c)) {
        d_.noalias() = W_.transpose() * p_.A.row(c).transpose();
      } else {
        d_ = W_.row(c - m_).transpose();
      }
      if (s < 0) d_ = -d_;
      return;
    }
    if (is_row(c)) {
      d_ = p_.A.row(c).transpose();
    } else {
      d_.setZero();
      d_[c - m_] = Scalar(1);
    }
    if (s < 0) d_ = -d_;
    solve_with_l<false>(d_);
    apply_qt(d_);
  }
  /// v ← J v (= L⁻ᵀ Q v in product form) for v zero outside [first, first + count).
  void apply_j(VectorN& v, Index first, Index count) {
    if (explicit_j_) {
      work_.noalias() = W_.middleCols(first, count) * v.segment(first, count);
      v = work_;
      return;
    }
    apply_q(v);
    solve_with_l<true>(v);
  }
  template <bool Transposed>
  void solve_with_l(VectorN& v) const;
  void apply_qt(VectorN& v);
  void apply_q(VectorN& v);
  void extend_w(Index k);
  void form_j0();
  void append_reflection(Scalar beta);
  template <bool Transposed>
  void apply_group(Index k0, VectorN& v) const;
  bool dependent(Index q) const {
    const Scalar tail = d_.tail(n_ - q).norm();
    return tail <= settings_.dependency_tolerance * d_.norm();
  }
  void add_to_factorization(Index q);
  void drop_from_factorization(Index k);
  void add_active(int c, int s, Scalar lambda);
  void solve_active_set();
  void solve_multipliers();
  void update_x();
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

  Problem p_;  // the data, owned once (problem())
  MatrixN L_;  // H = L Lᵀ: the lower triangles of H's diagonal blocks (zero elsewhere)
  // Product form (file comment), Q = P₀ ⋯ P_{r−1} W: column k < r of V_ holds v_k in rows
  // k..n−1 (zeros above, within its group), with β_k in beta_ (0 for P_k = I); rows
  // k0..k0+kBlock−1 of T_ hold the T of the group that starts at P_k0 (append_reflection());
  // W_ holds W̃ in rows and columns w0_..n−1. Explicit form (explicit_j_): W_ holds J.
  MatrixN V_;
  Eigen::Matrix<Scalar, Vars == Eigen::Dynamic ? Eigen::Dynamic : Vars + kBlock, kBlock> T_;
  MatrixN W_;
  MatrixN R_;  // upper triangular, top-left q×q used
  VectorM row_norm_, Ax_;
  VectorN x0_, d_, step_, tmp_, hh_, work_, r_, lambda_, beta_;
  VectorN inv_diag_;  // 1 / L_jj
  VectorN rhs_;       // s = b − Nᵀx₀ of the active set (solve_active_set())
  // H's diagonal blocks: [b, block_end_[b]) for each block's first variable b.
  Eigen::Matrix<int, Vars, 1> block_end_;
  // The lower triangles of H's blocks as last factorised (factorize() reuses L's leading rows
  // where H's leading principal block is unchanged); valid while cholesky_cached_.
  MatrixN H_factored_;
  bool cholesky_cached_ = false;
  Index reflections_ = 0;    // r
  Index w0_ = 0;             // W = diag(I_w0, W̃)
  bool explicit_j_ = false;  // J is kept explicitly (in W_) instead of Q in product form
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
  bool cache_valid_ = false;    // Q, R factorise that set for the current H and A
  Index num_equalities_ = 0;
  Scalar regularization_ = Scalar(0);  // the ε that init() factorised H + εI with
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
  if (l == nullptr) {  // the 5-argument init(): no variable bounds
    p_.l.setConstant(-kInf);
    p_.u.setConstant(kInf);
  }
  p_.H = H;
  p_.A = A;
  store_vectors(g, lb, ub, l, u);
  return init();
}

template <typename Scalar, int Vars, int Rows>
void DenseQp<Scalar, Vars, Rows>::check_problem_sizes(const char* where) const {
  // The messages are only built when a size is wrong (this runs every init() and update()).
  if (p_.H.rows() != n_ || p_.H.cols() != n_) {
    check_argument(false, where, "problem().H n x n",
                   std::to_string(p_.H.rows()) + " x " + std::to_string(p_.H.cols()));
  }
  if (p_.A.rows() != m_ || p_.A.cols() != n_) {
    check_argument(false, where, "problem().A m x n",
                   std::to_string(p_.A.rows()) + " x " + std::to_string(p_.A.cols()));
  }
  check_vector_sizes(where, p_.g, p_.lb, p_.ub, &p_.l, &p_.u);
}

template <typename Scalar, int Vars, int Rows>
QpStatus DenseQp<Scalar, Vars, Rows>::init() {
  check_problem_sizes("DenseQp::init");
  cache_valid_ = false;
  // Until this init() succeeds, no factorisation matches problem(): update() must not reuse one.
  factorized_ = false;
  data_ok_ = false;
  result_.status = QpStatus::unsolved;
  result_.message = "";
  if (!detail::all_finite(p_.H)) return invalid("H has a NaN or Inf entry");
  // Row norms, and from them A's finiteness: a norm that is not finite comes from a NaN or Inf
  // entry, or from entries so large that the square overflows (allowed).
  bool a_finite = true;
  for (Index i = 0; i < m_; ++i) {
    row_norm_[i] = p_.A.row(i).norm();
    if (!std::isfinite(row_norm_[i])) a_finite = a_finite && detail::all_finite(p_.A.row(i));
  }
  if (!a_finite) return invalid("A has a NaN or Inf entry");
  const Scalar h_scale = p_.H.cwiseAbs().maxCoeff();
  // Symmetry, |H_ij − H_ji| within rounding of H's scale: one comparison per pair, and no
  // running maximum (its dependency chain cost more than the rest of init() for walking QPs).
  const Scalar sym_tol = Scalar(1e3) * Eigen::NumTraits<Scalar>::epsilon() * (Scalar(1) + h_scale);
  bool symmetric = true;
  for (Index j = 0; j < n_; ++j) {
    for (Index i = j + 1; i < n_; ++i) {
      symmetric &= std::abs(p_.H(i, j) - p_.H(j, i)) <= sym_tol;
    }
  }
  if (!symmetric) return invalid("H is not symmetric");
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
  store_vectors(g, lb, ub, l, u);
  return update();
}

template <typename Scalar, int Vars, int Rows>
QpStatus DenseQp<Scalar, Vars, Rows>::update() {
  check_problem_sizes("DenseQp::update");
  result_.status = QpStatus::unsolved;
  result_.message = "";
  if (!factorized_) return invalid("update() needs a successful init() first");
  if (const char* why = detail::qp_settings_problem(settings_)) return invalid(why);
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
  if (!detail::all_finite(p_.g)) return "g has a NaN or Inf entry";
  for (Index i = 0; i < m_; ++i) {
    if (std::isnan(p_.lb[i]) || std::isnan(p_.ub[i])) return "lb or ub has a NaN entry";
    if (p_.lb[i] == kInf || p_.ub[i] == -kInf) return "lb = +inf or ub = -inf in some row";
    if (p_.lb[i] > p_.ub[i]) return "lb > ub in some row";
    if (row_norm_[i] == Scalar(0) && (p_.lb[i] > Scalar(0) || p_.ub[i] < Scalar(0))) {
      return "a zero row of A has bounds that exclude 0";
    }
  }
  for (Index j = 0; j < n_; ++j) {
    if (std::isnan(p_.l[j]) || std::isnan(p_.u[j])) return "l or u has a NaN entry";
    if (p_.l[j] == kInf || p_.u[j] == -kInf) return "l = +inf or u = -inf for some variable";
    if (p_.l[j] > p_.u[j]) return "l > u for some variable";
  }
  return nullptr;
}

template <typename Scalar, int Vars, int Rows>
const char* DenseQp<Scalar, Vars, Rows>::factorize() {
  factorized_ = false;
  if (const char* why = detail::qp_settings_problem(settings_)) return why;
  // H + εI is factorised; p_.H stays H (the caller may assemble into it in place).
  const Scalar epsilon = settings_.regularization;
  // Rows of L depend only on H's leading principal block up to them: where a block's leading
  // rows of H (lower triangle) are those factorised last time, with the same ε and the same
  // blocks so far, its leading rows of L are kept. (The walking MPC's jerk blocks never change;
  // only its footstep rows, which come last in each block, do.)
  bool reuse = cholesky_cached_ && epsilon == regularization_;
  cholesky_cached_ = false;
  regularization_ = epsilon;
  // H is factorised block by block where it is block diagonal (contiguous blocks with exactly
  // zero coupling), as walking QPs are (x, y and yaw decouple): O(Σ b³) instead of O(n³), and
  // the solves with L cost O(Σ b²). Left-looking Cholesky H_b = L_b L_bᵀ into L_.
  auto& L = L_;  // only the blocks' lower triangles are written and read
  Scalar max_diag = Scalar(0);
  Scalar min_diag = kInf;
  Index start = 0;
  Index reach = 0;
  for (Index i = 0; i < n_; ++i) {
    Index last = n_ - 1;  // last nonzero of row i = of column i (H is symmetric)
    while (last > reach && p_.H(last, i) == Scalar(0)) --last;
    reach = std::max(reach, last);
    if (reach > i) continue;
    // Block [start, i]; rows [start, keep) of L are kept.
    reuse = reuse && block_end_[start] == static_cast<int>(i + 1);
    Index keep = start;
    if (reuse) {
      keep = i + 1;
      for (Index j = start; j < keep; ++j) {  // the first changed row at or below (j, j)
        for (Index r = j; r < keep; ++r) {
          if (p_.H(r, j) != H_factored_(r, j)) {
            keep = r;
            break;
          }
        }
      }
    }
    block_end_[start] = static_cast<int>(i + 1);
    const char* not_pd =
        "H is not positive definite (hint: set settings.regularization > 0 for PSD H)";
    if (keep == start) {  // the whole block, column by column
      for (Index j = start; j <= i; ++j) {
        const Index k = j - start;
        auto col = tmp_.segment(j, i + 1 - j);
        col.noalias() = p_.H.col(j).segment(j, i + 1 - j) -
                        L.block(j, start, i + 1 - j, k) * L.block(j, start, 1, k).transpose();
        H_factored_.col(j).segment(j, i + 1 - j) = p_.H.col(j).segment(j, i + 1 - j);
        col[0] += epsilon;
        if (!(col[0] > Scalar(0))) return not_pd;
        const Scalar diag = std::sqrt(col[0]);
        L(j, j) = diag;
        inv_diag_[j] = Scalar(1) / diag;
        L.col(j).segment(j + 1, i - j) = col.tail(i - j) / diag;
      }
    } else {  // rows [keep, i] only, each by forward substitution with the rows above it
      for (Index r = keep; r <= i; ++r) {
        const Index k = r - start;
        auto row = tmp_.head(k);  // L(r, start..r−1)ᵀ = L_11⁻¹ H(start..r−1, r)
        row = p_.H.row(r).segment(start, k).transpose();
        H_factored_.row(r).segment(start, k + 1) = p_.H.row(r).segment(start, k + 1);
        detail::lower_solve<kPanel>(&L.coeffRef(start, start), L.outerStride(), &inv_diag_[start],
                                    row.data(), k);
        L.row(r).segment(start, k) = row.transpose();
        const Scalar pivot = p_.H(r, r) + epsilon - row.squaredNorm();
        if (!(pivot > Scalar(0))) return not_pd;
        L(r, r) = std::sqrt(pivot);
        inv_diag_[r] = Scalar(1) / L(r, r);
      }
    }
    for (Index j = start; j <= i; ++j) {
      max_diag = std::max(max_diag, L(j, j));
      min_diag = std::min(min_diag, L(j, j));
    }
    start = i + 1;
    reach = start;
  }
  if (!(min_diag > std::sqrt(Eigen::NumTraits<Scalar>::epsilon()) * Scalar(1e-3) * max_diag)) {
    return "H is numerically singular (hint: set settings.regularization > 0 for PSD H)";
  }
  factorized_ = true;
  cholesky_cached_ = true;
  return nullptr;
}

template <typename Scalar, int Vars, int Rows>
void DenseQp<Scalar, Vars, Rows>::refresh_equalities(bool* pattern_changed) {
  bool changed = false;
  Index count = 0;
  for (Index i = 0; i < m_; ++i) {
    const signed char eq = p_.lb[i] == p_.ub[i] ? 1 : 0;
    changed = changed || eq != row_eq_[i];
    row_eq_[i] = eq;
    count += eq;
  }
  for (Index j = 0; j < n_; ++j) {
    const signed char eq = p_.l[j] == p_.u[j] ? 1 : 0;
    changed = changed || eq != bound_eq_[j];
    bound_eq_[j] = eq;
    count += eq;
  }
  num_equalities_ = count;
  *pattern_changed = changed;
}

// v ← L⁻¹ v (forward substitution; zeros that lead a block's part of v, as in a constraint row
// that reaches few variables of the block, cost nothing), or v ← L⁻ᵀ v when Transposed (back
// substitution; trailing zeros alike), block by block.
template <typename Scalar, int Vars, int Rows>
template <bool Transposed>
void DenseQp<Scalar, Vars, Rows>::solve_with_l(VectorN& v) const {
  for (Index start = 0; start < n_;) {
    const Index end = block_end_[start];
    const Scalar* L = &L_.coeffRef(start, start);
    if (Transposed) {
      detail::upper_solve<kPanel>(L, L_.outerStride(), &inv_diag_[start], &v[start], end - start);
    } else {
      detail::lower_solve<kPanel>(L, L_.outerStride(), &inv_diag_[start], &v[start], end - start);
    }
    start = end;
  }
}

// v ← Gᵀ v (Transposed) or v ← G v for the group G = P_k0 ⋯ P_k0+kBlock−1 = I − V T Vᵀ.
// Fewer than kBlock rows are left only when nearly n constraints are active.
template <typename Scalar, int Vars, int Rows>
template <bool Transposed>
void DenseQp<Scalar, Vars, Rows>::apply_group(Index k0, VectorN& v) const {
  const Index rows = n_ - k0;
  auto y = v.tail(rows);
  const auto T = T_.template block<kBlock, kBlock>(k0, 0);
  if (rows >= kBlock) {
    detail::apply_block_reflector<kBlock, Transposed>(&V_.coeffRef(k0, k0), V_.outerStride(), T,
                                                      y.data(), rows);
  } else {
    const auto V = V_.block(k0, k0, rows, rows);
    Eigen::Matrix<Scalar, Eigen::Dynamic, 1, 0, kBlock, 1> s = V.transpose() * y;
    const auto Tr = T.topLeftCorner(rows, rows);
    if (Transposed) {
      s = Tr.transpose().template triangularView<Eigen::Lower>() * s;
    } else {
      s = Tr.template triangularView<Eigen::Upper>() * s;
    }
    y.noalias() -= V * s;
  }
}

// v ← Qᵀ v = Wᵀ P_{r−1} ⋯ P₀ v.
template <typename Scalar, int Vars, int Rows>
void DenseQp<Scalar, Vars, Rows>::apply_qt(VectorN& v) {
  for (Index k0 = 0; k0 < reflections_; k0 += kBlock) apply_group<true>(k0, v);
  if (w0_ < n_) {
    const Index nw = n_ - w0_;
    work_.head(nw).noalias() = W_.bottomRightCorner(nw, nw).transpose() * v.tail(nw);
    v.tail(nw) = work_.head(nw);
  }
}

// v ← Q v = P₀ ⋯ P_{r−1} W v.
template <typename Scalar, int Vars, int Rows>
void DenseQp<Scalar, Vars, Rows>::apply_q(VectorN& v) {
  if (w0_ < n_) {
    const Index nw = n_ - w0_;
    work_.head(nw).noalias() = W_.bottomRightCorner(nw, nw) * v.tail(nw);
    v.tail(nw) = work_.head(nw);
  }
  if (reflections_ == 0) return;
  for (Index k0 = (reflections_ - 1) / kBlock * kBlock; k0 >= 0; k0 -= kBlock) {
    apply_group<false>(k0, v);
  }
}

// Appends P_r = I − β v vᵀ (v in V_'s column r, rows r..n−1) to the product. Groups of kBlock
// reflections are applied together in the compact WY form P_k0 ⋯ P_k0+kBlock−1 = I − V T Vᵀ
// (Schreiber and Van Loan 1989; T upper triangular, column j: T(j,j) = β_j and
// T(0:j,j) = −β_j T(0:j,0:j) V(:,0:j)ᵀ v_j), so that a vector passes a group in one product
// with Vᵀ and one with V. The group's columns not yet used hold zeros (T's too): a partial group
// is applied as a full one.
template <typename Scalar, int Vars, int Rows>
void DenseQp<Scalar, Vars, Rows>::append_reflection(Scalar beta) {
  const Index r = reflections_;
  const Index k0 = r - r % kBlock;
  const Index j = r - k0;
  auto T = T_.template block<kBlock, kBlock>(k0, 0);
  if (j == 0) {
    T.setZero();
    const Index cols = std::min<Index>(kBlock, n_ - k0);
    V_.block(k0, k0 + 1, n_ - k0, cols - 1).setZero();
  }
  T(j, j) = beta;
  if (j > 0 && n_ - k0 >= kBlock) {
    // z = V(:,0:j)ᵀ v_j from all of the group's columns (those after j are zero).
    Eigen::Matrix<Scalar, kBlock, 1> z = detail::block_dot<kBlock>(
        &V_.coeffRef(k0, k0), V_.outerStride(), &V_.coeffRef(k0, r), n_ - k0);
    z.tail(kBlock - j).setZero();
    detail::upper_times<false>(T, z);
    T.col(j).head(j) = -beta * z.head(j);
  } else if (j > 0) {
    auto t = T.col(j).head(j);
    t.noalias() = V_.block(k0, k0, n_ - k0, j).transpose() * V_.col(r).tail(n_ - k0);
    t = T.topLeftCorner(j, j).template triangularView<Eigen::Upper>() * t;
    t *= -beta;
  }
  beta_[r] = beta;
  ++reflections_;
}

// Explicit form, from scratch: W_ = J = L⁻ᵀ within each block of H (zero outside). Column j
// solves Lᵀ y = e_j by back substitution, J(k,j) = −(Σ_{k<i≤j} L_ik J(i,j)) / L_kk, as a solve
// would (so Jᵀn is as accurate as L⁻¹n by substitution); the rows are taken from the bottom
// up, each for kBlock columns at a time (no dependency between them).
template <typename Scalar, int Vars, int Rows>
void DenseQp<Scalar, Vars, Rows>::form_j0() {
  W_.setZero();
  for (Index start = 0; start < n_;) {
    const Index end = block_end_[start];
    const Index b = end - start;
    auto J = W_.block(start, start, b, b);
    for (Index k = b - 1; k >= 0; --k) {
      const Scalar inv = inv_diag_[start + k];
      J(k, k) = inv;
      const auto l = L_.col(start + k).segment(start + k + 1, b - k - 1);  // L(k+1.., k)
      Index j0 = k + 1;
      for (; j0 + kBlock <= b; j0 += kBlock) {
        const Eigen::Matrix<Scalar, kBlock, 1> t = detail::block_dot<kBlock>(
            &J.coeffRef(k + 1, j0), W_.outerStride(), l.data(), j0 + kBlock - (k + 1));
        J.row(k).segment(j0, kBlock) = -inv * t.transpose();
      }
      for (; j0 < b; ++j0) {
        J(k, j0) = -inv * J.col(j0).segment(k + 1, j0 - k).dot(l.head(j0 - k));
      }
    }
    start = end;
  }
}

// Makes W̃ cover the columns (and rows) from k on: the new ones are those of the identity.
template <typename Scalar, int Vars, int Rows>
void DenseQp<Scalar, Vars, Rows>::extend_w(Index k) {
  if (k >= w0_) return;
  const Index added = w0_ - k;
  const Index kept = n_ - w0_;
  W_.block(k, k, added, added).setIdentity();
  W_.block(k, w0_, added, kept).setZero();
  W_.block(w0_, k, kept, added).setZero();
  w0_ = k;
}

// Appends the constraint whose d = Jᵀn is in d_ to the factorisation: one Householder reflection
// P maps d₂ = d_[q..n) onto σ e₁ and R gets column (d₁, σ). Q ← Q P: right after a refactorisation
// (W = I, q = r) P joins the product as P_q; otherwise it is applied to W's trailing columns.
template <typename Scalar, int Vars, int Rows>
void DenseQp<Scalar, Vars, Rows>::add_to_factorization(Index q) {
  const Index nq = n_ - q;
  WALKGEN_ASSERT(nq >= 1);
  WALKGEN_ASSERT(w0_ < n_ || q == reflections_);
  const bool append = w0_ == n_;
  R_.col(q).head(q) = d_.head(q);
  if (nq == 1) {
    R_(q, q) = d_[q];
    if (append) {
      V_(q, q) = Scalar(0);  // P = I
      append_reflection(Scalar(0));
    }
  } else {
    auto d2 = d_.tail(nq);
    const Scalar alpha = d2.norm();
    const Scalar x0 = d2[0];
    const Scalar sign = x0 >= Scalar(0) ? Scalar(1) : Scalar(-1);
    const Scalar beta = Scalar(1) / (alpha * (alpha + std::abs(x0)));  // 2 / vᵀv
    if (append) {
      auto v = V_.col(q).tail(nq);
      v = d2;
      v[0] += sign * alpha;
      append_reflection(beta);
    } else {
      auto v = hh_.head(nq);
      v = d2;
      v[0] += sign * alpha;
      extend_w(q);
      auto W2 = W_.block(w0_, q, n_ - w0_, nq);
      auto w = tmp_.head(n_ - w0_);
      w.noalias() = W2 * v;
      w *= beta;
      W2.noalias() -= w * v.transpose();
    }
    R_(q, q) = -sign * alpha;
  }
  R_.col(q).tail(n_ - q - 1).setZero();
}

// Removes active constraint k: R loses column k and is made triangular again by Givens
// rotations on rows (j, j+1), applied alike to Q's columns (j, j+1), i.e. to W's.
template <typename Scalar, int Vars, int Rows>
void DenseQp<Scalar, Vars, Rows>::drop_from_factorization(Index k) {
  for (Index j = k; j + 1 < q_; ++j) R_.col(j).head(j + 2) = R_.col(j + 1).head(j + 2);
  extend_w(k);  // also when no rotation follows: later additions go to W, not after P_{r−1}
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
    for (Index i = w0_; i < n_; ++i) {
      const Scalar w1 = W_(i, j);
      const Scalar w2 = W_(i, j + 1);
      W_(i, j) = c * w1 + s * w2;
      W_(i, j + 1) = -s * w1 + c * w2;
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
  for (Index k = 0; k < q_; ++k) {
    rhs_[k] = bound_of(active_[k], active_sign_[k]) - normal_dot(active_[k], active_sign_[k], x0_);
  }
  solve_multipliers();
  update_x();
}

// λ = R⁻¹R⁻ᵀ s for s in rhs_; leaves R⁻ᵀ s in r_.
template <typename Scalar, int Vars, int Rows>
void DenseQp<Scalar, Vars, Rows>::solve_multipliers() {
  if (q_ == 0) return;
  auto w = r_.head(q_);
  w = rhs_.head(q_);
  const auto Rq = R_.topLeftCorner(q_, q_);
  Rq.transpose().template triangularView<Eigen::Lower>().solveInPlace(w);
  auto lambda = lambda_.head(q_);
  lambda = w;
  Rq.template triangularView<Eigen::Upper>().solveInPlace(lambda);
}

// x = x₀ + J₁ R⁻ᵀ s with R⁻ᵀ s in r_ (solve_multipliers()).
template <typename Scalar, int Vars, int Rows>
void DenseQp<Scalar, Vars, Rows>::update_x() {
  result_.x = x0_;
  if (q_ == 0) return;
  tmp_.head(q_) = r_.head(q_);
  tmp_.tail(n_ - q_).setZero();
  apply_j(tmp_, 0, q_);  // J₁ R⁻ᵀ s
  result_.x += tmp_;
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
  if (m_ > 0 && !ax_current) Ax_.noalias() = p_.A * x;
  for (Index i = 0; i < m_; ++i) {
    const Scalar viol = std::max(p_.lb[i] - Ax_[i], Ax_[i] - p_.ub[i]);
    if (!(viol > Scalar(0))) continue;
    max_abs_viol = std::max(max_abs_viol, viol);
    if (row_norm_[i] == Scalar(0)) continue;  // a zero row constrains nothing it can reach
    const Scalar bound = p_.lb[i] - Ax_[i] > Ax_[i] - p_.ub[i] ? p_.lb[i] : p_.ub[i];
    ok = ok && viol / row_norm_[i] <= loose * (xscale + std::abs(bound) / row_norm_[i]);
  }
  for (Index j = 0; j < n_; ++j) {
    const Scalar viol = std::max(p_.l[j] - x[j], x[j] - p_.u[j]);
    if (!(viol > Scalar(0))) continue;
    max_abs_viol = std::max(max_abs_viol, viol);
    const Scalar bound = p_.l[j] - x[j] > x[j] - p_.u[j] ? p_.l[j] : p_.u[j];
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
  tmp_.head(q_) = w;
  tmp_.tail(n_ - q_).setZero();
  apply_j(tmp_, 0, q_);
  result_.x += tmp_;
  Rq.template triangularView<Eigen::Upper>().solveInPlace(w);
  lambda_.head(q_) += w;
}

// Drops the most negative inequality multiplier until none is negative (warm start only), right
// after solve_active_set(), as often as needed; x follows the final active set.
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
    if (worst < 0) break;
    drop_from_factorization(worst);
    // s = b − Nᵀx₀ loses the entry of the dropped constraint; x only matters at the end.
    for (Index k = worst; k < q_; ++k) rhs_[k] = rhs_[k + 1];
    solve_multipliers();
    dropped = true;
  }
  if (dropped) update_x();
  return dropped;
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
  if (m_ > 0) Ax_.noalias() = p_.A * x;
  for (Index i = 0; i < m_; ++i) {
    const Scalar v = Ax_[i];
    const Scalar below = p_.lb[i] - v;
    const Scalar above = v - p_.ub[i];
    const Scalar viol = std::max(below, above);
    if (viol <= Scalar(0)) continue;
    max_abs_viol = std::max(max_abs_viol, viol);
    if (row_state_[i] != 0 || row_norm_[i] == Scalar(0)) continue;
    const Scalar bound = below > above ? p_.lb[i] : p_.ub[i];
    const Scalar scaled = viol / row_norm_[i];
    if (scaled > tol * (xscale + std::abs(bound) / row_norm_[i]) && scaled > best_viol) {
      best_viol = scaled;
      best = static_cast<int>(i);
      *sign = below > above ? 1 : -1;
    }
  }
  for (Index j = 0; j < n_; ++j) {
    const Scalar below = p_.l[j] - x[j];
    const Scalar above = x[j] - p_.u[j];
    const Scalar viol = std::max(below, above);
    if (viol <= Scalar(0)) continue;
    max_abs_viol = std::max(max_abs_viol, viol);
    if (bound_state_[j] != 0) continue;
    const Scalar bound = below > above ? p_.l[j] : p_.u[j];
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
  step_.noalias() = p_.H.template selfadjointView<Eigen::Lower>() * x;  // (H + εI)x
  step_ += regularization_ * x;
  result_.objective = Scalar(0.5) * x.dot(step_) + p_.g.dot(x);
  step_ += p_.g;
  step_ += result_.z;
  Scalar compl_max = Scalar(0);
  for (Index k = 0; k < q_; ++k) {
    const int c = active_[k];
    const Scalar slack = normal_dot(c, active_sign_[k], x) - bound_of(c, active_sign_[k]);
    if (is_row(c)) {
      step_.noalias() += p_.A.row(c).transpose() * result_.y[c];
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

// Factorises from scratch the equalities and then the first `count` constraints listed in
// previous_active_/previous_sign_ (skipping any that became dependent or unbounded).
// In product form, starting from Q = I, this is a left-looking Householder QR of L⁻¹N: each
// constraint's d = Qᵀ L⁻¹ n passes the reflections so far and its own reflection joins the
// product (add_to_factorization()), so no n × n matrix is updated. The dependency test is the
// same as for constraints added one by one (dependent()), in the same order.
// Returns whether any listed constraint was taken.
template <typename Scalar, int Vars, int Rows>
bool DenseQp<Scalar, Vars, Rows>::rebuild_factorization(Index count) {
  // Few constraints to take (a cold start, a small problem): J explicitly, as the active-set
  // changes that follow cost less with it than with the product form, which pays off when many
  // are taken here. W_ = J and w0_ = 0 make add/drop_from_factorization() update J itself.
  explicit_j_ = n_ < kProductMinVars || 4 * (num_equalities_ + count) < n_;
  reflections_ = 0;  // Q = I
  if (explicit_j_) {
    form_j0();
    w0_ = 0;
  } else {
    w0_ = n_;
  }
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
  // x0 = −H⁻¹g = −L⁻ᵀ L⁻¹ g
  tmp_ = p_.g;
  solve_with_l<false>(tmp_);
  solve_with_l<true>(tmp_);
  x0_ = -tmp_;
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
    // Q, R, active_ are those of the previous solve; refresh the state flags.
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
        step_.head(q_).setZero();
        step_.tail(n_ - q_) = d_.tail(n_ - q_);
        apply_j(step_, q_, n_ - q_);  // J₂ d₂
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
