#pragma once
/// @file
/// Umbrella header of the OpenCV adapter (target walkgen::opencv, option WALKGEN_WITH_OPENCV):
/// stereo calibration, depth, obstacles from depth and the demonstration recorder
/// (docs/depth.md). Includes this adapter's public headers and the core they need, never another
/// adapter; the core umbrella walkgen/walkgen.hpp never includes it.

#include "walkgen/opencv/demonstration_recorder.hpp"
#include "walkgen/opencv/depth_obstacles.hpp"
#include "walkgen/opencv/stereo_calibration.hpp"
#include "walkgen/opencv/stereo_depth.hpp"
