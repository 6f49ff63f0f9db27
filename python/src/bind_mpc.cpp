/// @file
/// walkgen.WalkingMpc: the NMPC walking pattern generator (walkgen/mpc/walking_mpc.hpp) with
/// any horizon (WalkingMpc<double, Eigen::Dynamic>: the QP is sized at run time in every case,
/// so a fixed N would not be faster), its state and its plan as NumPy arrays.

#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <cmath>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include "arrays.hpp"
#include "bindings.hpp"
#include "walkgen/interpolation/trajectory.hpp"
#include "walkgen/mpc/walking_mpc.hpp"

namespace walkgen::python {
namespace {

using Mpc = WalkingMpc<double, Eigen::Dynamic>;
using State = WalkingState<double>;
using Pose = FootPose<double>;

/// A tick's outcome, copied out of the generator.
struct PyMpcResult {
  MpcStatus status = MpcStatus::solved;
  QpStatus qp_status = QpStatus::unsolved;
  std::string message;
  int sqp_iterations = 0, qp_iterations = 0;
  double primal_residual = 0, constraint_violation = 0;
  std::uint32_t relaxed_blocks = 0;
  bool soft_fallback = false;
  CommandStatus last_command = CommandStatus::accepted;
  py::array_t<double> command;
};

/// The current tick's plan sampled at the command period (walkgen/interpolation/trajectory.hpp):
/// (t / command_period, 21) in the thesis's CSV column order (trajectory_columns), and per
/// sample the time, the support foot (0 left, 1 right) and whether both feet are down.
py::dict interpolate(const Mpc& mpc, std::optional<double> command_period) {
  InterpolationSettings<double> is = interpolation_settings(mpc.settings());
  if (command_period) is.command_period = *command_period;
  const WalkingInterpolator<double> interpolator(is);
  std::vector<TrajectorySample<double>> samples(
      static_cast<std::size_t>(interpolator.samples_per_tick()));
  interpolator.interpolate(mpc.tick_plan(), samples.data());
  const auto k = static_cast<Eigen::Index>(samples.size());
  Eigen::MatrixXd table(k, 21);
  Eigen::VectorXd time(k), support(k), double_support(k);
  for (Eigen::Index i = 0; i < k; ++i) {
    const auto& t = samples[static_cast<std::size_t>(i)];
    table.row(i) << t.com_x.transpose(), t.com_y.transpose(), t.com_z, t.com_q.transpose(), t.zmp_x,
        t.zmp_y, t.zmp_z, t.left.motion.x.position, t.left.motion.y.position, t.left.z.position,
        t.left.motion.q.position, t.right.motion.x.position, t.right.motion.y.position,
        t.right.z.position, t.right.motion.q.position;
    time[i] = t.time;
    support[i] = t.support_foot == Foot::left ? 0.0 : 1.0;
    double_support[i] = t.double_support ? 1.0 : 0.0;
  }
  py::dict out;
  out["samples"] = to_numpy(table);
  out["time"] = to_numpy(time);
  out["support_foot"] = to_numpy(support).attr("astype")("int8");
  out["double_support"] = to_numpy(double_support).attr("astype")("bool");
  return out;
}

PyMpcResult copy_result(const Mpc::Result& r) {
  PyMpcResult out;
  out.status = r.status;
  out.qp_status = r.qp_status;
  out.message = r.message;
  out.sqp_iterations = r.sqp_iterations;
  out.qp_iterations = r.qp_iterations;
  out.primal_residual = r.primal_residual;
  out.constraint_violation = r.constraint_violation;
  out.relaxed_blocks = r.relaxed_blocks;
  out.soft_fallback = r.soft_fallback;
  out.last_command = r.last_command;
  out.command = to_numpy(r.command);
  return out;
}

Mpc make_mpc(WalkingSettings<double> settings, std::optional<long long> horizon,
             long long obstacle_capacity) {
  if (horizon) {
    check_argument(*horizon >= 1 && *horizon <= settings_limits::kMaxHorizon, "WalkingMpc: horizon",
                   "1 to " + std::to_string(settings_limits::kMaxHorizon) + " samples", *horizon);
    settings.n = static_cast<int>(*horizon);
  }
  check_argument(obstacle_capacity >= 0 && obstacle_capacity <= 1000,
                 "WalkingMpc: obstacle_capacity", "0 to 1000", obstacle_capacity);
  return Mpc(settings, static_cast<Eigen::Index>(obstacle_capacity));
}

/// The plan's CoM (positions, velocities, accelerations) or ZMP at the horizon's samples:
/// (N, 2) with columns x, y.
py::array_t<double> preview_xy(const Mpc& mpc, int which) {
  const auto& p = mpc.preview();
  const Eigen::Index N = mpc.horizon();
  const auto& U = mpc.plan().U;
  const Eigen::VectorXd jx = U.head(N);
  const Eigen::VectorXd jy = U.segment(N + mpc.planned_steps(), N);
  const State& st = mpc.state();
  Eigen::MatrixXd out(N, 2);
  const auto fill = [&](const auto& Ps, const auto& Pu) {
    out.col(0) = Ps * st.com_x + Pu * jx;
    out.col(1) = Ps * st.com_y + Pu * jy;
  };
  if (which == 0) fill(p.P_ps, p.P_pu);
  if (which == 1) fill(p.P_vs, p.P_vu);
  if (which == 2) fill(p.P_as, p.P_au);
  if (which == 3) fill(p.P_zs, p.P_zu);
  return to_numpy(out);
}

py::array_t<double> footsteps(const Mpc& mpc) {
  Eigen::MatrixXd out(mpc.planned_steps(), 3);
  for (int i = 1; i <= mpc.planned_steps(); ++i) {
    const Pose f = mpc.plan().footstep(i);
    out.row(i - 1) << f.x, f.y, f.q;
  }
  return to_numpy(out);
}

CommandStatus set_command(Mpc& mpc, double vx, double vy, double wz) {
  const CommandStatus status = mpc.set_command(Eigen::Vector3d(vx, vy, wz));
  if (status == CommandStatus::non_finite) {
    std::ostringstream got;
    got << "(" << vx << ", " << vy << ", " << wz << ")";
    throw invalid_argument(detail::expected_got("WalkingMpc.set_command", "finite (vx, vy, wz)",
                                                got.str(), "the previous command stays"));
  }
  return status;
}

std::vector<CircleObstacle<double>> as_obstacles(const py::iterable& items) {
  std::vector<CircleObstacle<double>> out;
  for (const py::handle item : items) {
    if (py::isinstance<CircleObstacle<double>>(item)) {
      out.push_back(item.cast<CircleObstacle<double>>());
      continue;
    }
    const auto v = as_float_array(item, "WalkingMpc.set_obstacles: an obstacle");
    check_argument(v.ndim() == 1 && (v.size() == 3 || v.size() == 4),
                   "WalkingMpc.set_obstacles: an obstacle",
                   "a CircleObstacle or (x, y, radius[, margin])", "shape " + shape_string(v));
    out.push_back({v.at(0), v.at(1), v.at(2), v.size() == 4 ? v.at(3) : 0.0});
  }
  return out;
}

std::string pose_repr(const Pose& p) {
  std::ostringstream os;
  os << "FootPose(x=" << p.x << ", y=" << p.y << ", q=" << p.q << ")";
  return os.str();
}

std::string result_repr(const PyMpcResult& r) {
  std::ostringstream os;
  os << "MpcResult(status='" << to_string(r.status) << "', qp_status='" << to_string(r.qp_status)
     << "', sqp_iterations=" << r.sqp_iterations << ", qp_iterations=" << r.qp_iterations
     << ", constraint_violation=" << r.constraint_violation << ")";
  return os.str();
}

}  // namespace

void bind_mpc(py::module_& m) {
  {
    py::list columns;
    std::string header = trajectory_csv_header();
    for (std::size_t start = 0;;) {
      const std::size_t comma = header.find(',', start);
      columns.append(header.substr(start, comma - start));
      if (comma == std::string::npos) break;
      start = comma + 1;
    }
    m.attr("trajectory_columns") = py::tuple(columns);
  }
  py::enum_<MpcStatus> status(m, "MpcStatus", "Outcome of a generator tick.");
  status.value("solved", MpcStatus::solved)
      .value("qp_failed", MpcStatus::qp_failed)
      .value("not_converged", MpcStatus::not_converged)
      .value("relaxed", MpcStatus::relaxed);
  enum_as_string(status);
  py::enum_<CommandStatus> command(m, "CommandStatus", "What set_command() did with a command.");
  command.value("accepted", CommandStatus::accepted)
      .value("non_finite", CommandStatus::non_finite)
      .value("clamped", CommandStatus::clamped);
  enum_as_string(command);

  py::class_<Pose>(m, "FootPose", "A foot's planar pose: x, y [m], yaw q [rad], world frame.")
      .def(py::init([](double x, double y, double q) {
             return Pose{x, y, q};
           }),
           py::arg("x"), py::arg("y"), py::arg("q") = 0.0)
      .def_readwrite("x", &Pose::x)
      .def_readwrite("y", &Pose::y)
      .def_readwrite("q", &Pose::q)
      .def("__repr__", &pose_repr);

  py::class_<State>(m, "WalkingState",
                    "The generator's state at a tick; change it and pass it to set_state().")
      .def_property(
          "com_x", [](const State& s) { return to_numpy(s.com_x); },
          [](State& s, const py::object& v) {
            s.com_x = VectorArg(v, "WalkingState.com_x", 3).map();
          },
          "CoM x, ẋ, ẍ (3,)")
      .def_property(
          "com_y", [](const State& s) { return to_numpy(s.com_y); },
          [](State& s, const py::object& v) {
            s.com_y = VectorArg(v, "WalkingState.com_y", 3).map();
          },
          "CoM y, ẏ, ÿ (3,)")
      .def_readwrite("support_foot", &State::support_foot)
      .def_readwrite("support", &State::support, "the support foot's pose")
      .def_readwrite("swing_origin", &State::swing_origin, "where the swing foot lifted off")
      .def_property_readonly(
          "swing", [](const State& s) { return s.swing.pose(); }, "the swing foot's pose now")
      .def_readwrite("phase", &State::phase, "samples of the current step elapsed")
      .def_readwrite("time", &State::time, "[s] since the start")
      .def_readwrite("step_count", &State::step_count, "steps completed")
      .def_property_readonly("heading", &State::heading, "mean yaw of the feet [rad]");

  py::class_<PyMpcResult>(m, "MpcResult", "A generator tick's outcome.")
      .def_readonly("status", &PyMpcResult::status)
      .def_readonly("qp_status", &PyMpcResult::qp_status)
      .def_readonly("message", &PyMpcResult::message)
      .def_readonly("sqp_iterations", &PyMpcResult::sqp_iterations)
      .def_readonly("qp_iterations", &PyMpcResult::qp_iterations)
      .def_readonly("primal_residual", &PyMpcResult::primal_residual)
      .def_readonly("constraint_violation", &PyMpcResult::constraint_violation)
      .def_readonly("relaxed_blocks", &PyMpcResult::relaxed_blocks,
                    "status 'relaxed': the soft constraint blocks the plan violates, bit k = "
                    "row block k (WalkingMpc.block_names spells them)")
      .def_readonly("soft_fallback", &PyMpcResult::soft_fallback,
                    "an infeasible QP of this tick was solved with the soft constraints")
      .def_readonly("last_command", &PyMpcResult::last_command)
      .def_readonly("command", &PyMpcResult::command, "the command in use (vx, vy, wz)")
      .def_property_readonly("ok",
                             [](const PyMpcResult& r) { return r.status == MpcStatus::solved; })
      .def("__repr__", &result_repr);

  py::class_<Mpc>(m, "WalkingMpc",
                  "The NMPC walking pattern generator (thesis ch. 2): set_command(), then "
                  "solve() and advance() once per preview period t.")
      .def(py::init(&make_mpc), py::arg("settings") = hrp2_settings<double>(),
           py::arg("horizon") = py::none(), py::arg("obstacle_capacity") = 0,
           "Builds the generator; horizon (samples) overrides settings.n. Raises ValueError "
           "on invalid settings.")
      .def_property_readonly("horizon", &Mpc::horizon)
      .def_property_readonly("planned_steps", &Mpc::planned_steps)
      .def_property_readonly("samples_per_step", &Mpc::samples_per_step)
      .def_property_readonly("num_vars", &Mpc::num_vars, "variables of the QP")
      .def_property_readonly("num_rows", &Mpc::num_rows, "constraint rows of the QP")
      .def_property_readonly("obstacle_capacity", &Mpc::obstacle_capacity)
      .def_property_readonly("settings", [](const Mpc& mpc) { return mpc.settings(); })
      .def("set_command", &set_command, py::arg("vx"), py::arg("vy") = 0.0, py::arg("wz") = 0.0,
           "Velocity command in the robot's frame [m/s, m/s, rad/s]; returns 'accepted' or "
           "'clamped' (to settings.max_command). Non-finite values raise ValueError.")
      .def_property_readonly("command", [](const Mpc& mpc) { return to_numpy(mpc.command()); })
      .def("state", &Mpc::state, "A copy of the state.")
      .def("set_state", &Mpc::set_state, py::arg("state"),
           "Overwrites the state (feedback). Raises ValueError for non-finite or implausible "
           "states, which leave it unchanged.")
      .def(
          "reset",
          [](Mpc& mpc, const std::optional<State>& state) {
            mpc.reset(state ? *state : Mpc::initial_state(mpc.settings()));
          },
          py::arg("state") = py::none(),
          "Restarts from `state` (default: the settings' initial state), forgetting the plan.")
      .def_property_readonly("reference_heading", &Mpc::reference_heading)
      .def("conflicting_blocks", &Mpc::conflicting_blocks,
           "After a tick whose QP was infeasible: bit k set when dropping constraint row block "
           "k alone makes the tick's last hard QP feasible (block_names spells them); 0 when "
           "none does or it is not infeasible.")
      .def("block_names", &Mpc::block_names, py::arg("mask"),
           "The constraint blocks of a mask (MpcResult.relaxed_blocks), joined by '+'.")
      .def(
          "set_obstacles",
          [](Mpc& mpc, const py::iterable& items) { mpc.set_obstacles(as_obstacles(items)); },
          py::arg("obstacles"),
          "Replaces the obstacles: CircleObstacle or (x, y, radius[, margin]) items, at most "
          "obstacle_capacity.")
      .def_property_readonly(  // a copy: the generator reuses its storage
          "obstacles",
          [](const Mpc& mpc) {
            const auto& o = mpc.obstacles();
            return std::vector<CircleObstacle<double>>(o.begin(), o.end());
          })
      .def(
          "solve",
          [](Mpc& mpc) {
            {
              py::gil_scoped_release release;
              (void)mpc.solve();
            }
            return copy_result(mpc.result());
          },
          "Plans from the current state (one tick of the NMPC).")
      .def("advance", &Mpc::advance, py::call_guard<py::gil_scoped_release>(),
           "Moves the state one period t along the plan.")
      .def_property_readonly("result", [](const Mpc& mpc) { return copy_result(mpc.result()); })
      .def("footsteps", &footsteps, "Planned footsteps (planned_steps, 3): x, y, yaw.")
      .def(
          "com_trajectory", [](const Mpc& mpc) { return preview_xy(mpc, 0); },
          "Planned CoM positions at the next `horizon` samples (horizon, 2).")
      .def(
          "com_velocity_trajectory", [](const Mpc& mpc) { return preview_xy(mpc, 1); },
          "Planned CoM velocities (horizon, 2).")
      .def(
          "com_acceleration_trajectory", [](const Mpc& mpc) { return preview_xy(mpc, 2); },
          "Planned CoM accelerations (horizon, 2).")
      .def(
          "zmp_trajectory", [](const Mpc& mpc) { return preview_xy(mpc, 3); },
          "Planned ZMP at the next `horizon` samples (horizon, 2).")
      .def(
          "jerks",
          [](const Mpc& mpc) {
            const Eigen::Index N = mpc.horizon();
            Eigen::MatrixXd out(N, 2);
            out.col(0) = mpc.plan().U.head(N);
            out.col(1) = mpc.plan().U.segment(N + mpc.planned_steps(), N);
            return to_numpy(out);
          },
          "Planned CoM jerks (horizon, 2).")
      .def("interpolate", &interpolate, py::arg("command_period") = py::none(),
           "This tick's plan at the command period (default settings.command_period): a dict "
           "with 'samples' (k, 21) in the columns of walkgen.trajectory_columns, 'time' (k,), "
           "'support_foot' (k,) 0 left / 1 right and 'double_support' (k,). Call after solve().")
      .def(
          "decision_vector", [](const Mpc& mpc) { return to_numpy(mpc.plan().U); },
          "The plan's decision vector U (layout in walking_layout.hpp).");
}

}  // namespace walkgen::python
