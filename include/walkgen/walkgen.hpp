#pragma once
/// @file
/// Core umbrella header: everything that needs Eigen only. Never includes an adapter.

#include "walkgen/core/assert.hpp"
#include "walkgen/core/atomic_file.hpp"
#include "walkgen/core/data_dir.hpp"
#include "walkgen/core/decimal.hpp"
#include "walkgen/core/exceptions.hpp"
#include "walkgen/core/foot.hpp"
#include "walkgen/core/math.hpp"
#include "walkgen/estimation/base_estimator.hpp"
#include "walkgen/interpolation/polynomial.hpp"
#include "walkgen/interpolation/swing_foot.hpp"
#include "walkgen/interpolation/trajectory.hpp"
#include "walkgen/kinematics/kinematic_tree.hpp"
#include "walkgen/model/lipm.hpp"
#include "walkgen/model/support_polygon.hpp"
#include "walkgen/mpc/settings.hpp"
#include "walkgen/mpc/walking_mpc.hpp"
#include "walkgen/qp/dense_qp.hpp"
#include "walkgen/robot/robot.hpp"
#include "walkgen/robot/robot_description.hpp"
#include "walkgen/version.hpp"
