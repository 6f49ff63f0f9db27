// Forward kinematics and centre of mass against an independent reference: MuJoCo's own
// kinematics (mj_kinematics, mj_comPos, mj_jacBody, mj_jacSubtreeCom) on the generated MJCF,
// with the KinematicTree read from the generated URDF. Both files come from models/generate.py;
// this test proves that they describe the same robot and that walkgen computes it as MuJoCo
// does, for 1000 random in-limit configurations and random floating-base poses:
// every link's position within 1e-9 m and orientation within 1e-9 rad, the CoM within 1e-9 m.

#include <gtest/gtest.h>
#include <mujoco/mujoco.h>

#include <memory>
#include <random>
#include <string>
#include <vector>

#include "support/kinematics.hpp"
#include "walkgen/urdf/urdf_loader.hpp"

namespace {

using walkgen_test::Tree;

const std::string kModels = std::string(WALKGEN_SOURCE_DIR) + "/models/";

struct MujocoModel {
  std::unique_ptr<mjModel, decltype(&mj_deleteModel)> m{nullptr, mj_deleteModel};
  std::unique_ptr<mjData, decltype(&mj_deleteData)> d{nullptr, mj_deleteData};
};

MujocoModel load_mjcf() {
  MujocoModel model;
  char error[1000] = "";
  model.m.reset(
      mj_loadXML((kModels + "walkgen_humanoid.xml").c_str(), nullptr, error, sizeof(error)));
  EXPECT_NE(model.m, nullptr) << error;
  if (model.m) model.d.reset(mj_makeData(model.m.get()));
  return model;
}

// Where a link of the tree lives in MuJoCo: a body, or a site for frames inside a body.
struct MujocoFrame {
  int body = -1;
  int site = -1;
};

Eigen::Matrix3d matrix(const mjtNum* m) {  // MuJoCo stores 3x3 matrices row-major
  return Eigen::Map<const Eigen::Matrix<double, 3, 3, Eigen::RowMajor>>(m);
}

class MujocoReference : public ::testing::Test {
 protected:
  void SetUp() override {
    ASSERT_NE(mj.m, nullptr);
    for (const auto& link : tree.links()) {
      MujocoFrame f;
      f.body = mj_name2id(mj.m.get(), mjOBJ_BODY, link.name.c_str());
      if (f.body < 0) f.site = mj_name2id(mj.m.get(), mjOBJ_SITE, link.name.c_str());
      ASSERT_TRUE(f.body >= 0 || f.site >= 0) << link.name << " is not in the MJCF";
      frames.push_back(f);
    }
    for (const auto& name : tree.joint_names()) {
      const int j = mj_name2id(mj.m.get(), mjOBJ_JOINT, name.c_str());
      ASSERT_GE(j, 0) << name;
      ASSERT_EQ(mj.m->jnt_type[j], mjJNT_HINGE) << name;
      joints.push_back(j);
    }
    root = mj_name2id(mj.m.get(), mjOBJ_BODY, "root_link");
    ASSERT_EQ(mj.m->jnt_type[mj.m->body_jntadr[root]], mjJNT_FREE);
  }

  // Sets MuJoCo's qpos to the same configuration and runs its kinematics.
  void mujoco_kinematics(const walkgen_test::BasePose& base, const Eigen::VectorXd& q) {
    const int free = mj.m->jnt_qposadr[mj.m->body_jntadr[root]];
    const Eigen::Quaterniond quat(base.rotation);
    for (int i = 0; i < 3; ++i) mj.d->qpos[free + i] = base.position[i];
    mj.d->qpos[free + 3] = quat.w();
    mj.d->qpos[free + 4] = quat.x();
    mj.d->qpos[free + 5] = quat.y();
    mj.d->qpos[free + 6] = quat.z();
    for (std::size_t i = 0; i < joints.size(); ++i) {
      mj.d->qpos[mj.m->jnt_qposadr[joints[i]]] = q[Eigen::Index(i)];
    }
    mj_kinematics(mj.m.get(), mj.d.get());
    mj_comPos(mj.m.get(), mj.d.get());
  }

  MujocoModel mj = load_mjcf();
  Tree tree = walkgen::kinematic_tree_from_urdf_file(kModels + "walkgen_humanoid.urdf");
  std::vector<MujocoFrame> frames;  // per tree link
  std::vector<int> joints;          // MuJoCo joint id per entry of q
  int root = -1;
};

// The two files agree on the model's parameters: masses, CoMs, inertias, axes and limits.
TEST_F(MujocoReference, SameParameters) {
  EXPECT_NEAR(mj_getTotalmass(mj.m.get()), tree.mass(), 1e-12);
  for (std::size_t i = 0; i < frames.size(); ++i) {
    const auto& link = tree.links()[i];
    if (frames[i].body < 0) {
      EXPECT_EQ(link.mass, 0.0) << link.name;
      continue;
    }
    const int b = frames[i].body;
    EXPECT_EQ(mj.m->body_mass[b], link.mass) << link.name;
    if (link.mass == 0.0) continue;
    EXPECT_EQ(Eigen::Map<const Eigen::Vector3d>(mj.m->body_ipos + 3 * b), link.com) << link.name;
    EXPECT_EQ(Eigen::Map<const Eigen::Vector3d>(mj.m->body_inertia + 3 * b),
              link.inertia.diagonal())
        << link.name;
    EXPECT_TRUE(link.inertia.isDiagonal(0.0)) << link.name;
  }
  const Eigen::VectorXd lower = tree.lower_limits(), upper = tree.upper_limits();
  for (std::size_t i = 0; i < joints.size(); ++i) {
    const int j = joints[i];
    EXPECT_EQ(mj.m->jnt_range[2 * j], lower[Eigen::Index(i)]) << tree.joint_names()[i];
    EXPECT_EQ(mj.m->jnt_range[2 * j + 1], upper[Eigen::Index(i)]) << tree.joint_names()[i];
    const int link = tree.link_index(mj_id2name(mj.m.get(), mjOBJ_BODY, mj.m->jnt_bodyid[j]));
    EXPECT_EQ(tree.link(link).joint_name, tree.joint_names()[i]);
    EXPECT_EQ(Eigen::Map<const Eigen::Vector3d>(mj.m->jnt_axis + 3 * j), tree.link(link).axis);
  }
}

TEST_F(MujocoReference, ForwardKinematicsAndComAgreeOn1000Configurations) {
  std::mt19937 rng(1);
  auto ws = tree.make_workspace();
  double position_error = 0.0, rotation_error = 0.0, com_error = 0.0;
  for (int trial = 0; trial < 1000; ++trial) {
    const auto base = walkgen_test::random_base_pose(rng, 2.0);
    const Eigen::VectorXd q = walkgen_test::random_configuration(tree, rng);
    tree.forward_kinematics(base.position, base.rotation, q, ws);
    mujoco_kinematics(base, q);
    for (std::size_t i = 0; i < frames.size(); ++i) {
      const int b = frames[i].body, s = frames[i].site;
      const Eigen::Vector3d p =
          Eigen::Map<const Eigen::Vector3d>(b >= 0 ? mj.d->xpos + 3 * b : mj.d->site_xpos + 3 * s);
      const Eigen::Matrix3d R = matrix(b >= 0 ? mj.d->xmat + 9 * b : mj.d->site_xmat + 9 * s);
      const int link = int(i);
      position_error = std::max(position_error, (ws.position_W(link) - p).norm());
      rotation_error =
          std::max(rotation_error, Eigen::AngleAxisd(ws.rotation_W(link).transpose() * R).angle());
    }
    const Eigen::Vector3d com = Eigen::Map<const Eigen::Vector3d>(mj.d->subtree_com + 3 * root);
    com_error = std::max(com_error, (tree.center_of_mass(ws) - com).norm());
  }
  EXPECT_LE(position_error, 1e-9);
  EXPECT_LE(rotation_error, 1e-9);
  EXPECT_LE(com_error, 1e-9);
  RecordProperty("max_position_error_m", walkgen_test::scientific(position_error));
  RecordProperty("max_rotation_error_rad", walkgen_test::scientific(rotation_error));
  RecordProperty("max_com_error_m", walkgen_test::scientific(com_error));
}

// MuJoCo's Jacobians (mj_jacBody at each body's origin, mj_jacSubtreeCom) in walkgen's
// convention: MuJoCo's free joint takes the root's angular velocity in the root frame, ours in
// the world, so its rotational columns are multiplied by R_rootᵀ.
TEST_F(MujocoReference, JacobiansAgree) {
  std::mt19937 rng(5);
  auto ws = tree.make_workspace();
  const int nv = mj.m->nv;
  const int free_dof = mj.m->jnt_dofadr[mj.m->body_jntadr[root]];
  using RowMajor = Eigen::Matrix<double, 3, Eigen::Dynamic, Eigen::RowMajor>;
  RowMajor jacp(3, nv), jacr(3, nv);
  Eigen::Matrix<double, 6, Eigen::Dynamic> J(6, tree.num_velocities()),
      J_mj(6, tree.num_velocities());
  Eigen::Matrix<double, 3, Eigen::Dynamic> Jc(3, tree.num_velocities()),
      Jc_mj(3, tree.num_velocities());
  // MuJoCo's columns in walkgen's order: the free joint's six, then one per entry of q.
  auto reorder = [&](const RowMajor& mj_jac, const Eigen::Matrix3d& R_root, auto&& out) {
    out.template leftCols<3>() = mj_jac.middleCols<3>(free_dof);
    out.template middleCols<3>(3) = mj_jac.middleCols<3>(free_dof + 3) * R_root.transpose();
    for (std::size_t i = 0; i < joints.size(); ++i) {
      out.col(6 + Eigen::Index(i)) = mj_jac.col(mj.m->jnt_dofadr[joints[i]]);
    }
  };
  const walkgen_test::Blocks cols = walkgen_test::velocity_blocks(tree);
  walkgen_test::JacobianCheck frame_check, com_check;
  for (int trial = 0; trial < 100; ++trial) {
    const auto base = walkgen_test::random_base_pose(rng);
    const Eigen::VectorXd q = walkgen_test::random_configuration(tree, rng);
    tree.forward_kinematics(base.position, base.rotation, q, ws);
    mujoco_kinematics(base, q);
    for (std::size_t i = 0; i < frames.size(); ++i) {
      if (frames[i].body < 0) continue;
      mj_jacBody(mj.m.get(), mj.d.get(), jacp.data(), jacr.data(), frames[i].body);
      reorder(jacp, base.rotation, J_mj.topRows<3>());
      reorder(jacr, base.rotation, J_mj.bottomRows<3>());
      tree.frame_jacobian(ws, int(i), J);
      frame_check.merge(walkgen_test::compare_jacobians(
          "frame Jacobian of link '" + tree.link(int(i)).name + "'", J, J_mj, {1e-9},
          {{"linear velocity", 3}, {"angular velocity", 3}}, cols, "MuJoCo's mj_jacBody"));
    }
    mj_jacSubtreeCom(mj.m.get(), mj.d.get(), jacp.data(), root);
    reorder(jacp, base.rotation, Jc_mj);
    tree.center_of_mass_jacobian(ws, Jc);
    com_check.merge(walkgen_test::compare_jacobians("centre-of-mass Jacobian", Jc, Jc_mj, {1e-9},
                                                    {{"CoM", 3}}, cols,
                                                    "MuJoCo's mj_jacSubtreeCom"));
  }
  EXPECT_TRUE(frame_check.passed()) << frame_check.message();
  EXPECT_TRUE(com_check.passed()) << com_check.message();
  const double error = std::max(frame_check.max_error, com_check.max_error);
  RecordProperty("max_jacobian_error", walkgen_test::scientific(error));
}

}  // namespace
