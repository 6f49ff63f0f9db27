/// @file
/// walkgen.DenseQp: the built-in dense QP (walkgen/qp/dense_qp.hpp) on NumPy arrays.
///
///   minimise ½xᵀHx + gᵀx  subject to  lb ≤ Ax ≤ ub,  l ≤ x ≤ u
///
/// solve(H, g, A, lb, ub, l, u) sets the whole problem and solves it; update(g=..., lb=...)
/// changes vectors only (the factorisation of H and the warm start's are kept) and solve()
/// without arguments solves what is set. Data the C++ solver calls invalid (NaN, lb > ub, H not
/// positive definite) raise ValueError with its message; an infeasible problem is a status.

#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <limits>
#include <optional>
#include <sstream>
#include <string>

#include "arrays.hpp"
#include "bindings.hpp"
#include "walkgen/qp/dense_qp.hpp"

namespace walkgen::python {
namespace {

using Qp = DenseQp<double>;
constexpr double kInf = std::numeric_limits<double>::infinity();

/// A solve's outcome, copied out of the solver (it stays valid after the next solve).
struct PyQpResult {
  QpStatus status = QpStatus::unsolved;
  py::array_t<double> x, y, z;
  int iterations = 0, active_set_size = 0;
  bool warm_started = false, reused_factorization = false;
  double objective = 0, primal_residual = 0, dual_residual = 0, complementarity = 0;
  std::string message;
};

PyQpResult copy_result(const Qp::Result& r) {
  PyQpResult out;
  out.status = r.status;
  out.x = to_numpy(r.x);
  out.y = to_numpy(r.y);
  out.z = to_numpy(r.z);
  out.iterations = r.iterations;
  out.active_set_size = r.active_set_size;
  out.warm_started = r.warm_started;
  out.reused_factorization = r.reused_factorization;
  out.objective = r.objective;
  out.primal_residual = r.primal_residual;
  out.dual_residual = r.dual_residual;
  out.complementarity = r.complementarity;
  out.message = r.message;
  return out;
}

/// Raises ValueError when init()/update() found the data unusable.
void raise_if_invalid(const Qp& qp, QpStatus status, const char* where) {
  if (status == QpStatus::invalid_input) {
    throw invalid_argument(std::string(where) + ": " + qp.result().message);
  }
}

/// Writes `object` (or `fill` where it is None) into the vector `target`.
void assign_vector(Eigen::VectorXd& target, const py::object& object, const char* where,
                   double fill) {
  if (object.is_none()) {
    target.setConstant(fill);
  } else {
    target = VectorArg(object, where, target.size()).map();
  }
}

PyQpResult solve_now(Qp& qp) {
  {
    py::gil_scoped_release release;
    (void)qp.solve();
  }
  return copy_result(qp.result());
}

PyQpResult solve_problem(Qp& qp, const py::object& H, const py::object& g, const py::object& A,
                         const py::object& lb, const py::object& ub, const py::object& l,
                         const py::object& u) {
  const Eigen::Index n = qp.num_vars(), m = qp.num_rows();
  if (H.is_none() && g.is_none()) {
    if (!A.is_none() || !lb.is_none() || !ub.is_none() || !l.is_none() || !u.is_none()) {
      throw invalid_argument(
          "DenseQp.solve: expected H and g with the other data, got them without (hint: "
          "update() changes vectors only)");
    }
    return solve_now(qp);
  }
  if (H.is_none() || g.is_none()) {
    throw invalid_argument("DenseQp.solve: expected both H and g, got only one of them");
  }
  if (A.is_none() && m > 0) {
    throw invalid_argument(detail::expected_got(
        "DenseQp.solve: A",
        "a matrix of shape (" + std::to_string(m) + ", " + std::to_string(n) + ")", "None",
        "this solver was built with m rows"));
  }
  Qp::Problem& p = qp.problem();
  p.H = MatrixArg(H, "DenseQp.solve: H", n, n).map(n, n);
  p.A = A.is_none() ? RowMatrix::Zero(m, n)
                    : RowMatrix(MatrixArg(A, "DenseQp.solve: A", m, n).map(m, n));
  assign_vector(p.g, g, "DenseQp.solve: g", 0.0);
  assign_vector(p.lb, lb, "DenseQp.solve: lb", -kInf);
  assign_vector(p.ub, ub, "DenseQp.solve: ub", kInf);
  assign_vector(p.l, l, "DenseQp.solve: l", -kInf);
  assign_vector(p.u, u, "DenseQp.solve: u", kInf);
  raise_if_invalid(qp, qp.init(), "DenseQp.solve");
  return solve_now(qp);
}

void update_problem(Qp& qp, const py::object& g, const py::object& lb, const py::object& ub,
                    const py::object& l, const py::object& u) {
  Qp::Problem& p = qp.problem();
  const auto keep_or_set = [](Eigen::VectorXd& target, const py::object& object,
                              const char* where) {
    if (!object.is_none()) target = VectorArg(object, where, target.size()).map();
  };
  keep_or_set(p.g, g, "DenseQp.update: g");
  keep_or_set(p.lb, lb, "DenseQp.update: lb");
  keep_or_set(p.ub, ub, "DenseQp.update: ub");
  keep_or_set(p.l, l, "DenseQp.update: l");
  keep_or_set(p.u, u, "DenseQp.update: u");
  raise_if_invalid(qp, qp.update(), "DenseQp.update");
}

std::string result_repr(const PyQpResult& r) {
  std::ostringstream os;
  os << "QpResult(status='" << to_string(r.status) << "', iterations=" << r.iterations
     << ", objective=" << r.objective << ", primal_residual=" << r.primal_residual
     << ", dual_residual=" << r.dual_residual << ")";
  return os.str();
}

}  // namespace

void bind_qp(py::module_& m) {
  py::enum_<QpStatus> status(m, "QpStatus", "Outcome of a QP solve (str() gives its name).");
  status.value("unsolved", QpStatus::unsolved)
      .value("solved", QpStatus::solved)
      .value("infeasible", QpStatus::infeasible)
      .value("max_iterations", QpStatus::max_iterations)
      .value("invalid_input", QpStatus::invalid_input)
      .value("inaccurate", QpStatus::inaccurate);
  enum_as_string(status);

  py::class_<QpSettings<double>>(m, "QpSettings", "DenseQp's settings (see dense_qp.hpp).")
      .def(py::init<>())
      .def_readwrite("max_iterations", &QpSettings<double>::max_iterations)
      .def_readwrite("warm_start", &QpSettings<double>::warm_start)
      .def_readwrite("regularization", &QpSettings<double>::regularization)
      .def_readwrite("primal_tolerance", &QpSettings<double>::primal_tolerance)
      .def_readwrite("dependency_tolerance", &QpSettings<double>::dependency_tolerance)
      .def_readwrite("compute_residuals", &QpSettings<double>::compute_residuals);

  py::class_<PyQpResult>(m, "QpResult",
                         "A QP solve's outcome. Multipliers follow H x + g + Aᵀy + z = 0.")
      .def_readonly("status", &PyQpResult::status)
      .def_readonly("x", &PyQpResult::x, "primal solution (n,)")
      .def_readonly("y", &PyQpResult::y, "multipliers of the rows of A (m,)")
      .def_readonly("z", &PyQpResult::z, "multipliers of the variable bounds (n,)")
      .def_readonly("iterations", &PyQpResult::iterations, "active-set changes in this solve")
      .def_readonly("active_set_size", &PyQpResult::active_set_size)
      .def_readonly("warm_started", &PyQpResult::warm_started)
      .def_readonly("reused_factorization", &PyQpResult::reused_factorization)
      .def_readonly("objective", &PyQpResult::objective)
      .def_readonly("primal_residual", &PyQpResult::primal_residual)
      .def_readonly("dual_residual", &PyQpResult::dual_residual)
      .def_readonly("complementarity", &PyQpResult::complementarity)
      .def_readonly("message", &PyQpResult::message)
      .def_property_readonly("ok", [](const PyQpResult& r) { return r.status == QpStatus::solved; })
      .def("__repr__", &result_repr);

  py::class_<Qp>(m, "DenseQp",
                 "Dense strictly convex QP with n variables and m rows (Goldfarb-Idnani).")
      .def(py::init([](long long n, long long rows, const QpSettings<double>& settings) {
             return Qp(static_cast<Eigen::Index>(n), static_cast<Eigen::Index>(rows), settings);
           }),
           py::arg("n"), py::arg("m") = 0, py::arg("settings") = QpSettings<double>())
      .def_property_readonly("num_vars", &Qp::num_vars)
      .def_property_readonly("num_rows", &Qp::num_rows)
      .def_property(
          "settings", [](const Qp& qp) { return qp.settings(); },
          [](Qp& qp, const QpSettings<double>& s) {
            validate(s);
            qp.settings() = s;
          })
      .def("solve", &solve_problem, py::arg("H") = py::none(), py::arg("g") = py::none(),
           py::arg("A") = py::none(), py::arg("lb") = py::none(), py::arg("ub") = py::none(),
           py::arg("l") = py::none(), py::arg("u") = py::none(),
           "solve(H, g, A=None, lb=None, ub=None, l=None, u=None) -> QpResult: sets the whole "
           "problem (None bounds are infinite) and solves it from the previous active set. "
           "solve() without arguments solves the problem as update() left it.")
      .def("update", &update_problem, py::arg("g") = py::none(), py::arg("lb") = py::none(),
           py::arg("ub") = py::none(), py::arg("l") = py::none(), py::arg("u") = py::none(),
           "update(g=None, lb=None, ub=None, l=None, u=None): replaces the vectors given (H and "
           "A stay, with their factorisation); solve() then solves the new problem.")
      .def("reset_warm_start", &Qp::reset_warm_start,
           "The next solve starts from an empty active set.")
      .def_property_readonly("result", [](const Qp& qp) { return copy_result(qp.result()); });
}

}  // namespace walkgen::python
