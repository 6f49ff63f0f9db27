// to_string() of every public enum of the core library, status enums and discrete choices alike
// (the adapters' own enums are checked in their tests with the same helper): constexpr, noexcept,
// the enumerator's snake_case name, each name once, and "unknown" for a value out of range.

#include <gtest/gtest.h>

#include <array>
#include <string>

#include "support/enum_strings.hpp"
#include "walkgen/control/go_to_target.hpp"
#include "walkgen/control/walking_loop.hpp"
#include "walkgen/core/foot.hpp"
#include "walkgen/kinematics/ik_target.hpp"
#include "walkgen/kinematics/kinematic_tree.hpp"
#include "walkgen/mpc/walking_layout.hpp"
#include "walkgen/mpc/walking_mpc.hpp"
#include "walkgen/qp/dense_qp.hpp"
#include "walkgen/robot/robot.hpp"
#include "walkgen/scenarios/manufactured_qp.hpp"
#include "walkgen/scenarios/walking_scenarios.hpp"

namespace {

using walkgen::CommandStatus;
using walkgen::Foot;
using walkgen::FootstepGroup;
using walkgen::IkStatus;
using walkgen::JointCommandStatus;
using walkgen::JointType;
using walkgen::LoopMode;
using walkgen::LoopStatus;
using walkgen::MpcStatus;
using walkgen::PassSide;
using walkgen::PatternWalkStatus;
using walkgen::QpKind;
using walkgen::QpStatus;
using walkgen::RenderStatus;
using walkgen::RobotStatus;
using walkgen::ShiftRule;
using walkgen::StopReason;

/// Every enumerator of each enum, in declaration order.
template <typename Enum>
struct Enumerators;
template <>
struct Enumerators<QpStatus> {
  static constexpr std::array<QpStatus, 6> all = {QpStatus::unsolved,      QpStatus::solved,
                                                  QpStatus::infeasible,    QpStatus::max_iterations,
                                                  QpStatus::invalid_input, QpStatus::inaccurate};
};
template <>
struct Enumerators<MpcStatus> {
  static constexpr std::array<MpcStatus, 4> all = {MpcStatus::solved, MpcStatus::qp_failed,
                                                   MpcStatus::not_converged, MpcStatus::relaxed};
};
template <>
struct Enumerators<CommandStatus> {
  static constexpr std::array<CommandStatus, 3> all = {
      CommandStatus::accepted, CommandStatus::non_finite, CommandStatus::clamped};
};
template <>
struct Enumerators<IkStatus> {
  static constexpr std::array<IkStatus, 3> all = {IkStatus::converged, IkStatus::not_converged,
                                                  IkStatus::invalid_input};
};
template <>
struct Enumerators<LoopStatus> {
  static constexpr std::array<LoopStatus, 8> all = {
      LoopStatus::ok,          LoopStatus::qp_failed,     LoopStatus::fallen, LoopStatus::diverged,
      LoopStatus::not_started, LoopStatus::not_converged, LoopStatus::fault,  LoopStatus::relaxed};
};
template <>
struct Enumerators<LoopMode> {
  static constexpr std::array<LoopMode, 5> all = {
      LoopMode::idle, LoopMode::walking, LoopMode::stopping, LoopMode::stopped, LoopMode::fault};
};
template <>
struct Enumerators<StopReason> {
  static constexpr std::array<StopReason, 8> all = {
      StopReason::none,        StopReason::requested,         StopReason::qp_failures,
      StopReason::ik_failures, StopReason::torque_saturation, StopReason::sensor_fault,
      StopReason::fallen,      StopReason::diverged};
};
template <>
struct Enumerators<RobotStatus> {
  static constexpr std::array<RobotStatus, 3> all = {RobotStatus::ok, RobotStatus::fallen,
                                                     RobotStatus::diverged};
};
template <>
struct Enumerators<JointCommandStatus> {
  static constexpr std::array<JointCommandStatus, 2> all = {JointCommandStatus::accepted,
                                                            JointCommandStatus::rejected};
};
template <>
struct Enumerators<RenderStatus> {
  static constexpr std::array<RenderStatus, 2> all = {RenderStatus::ok, RenderStatus::unavailable};
};
template <>
struct Enumerators<Foot> {
  static constexpr std::array<Foot, 2> all = {Foot::left, Foot::right};
};
template <>
struct Enumerators<ShiftRule> {
  static constexpr std::array<ShiftRule, 3> all = {ShiftRule::per_sample, ShiftRule::per_step,
                                                   ShiftRule::fixed};
};
template <>
struct Enumerators<JointType> {
  static constexpr std::array<JointType, 2> all = {JointType::revolute, JointType::fixed};
};
template <>
struct Enumerators<QpKind> {
  static constexpr std::array<QpKind, 5> all = {QpKind::generic, QpKind::degenerate,
                                                QpKind::equalities, QpKind::many_bounds,
                                                QpKind::parallel};
};
template <>
struct Enumerators<PassSide> {
  static constexpr std::array<PassSide, 4> all = {PassSide::toward_heading, PassSide::shorter,
                                                  PassSide::left, PassSide::right};
};

template <>
struct Enumerators<FootstepGroup> {
  static constexpr std::array<FootstepGroup, 2> all = {FootstepGroup::positions,
                                                       FootstepGroup::yaws};
};
template <>
struct Enumerators<PatternWalkStatus> {
  static constexpr std::array<PatternWalkStatus, 3> all = {
      PatternWalkStatus::ok, PatternWalkStatus::command_rejected, PatternWalkStatus::mpc_failed};
};

// constexpr: usable where a constant expression is needed.
static_assert(to_string(QpStatus::solved)[0] == 's');
static_assert(to_string(MpcStatus::qp_failed)[0] == 'q');
static_assert(to_string(CommandStatus::clamped)[0] == 'c');
static_assert(to_string(IkStatus::not_converged)[0] == 'n');
static_assert(to_string(LoopStatus::not_started)[0] == 'n');
static_assert(to_string(LoopMode::stopping)[0] == 's');
static_assert(to_string(StopReason::sensor_fault)[0] == 's');
static_assert(to_string(RobotStatus::fallen)[0] == 'f');
static_assert(to_string(JointCommandStatus::rejected)[0] == 'r');
static_assert(to_string(RenderStatus::unavailable)[0] == 'u');
static_assert(to_string(Foot::right)[0] == 'r');
static_assert(to_string(ShiftRule::per_step)[0] == 'p');
static_assert(to_string(JointType::fixed)[0] == 'f');
static_assert(to_string(PassSide::shorter)[0] == 's');
static_assert(to_string(QpKind::many_bounds)[0] == 'm');
static_assert(to_string(FootstepGroup::yaws)[0] == 'y');
static_assert(to_string(PatternWalkStatus::mpc_failed)[0] == 'm');

template <typename Enum>
class StatusStrings : public ::testing::Test {};

/// ctest names such as test_status_strings.StatusStrings/LoopStatus.EveryEnumerator.
struct EnumName {
  template <typename Enum>
  static std::string GetName(int) {
    if (std::is_same<Enum, QpStatus>::value) return "QpStatus";
    if (std::is_same<Enum, MpcStatus>::value) return "MpcStatus";
    if (std::is_same<Enum, CommandStatus>::value) return "CommandStatus";
    if (std::is_same<Enum, IkStatus>::value) return "IkStatus";
    if (std::is_same<Enum, LoopStatus>::value) return "LoopStatus";
    if (std::is_same<Enum, LoopMode>::value) return "LoopMode";
    if (std::is_same<Enum, StopReason>::value) return "StopReason";
    if (std::is_same<Enum, RobotStatus>::value) return "RobotStatus";
    if (std::is_same<Enum, JointCommandStatus>::value) return "JointCommandStatus";
    if (std::is_same<Enum, RenderStatus>::value) return "RenderStatus";
    if (std::is_same<Enum, Foot>::value) return "Foot";
    if (std::is_same<Enum, ShiftRule>::value) return "ShiftRule";
    if (std::is_same<Enum, JointType>::value) return "JointType";
    if (std::is_same<Enum, PassSide>::value) return "PassSide";
    if (std::is_same<Enum, QpKind>::value) return "QpKind";
    if (std::is_same<Enum, FootstepGroup>::value) return "FootstepGroup";
    if (std::is_same<Enum, PatternWalkStatus>::value) return "PatternWalkStatus";
    return "unnamed";
  }
};

using Enums =
    ::testing::Types<QpStatus, MpcStatus, CommandStatus, IkStatus, LoopStatus, LoopMode, StopReason,
                     RobotStatus, JointCommandStatus, RenderStatus, Foot, ShiftRule, JointType,
                     PassSide, QpKind, FootstepGroup, PatternWalkStatus>;
TYPED_TEST_SUITE(StatusStrings, Enums, EnumName);

TYPED_TEST(StatusStrings, EveryEnumeratorHasItsOwnNameAndOutOfRangeIsUnknown) {
  walkgen_test::expect_enum_strings(Enumerators<TypeParam>::all);
}

TEST(StatusStrings, NamesAreTheEnumerators) {
  EXPECT_STREQ(to_string(QpStatus::max_iterations), "max_iterations");
  EXPECT_STREQ(to_string(MpcStatus::qp_failed), "qp_failed");
  EXPECT_STREQ(to_string(MpcStatus::not_converged), "not_converged");
  EXPECT_STREQ(to_string(MpcStatus::relaxed), "relaxed");
  EXPECT_STREQ(to_string(QpStatus::inaccurate), "inaccurate");
  EXPECT_STREQ(to_string(CommandStatus::non_finite), "non_finite");
  EXPECT_STREQ(to_string(IkStatus::invalid_input), "invalid_input");
  EXPECT_STREQ(to_string(LoopStatus::not_started), "not_started");
  EXPECT_STREQ(to_string(RobotStatus::diverged), "diverged");
  EXPECT_STREQ(to_string(JointCommandStatus::rejected), "rejected");
  EXPECT_STREQ(to_string(RenderStatus::unavailable), "unavailable");
  EXPECT_STREQ(to_string(Foot::left), "left");
  EXPECT_STREQ(to_string(ShiftRule::per_sample), "per_sample");
  EXPECT_STREQ(to_string(JointType::revolute), "revolute");
  EXPECT_STREQ(to_string(PassSide::toward_heading), "toward_heading");
  EXPECT_STREQ(to_string(QpKind::many_bounds), "many_bounds");
  EXPECT_STREQ(to_string(FootstepGroup::positions), "positions");
  EXPECT_STREQ(to_string(PatternWalkStatus::command_rejected), "command_rejected");
}

}  // namespace
