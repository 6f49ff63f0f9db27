// Packaging check: a program built against walkgen must compile, link and solve correctly.
// minimise 1/2 |x - (1, 2)|^2  subject to  x0 + x1 <= 1;  the solution is x = (0, 1).
#include <cmath>
#include <cstdio>
#include <limits>

#include <Eigen/Dense>
#include <walkgen/walkgen.hpp>

int main() {
  const Eigen::MatrixXd H = Eigen::MatrixXd::Identity(2, 2);
  const Eigen::VectorXd g = -Eigen::Vector2d(1.0, 2.0);
  const Eigen::MatrixXd A = Eigen::MatrixXd::Ones(1, 2);
  const Eigen::VectorXd lb = Eigen::VectorXd::Constant(1, -std::numeric_limits<double>::infinity());
  const Eigen::VectorXd ub = Eigen::VectorXd::Constant(1, 1.0);

  walkgen::DenseQp<double> qp(2, 1);
  qp.init(H, g, A, lb, ub);
  const auto& r = qp.solve();

  const bool solved = r.status == walkgen::QpStatus::solved;
  const bool correct =
      r.x.size() == 2 && std::abs(r.x(0) - 0.0) <= 1e-9 && std::abs(r.x(1) - 1.0) <= 1e-9;
  std::printf("walkgen %s: status %s, x = (%.17g, %.17g)\n", walkgen::kVersion,
              solved ? "solved" : "NOT solved", r.x.size() > 0 ? r.x(0) : NAN,
              r.x.size() > 1 ? r.x(1) : NAN);
  if (!solved || !correct) {
    std::fprintf(stderr, "wrong answer: expected status solved and x = (0, 1) within 1e-9\n");
    return 1;
  }
  return 0;
}
