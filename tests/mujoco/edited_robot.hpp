#pragma once
// A Robot that is a MujocoRobot whose reported measurement a test edits: commands, physics and
// images are the MujocoRobot's; output() is its output after edit() (e.g. a sensor fault, a
// missing IMU). What a faulty robot would hand the loop, with MuJoCo's physics behind it.

#include "walkgen/mujoco/mujoco_robot.hpp"

namespace walkgen_test {

class EditedRobot : public walkgen::Robot {
 public:
  explicit EditedRobot(walkgen::MujocoRobot& inner) : inner_(inner) { out_ = inner_.output(); }

  const walkgen::RobotInfo& info() const override { return inner_.info(); }
  walkgen::JointCommandStatus set_joint_targets(
      const Eigen::Ref<const Eigen::VectorXd>& q) override {
    return inner_.set_joint_targets(q);
  }
  walkgen::RobotStatus step(double duration) override {
    const walkgen::RobotStatus s = inner_.step(duration);
    refresh();
    return s;
  }
  void set_balance_reference(const walkgen::BalanceReference& reference) override {
    inner_.set_balance_reference(reference);  // a torque-driven robot's balance feed-forward
  }
  const walkgen::RobotOutput& output() const override { return out_; }
  const walkgen::StereoImages& render_cameras() override { return inner_.render_cameras(); }
  void reset() override {
    inner_.reset();
    on_reset();
    refresh();
  }

 protected:
  /// Edits the MujocoRobot's measurement `out` (a copy) before it is reported.
  virtual void edit(walkgen::RobotOutput& out) = 0;
  /// Forgets what edit() accumulated (after the MujocoRobot's reset()).
  virtual void on_reset() {}
  /// Reports the MujocoRobot's current measurement through edit() (call once from the derived
  /// class's constructor: edit() is not virtual-dispatched from the base's).
  void refresh() {
    out_ = inner_.output();
    edit(out_);
  }

 private:
  walkgen::MujocoRobot& inner_;
  walkgen::RobotOutput out_;
};

}  // namespace walkgen_test
