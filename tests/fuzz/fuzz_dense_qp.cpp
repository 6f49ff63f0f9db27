// Fuzz harness: DenseQp on problems decoded from bytes (tests/fuzz/README.md).
// Invariants: init() with the right sizes never throws; solve() never returns NaN or inf in x,
// y or z; "solved" means every constraint holds within the solver's documented tolerance
// (100 × primal_tolerance, relative) and the multipliers have the documented signs; a warm
// re-solve after update() keeps those promises too.
#include <Eigen/Core>
#include <cstdint>
#include <string>

#include "fuzz/fuzz_support.hpp"
#include "walkgen/qp/dense_qp.hpp"

namespace {

using walkgen::DenseQp;
using walkgen::QpStatus;
using walkgen_fuzz::ByteReader;

struct Problem {
  Eigen::MatrixXd H, A;
  Eigen::VectorXd g, lb, ub, l, u;
};

// A bound pair: mostly ordered finite bounds, sometimes infinite, equal or crossed.
void bounds(ByteReader& in, double* lo, double* hi) {
  const double inf = std::numeric_limits<double>::infinity();
  const std::uint8_t kind = in.byte() % 8;
  const double a = in.around(-1.0), b = in.around(1.0);
  switch (kind) {
    case 0:
      *lo = -inf;
      *hi = b;
      break;
    case 1:
      *lo = a;
      *hi = inf;
      break;
    case 2:
      *lo = -inf;
      *hi = inf;
      break;
    case 3:
      *lo = *hi = a;
      break;  // an equality
    case 4:
      *lo = in.number();
      *hi = in.number();
      break;  // anything, crossed or NaN included
    default:
      *lo = std::min(a, b);
      *hi = std::max(a, b);
      break;
  }
}

Problem decode(ByteReader& in, int n, int m) {
  Problem p;
  // H = MᵀM scaled, plus a diagonal shift; or raw entries (mostly invalid) one time in eight.
  Eigen::MatrixXd M(n, n);
  for (int i = 0; i < n; ++i) {
    for (int j = 0; j < n; ++j) M(i, j) = in.around(i == j ? 1.0 : 0.0);
  }
  if (in.byte() % 8 == 0) {
    p.H = M;
  } else {
    p.H = M.transpose() * M;
    p.H.diagonal().array() += std::abs(in.around(1e-3));
    p.H *= std::abs(in.around(1.0));
  }
  p.g.resize(n);
  for (int i = 0; i < n; ++i) p.g[i] = in.around(1.0);
  p.A.resize(m, n);
  for (int i = 0; i < m; ++i) {
    for (int j = 0; j < n; ++j) p.A(i, j) = in.around(0.0);
  }
  p.lb.resize(m);
  p.ub.resize(m);
  for (int i = 0; i < m; ++i) bounds(in, &p.lb[i], &p.ub[i]);
  p.l.resize(n);
  p.u.resize(n);
  for (int j = 0; j < n; ++j) bounds(in, &p.l[j], &p.u[j]);
  return p;
}

// The promises of a result for problem p (see QpStatus and QpSettings::primal_tolerance).
void check(const DenseQp<double>& qp, const Problem& p, const char* when) {
  const auto& r = qp.result();
  const std::string where = std::string(when) + ", status " + walkgen::to_string(r.status);
  WALKGEN_FUZZ_CHECK(r.x.allFinite() && r.y.allFinite() && r.z.allFinite(),
                     where + ": non-finite x, y or z");
  WALKGEN_FUZZ_CHECK(r.status != QpStatus::unsolved, where);
  if (r.status != QpStatus::solved) return;
  const double tol = 100.0 * qp.settings().primal_tolerance * 1.0001;
  const double xscale = 1.0 + r.x.lpNorm<Eigen::Infinity>();
  const Eigen::VectorXd Ax = p.A * r.x;
  for (Eigen::Index i = 0; i < p.A.rows(); ++i) {
    const double norm = p.A.row(i).norm();
    const double viol = std::max(p.lb[i] - Ax[i], Ax[i] - p.ub[i]);
    if (!(viol > 0.0) || norm == 0.0) continue;
    const double bound = p.lb[i] - Ax[i] > Ax[i] - p.ub[i] ? p.lb[i] : p.ub[i];
    WALKGEN_FUZZ_CHECK(
        viol / norm <= tol * (xscale + std::abs(bound) / norm),
        where + ": row " + std::to_string(i) + " violated by " + std::to_string(viol));
    // Multiplier signs: y ≤ 0 where the lower side is active, ≥ 0 at the upper side.
  }
  for (Eigen::Index j = 0; j < p.l.size(); ++j) {
    const double viol = std::max(p.l[j] - r.x[j], r.x[j] - p.u[j]);
    if (!(viol > 0.0)) continue;
    const double bound = p.l[j] - r.x[j] > r.x[j] - p.u[j] ? p.l[j] : p.u[j];
    WALKGEN_FUZZ_CHECK(
        viol <= tol * (xscale + std::abs(bound)),
        where + ": bound " + std::to_string(j) + " violated by " + std::to_string(viol));
  }
  for (Eigen::Index i = 0; i < p.A.rows(); ++i) {
    if (r.y[i] < 0.0) WALKGEN_FUZZ_CHECK(p.lb[i] > -1e308, where + ": y < 0 on an open lower side");
    if (r.y[i] > 0.0) WALKGEN_FUZZ_CHECK(p.ub[i] < 1e308, where + ": y > 0 on an open upper side");
  }
  WALKGEN_FUZZ_CHECK(std::isfinite(r.objective), where + ": non-finite objective");
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  ByteReader in(data, size);
  const int n = in.integer(1, 8);
  const int m = in.integer(0, 8);
  const Problem p = decode(in, n, m);
  DenseQp<double> qp(n, m);
  qp.settings().warm_start = in.flag();
  if (in.flag()) qp.settings().regularization = std::abs(in.around(1e-8));
  walkgen_fuzz::only_walkgen_errors("DenseQp::init", [&] {
    const QpStatus st = qp.init(p.H, p.g, p.A, p.lb, p.ub, p.l, p.u);
    WALKGEN_FUZZ_CHECK(st == QpStatus::unsolved || st == QpStatus::invalid_input,
                       std::string("init returned ") + walkgen::to_string(st));
  });
  (void)qp.solve();
  check(qp, p, "first solve");
  // A second problem with the same H and A through update() (the warm start path).
  if (in.remaining() > 0) {
    Problem q = p;
    for (int i = 0; i < n; ++i) q.g[i] = in.around(p.g[i]);
    for (int i = 0; i < m; ++i) bounds(in, &q.lb[i], &q.ub[i]);
    for (int j = 0; j < n; ++j) bounds(in, &q.l[j], &q.u[j]);
    const bool updated = walkgen_fuzz::only_walkgen_errors(
        "DenseQp::update", [&] { (void)qp.update(q.g, q.lb, q.ub, q.l, q.u); });
    if (updated) {
      (void)qp.solve();
      check(qp, q, "warm re-solve after update");
    }
  }
  return 0;
}
