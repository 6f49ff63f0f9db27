// to_string() of every status enum of the core library (the adapters' own enums are checked in
// their tests with the same helper): constexpr, noexcept, the enumerator's snake_case name, each
// name once, and "unknown" for a value out of range.

#include <gtest/gtest.h>

#include <array>
#include <string>

#include "support/enum_strings.hpp"
#include "walkgen/control/walking_loop.hpp"
#include "walkgen/core/foot.hpp"
#include "walkgen/kinematics/ik_target.hpp"
#include "walkgen/mpc/walking_mpc.hpp"
#include "walkgen/qp/dense_qp.hpp"
#include "walkgen/robot_io/robot.hpp"

namespace {

using walkgen::CommandStatus;
using walkgen::Foot;
using walkgen::IkStatus;
using walkgen::JointCommandStatus;
using walkgen::LoopStatus;
using walkgen::MpcStatus;
using walkgen::QpStatus;
using walkgen::RenderStatus;
using walkgen::RobotStatus;

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
  static constexpr std::array<MpcStatus, 3> all = {MpcStatus::solved, MpcStatus::qp_failed,
                                                   MpcStatus::not_converged};
};
template <>
struct Enumerators<CommandStatus> {
  static constexpr std::array<CommandStatus, 3> all = {
      CommandStatus::accepted, CommandStatus::non_finite, CommandStatus::out_of_range};
};
template <>
struct Enumerators<IkStatus> {
  static constexpr std::array<IkStatus, 3> all = {IkStatus::converged, IkStatus::not_converged,
                                                  IkStatus::invalid_input};
};
template <>
struct Enumerators<LoopStatus> {
  static constexpr std::array<LoopStatus, 6> all = {
      LoopStatus::ok,       LoopStatus::qp_failed,   LoopStatus::fallen,
      LoopStatus::diverged, LoopStatus::not_started, LoopStatus::not_converged};
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

// constexpr: usable where a constant expression is needed.
static_assert(to_string(QpStatus::solved)[0] == 's');
static_assert(to_string(MpcStatus::qp_failed)[0] == 'q');
static_assert(to_string(CommandStatus::out_of_range)[0] == 'o');
static_assert(to_string(IkStatus::not_converged)[0] == 'n');
static_assert(to_string(LoopStatus::not_started)[0] == 'n');
static_assert(to_string(RobotStatus::fallen)[0] == 'f');
static_assert(to_string(JointCommandStatus::rejected)[0] == 'r');
static_assert(to_string(RenderStatus::unavailable)[0] == 'u');
static_assert(to_string(Foot::right)[0] == 'r');

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
    if (std::is_same<Enum, RobotStatus>::value) return "RobotStatus";
    if (std::is_same<Enum, JointCommandStatus>::value) return "JointCommandStatus";
    if (std::is_same<Enum, RenderStatus>::value) return "RenderStatus";
    if (std::is_same<Enum, Foot>::value) return "Foot";
    return "unnamed";
  }
};

using Enums = ::testing::Types<QpStatus, MpcStatus, CommandStatus, IkStatus, LoopStatus,
                               RobotStatus, JointCommandStatus, RenderStatus, Foot>;
TYPED_TEST_SUITE(StatusStrings, Enums, EnumName);

TYPED_TEST(StatusStrings, EveryEnumeratorHasItsOwnNameAndOutOfRangeIsUnknown) {
  walkgen_test::expect_enum_strings(Enumerators<TypeParam>::all);
}

TEST(StatusStrings, NamesAreTheEnumerators) {
  EXPECT_STREQ(to_string(QpStatus::max_iterations), "max_iterations");
  EXPECT_STREQ(to_string(MpcStatus::qp_failed), "qp_failed");
  EXPECT_STREQ(to_string(MpcStatus::not_converged), "not_converged");
  EXPECT_STREQ(to_string(QpStatus::inaccurate), "inaccurate");
  EXPECT_STREQ(to_string(CommandStatus::non_finite), "non_finite");
  EXPECT_STREQ(to_string(IkStatus::invalid_input), "invalid_input");
  EXPECT_STREQ(to_string(LoopStatus::not_started), "not_started");
  EXPECT_STREQ(to_string(RobotStatus::diverged), "diverged");
  EXPECT_STREQ(to_string(JointCommandStatus::rejected), "rejected");
  EXPECT_STREQ(to_string(RenderStatus::unavailable), "unavailable");
  EXPECT_STREQ(to_string(Foot::left), "left");
}

}  // namespace
