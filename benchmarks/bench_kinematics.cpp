// Kinematics of walkgen's humanoid (models/): forward kinematics in double and in ceres::Jet, the
// centre of mass, and one warm-started whole-body IK solve (walkgen::CeresInverseKinematics) per
// command sample of a Heicub walk, with the analytic residual Jacobian (the default) and with
// Ceres' automatic differentiation over the FK in Jets. Side by side, where KDL is installed
// (Debian: liborocos-kdl-dev): KDL's ChainIkSolverPos_LMA on the two leg chains (root link to sole)
// for the same samples, each leg warm-started from the previous sample. Per-solve medians and the
// ratio are reported as counters (median_us, ratio_walkgen_over_kdl). And one update of the state
// estimator (BM_BaseEstimatorUpdate).
//   build/release/benchmarks/bench_kinematics --benchmark_filter=Ik
#include <benchmark/benchmark.h>

#include <algorithm>
#include <chrono>
#include <stdexcept>
#include <string>
#include <vector>

#include "walkgen/control/pattern_targets.hpp"
#include "walkgen/estimation/base_estimator.hpp"
#include "walkgen/humanoid/humanoid_ik.hpp"
#include "walkgen/scenarios/walking_scenarios.hpp"

#ifdef WALKGEN_HAVE_KDL
#include <kdl/chain.hpp>
#include <kdl/chainfksolverpos_recursive.hpp>
#include <kdl/chainiksolverpos_lma.hpp>
#endif

namespace {

using Tree = walkgen::KinematicTree<double>;
using walkgen::HumanoidIk;

const Tree& tree() {
  static const Tree t = walkgen::humanoid_tree();
  return t;
}

/// Two gait cycles of a Heicub walk forward, 1280 command samples.
const std::vector<walkgen::TrajectorySample<double>>& walk() {
  static const walkgen::PatternWalk w = walkgen::heicub_walk(Eigen::Vector3d(0.03, 0.0, 0.0), 32);
  if (!w.ok()) throw std::runtime_error(w.message);
  return w.samples;
}

/// Whole-body IK solutions along walk(), the reference of the KDL leg problems.
struct WalkSolution {
  std::vector<Eigen::VectorXd> q;
  std::vector<Eigen::Vector3d> base_position;
  std::vector<Eigen::Matrix3d> base_rotation;
  int failures = 0;  ///< samples whose IK did not converge (the previous solution is kept)
};
const WalkSolution& walk_solution() {
  static const WalkSolution solution = [] {
    WalkSolution s;
    HumanoidIk ik(tree());
    walkgen::start_walk(ik, walk().front());
    for (const auto& sample : walk()) {
      s.failures += ik.solve(walkgen::ik_target(sample)).status != walkgen::IkStatus::converged;
      s.q.push_back(ik.q());
      s.base_position.push_back(ik.base_position_W());
      s.base_rotation.push_back(ik.base_rotation_W());
    }
    return s;
  }();
  return solution;
}

double median(std::vector<double> v) {
  std::nth_element(v.begin(), v.begin() + std::ptrdiff_t(v.size() / 2), v.end());
  return v[v.size() / 2];
}

double walkgen_ik_median_us = 0.0;  // for the ratio reported by the KDL benchmark

template <typename Scalar>
void BM_ForwardKinematics(benchmark::State& state) {
  const auto t = tree().cast<Scalar>();
  auto ws = t.make_workspace();
  const Eigen::VectorXd q = walkgen::stand_configuration(tree());
  Eigen::Matrix<Scalar, Eigen::Dynamic, 1> qs(q.size());
  for (Eigen::Index i = 0; i < q.size(); ++i) qs[i] = Scalar(q[i]);
  if constexpr (!std::is_same<Scalar, double>::value) {
    for (Eigen::Index i = 0; i < q.size(); ++i) qs[i].v[6 + i] = 1.0;  // seed dq
  }
  const Eigen::Matrix<Scalar, 3, 1> p(Scalar(0), Scalar(0), Scalar(0.5));
  const Eigen::Matrix<Scalar, 3, 3> R = Eigen::Matrix<Scalar, 3, 3>::Identity();
  for (auto _ : state) {
    t.forward_kinematics(p, R, qs, ws);
    benchmark::DoNotOptimize(ws.position_W(t.num_links() - 1));
  }
}
BENCHMARK_TEMPLATE(BM_ForwardKinematics, double);
BENCHMARK_TEMPLATE(BM_ForwardKinematics, walkgen::HumanoidIk::Jet);

void BM_CenterOfMass(benchmark::State& state) {
  auto ws = tree().make_workspace();
  const Eigen::VectorXd q = walkgen::stand_configuration(tree());
  for (auto _ : state) {
    tree().forward_kinematics(Eigen::Vector3d(0, 0, 0.5), Eigen::Matrix3d::Identity(), q, ws);
    benchmark::DoNotOptimize(tree().center_of_mass(ws));
  }
}
BENCHMARK(BM_CenterOfMass);

void BM_CenterOfMassJacobian(benchmark::State& state) {
  auto ws = tree().make_workspace();
  tree().forward_kinematics(Eigen::Vector3d(0, 0, 0.5), Eigen::Matrix3d::Identity(),
                            walkgen::stand_configuration(tree()), ws);
  Eigen::Matrix<double, 3, Eigen::Dynamic> J(3, tree().num_velocities());
  for (auto _ : state) {
    tree().center_of_mass_jacobian(ws, J);
    benchmark::DoNotOptimize(J.data());
  }
}
BENCHMARK(BM_CenterOfMassJacobian);

/// One state-estimator update (walkgen::BaseEstimator: predict, two sole corrections, a contact
/// velocity correction, the CoM and its velocity): what the loop pays per command period for
/// the estimate. The right foot alternates between contact and swing.
void BM_BaseEstimatorUpdate(benchmark::State& state) {
  const walkgen::RobotDescription robot = walkgen::walkgen_humanoid_description();
  walkgen::BaseEstimator estimator(tree(), robot.joint_names,
                                   walkgen::base_estimator_settings(robot));
  walkgen::RobotOutput m;
  m.q = Eigen::VectorXd::Zero(Eigen::Index(robot.joint_names.size()));
  m.dq = Eigen::VectorXd::Constant(m.q.size(), 0.1);
  m.imu.available = true;
  m.imu.acceleration_I = Eigen::Vector3d(0.1, 0.0, 9.81);
  m.ft[0].force_S.z() = 200.0;
  if (estimator.reset(Eigen::Vector3d(0, 0, 0.5), m) != walkgen::EstimateStatus::ok)
    throw std::runtime_error("BM_BaseEstimatorUpdate: reset failed");
  long k = 0;
  for (auto _ : state) {
    m.ft[1].force_S.z() = (++k / 20) % 2 == 0 ? 200.0 : -5.0;
    benchmark::DoNotOptimize(estimator.update(m, 0.01));
    benchmark::DoNotOptimize(estimator.estimate().com_velocity_W.data());
  }
}
BENCHMARK(BM_BaseEstimatorUpdate);

/// One warm-started whole-body IK solve per command sample, walking through walk() in order,
/// with the analytic residual Jacobian (the default) or Ceres' automatic differentiation.
template <walkgen::IkDerivatives Derivatives>
void BM_IkWarmStartedPerSample(benchmark::State& state) {
  const auto& samples = walk();
  const auto& solution = walk_solution();
  walkgen::CeresIkSettings settings;
  settings.derivatives = Derivatives;
  HumanoidIk ik(tree(), settings);
  std::vector<double> times;
  std::size_t k = 0;
  int iterations = 0, failures = 0;
  for (auto _ : state) {
    if (k == samples.size()) k = 0;
    if (k == 0) {  // start over from the converged first sample
      state.PauseTiming();
      ik.set_initial_guess(solution.base_position[0], solution.base_rotation[0], solution.q[0]);
      if (ik.solve(walkgen::ik_target(samples[0])).status != walkgen::IkStatus::converged) {
        state.SkipWithError("the first sample did not converge");
      }
      k = 1;
      state.ResumeTiming();
    }
    const auto start = std::chrono::steady_clock::now();
    const walkgen::IkResult r = ik.solve(walkgen::ik_target(samples[k]));
    times.push_back(
        std::chrono::duration<double, std::micro>(std::chrono::steady_clock::now() - start)
            .count());
    iterations += r.iterations;
    failures += r.status != walkgen::IkStatus::converged;
    ++k;
  }
  const double median_us = median(times);
  if (Derivatives == walkgen::IkDerivatives::analytic) walkgen_ik_median_us = median_us;
  state.counters["median_us"] = median_us;
  state.counters["lm_iterations"] = double(iterations) / double(times.size());
  state.counters["failures"] = failures;
}
BENCHMARK_TEMPLATE(BM_IkWarmStartedPerSample, walkgen::IkDerivatives::analytic);
BENCHMARK_TEMPLATE(BM_IkWarmStartedPerSample, walkgen::IkDerivatives::automatic);

#ifdef WALKGEN_HAVE_KDL
/// The KDL chain from the root link to `tip`, built from the tree's description: per joint a
/// fixed segment to its origin (xyz, rpy), then for a revolute joint a rotation about its axis.
KDL::Chain kdl_chain(const Tree& t, const std::string& tip) {
  const auto& d = t.description();
  std::vector<const walkgen::JointDescription*> path;
  for (std::string link = tip;;) {
    const auto it =
        std::find_if(d.joints.begin(), d.joints.end(),
                     [&](const walkgen::JointDescription& j) { return j.child == link; });
    if (it == d.joints.end()) break;
    path.insert(path.begin(), &*it);
    link = it->parent;
  }
  KDL::Chain chain;
  for (const auto* j : path) {
    const KDL::Frame origin(KDL::Rotation::RPY(j->rpy.x(), j->rpy.y(), j->rpy.z()),
                            KDL::Vector(j->xyz.x(), j->xyz.y(), j->xyz.z()));
    chain.addSegment(KDL::Segment(j->name + "_origin", KDL::Joint(KDL::Joint::None), origin));
    if (j->type == walkgen::JointType::revolute) {
      const Eigen::Vector3d a = j->axis.normalized();
      chain.addSegment(
          KDL::Segment(j->name, KDL::Joint(j->name, KDL::Vector::Zero(),
                                           KDL::Vector(a.x(), a.y(), a.z()), KDL::Joint::RotAxis)));
    }
  }
  return chain;
}

/// The sole pose in the root frame for the whole-body solution at sample k.
KDL::Frame sole_in_root(const std::string& sole, std::size_t k) {
  const auto& s = walk_solution();
  auto ws = tree().make_workspace();
  tree().forward_kinematics(s.base_position[k], s.base_rotation[k], s.q[k], ws);
  const int link = tree().link_index(sole);
  const Eigen::Matrix3d R = s.base_rotation[k].transpose() * ws.rotation_W(link);
  const Eigen::Vector3d p =
      s.base_rotation[k].transpose() * (ws.position_W(link) - s.base_position[k]);
  KDL::Frame f;
  f.p = KDL::Vector(p.x(), p.y(), p.z());
  f.M = KDL::Rotation(R(0, 0), R(0, 1), R(0, 2), R(1, 0), R(1, 1), R(1, 2), R(2, 0), R(2, 1),
                      R(2, 2));
  return f;
}

/// KDL's LMA on both legs per command sample (warm-started from the previous sample's legs),
/// against the sole poses of the whole-body solution in the root frame.
void BM_KdlLegIkPerSample(benchmark::State& state) {
  struct Leg {
    KDL::Chain chain;
    std::vector<KDL::Frame> targets;
    std::vector<int> q_index;  // entries of the whole-body q
  };
  std::vector<Leg> legs;
  const auto& solution = walk_solution();
  for (const char* side : {"l_", "r_"}) {
    Leg leg;
    leg.chain = kdl_chain(tree(), std::string(side) + "sole");
    for (std::size_t k = 0; k < walk().size(); ++k) {
      leg.targets.push_back(sole_in_root(std::string(side) + "sole", k));
    }
    for (const char* j :
         {"hip_pitch", "hip_roll", "hip_yaw", "knee", "ankle_pitch", "ankle_roll"}) {
      leg.q_index.push_back(tree().joint_index(std::string(side) + j));
    }
    legs.push_back(std::move(leg));
  }
  // Cross-check: KDL's FK of the chain equals walkgen's at the first sample.
  for (auto& leg : legs) {
    KDL::JntArray q(leg.chain.getNrOfJoints());
    for (unsigned i = 0; i < q.rows(); ++i) q(i) = solution.q[0][leg.q_index[i]];
    KDL::Frame f;
    KDL::ChainFkSolverPos_recursive(leg.chain).JntToCart(q, f);
    if ((f.p - leg.targets[0].p).Norm() > 1e-9) state.SkipWithError("KDL chain FK differs");
  }
  Eigen::Matrix<double, 6, 1> weights = Eigen::Matrix<double, 6, 1>::Ones();
  std::vector<KDL::ChainIkSolverPos_LMA> solvers;
  for (const auto& leg : legs) solvers.emplace_back(leg.chain, weights, 1e-9, 500, 1e-15);
  std::vector<KDL::JntArray> q(2, KDL::JntArray(6)), q_out(2, KDL::JntArray(6));
  std::vector<double> times;
  std::size_t k = 0;
  int failures = 0;
  for (auto _ : state) {
    if (k == walk().size()) k = 0;
    if (k == 0) {
      for (int l = 0; l < 2; ++l) {
        for (int i = 0; i < 6; ++i) q[l](i) = solution.q[0][legs[l].q_index[i]];
      }
      k = 1;
    }
    const auto start = std::chrono::steady_clock::now();
    for (int l = 0; l < 2; ++l) {
      failures += solvers[l].CartToJnt(q[l], legs[l].targets[k], q_out[l]) < 0;
      q[l] = q_out[l];
    }
    times.push_back(
        std::chrono::duration<double, std::micro>(std::chrono::steady_clock::now() - start)
            .count());
    ++k;
  }
  const double kdl_median = median(times);
  state.counters["median_us"] = kdl_median;
  state.counters["failures"] = failures;
  state.counters["reference_failures"] = solution.failures;  // of the whole-body reference IK
  if (walkgen_ik_median_us > 0.0) {
    state.counters["ratio_walkgen_over_kdl"] = walkgen_ik_median_us / kdl_median;
  }
}
BENCHMARK(BM_KdlLegIkPerSample);
#endif

}  // namespace
