#pragma once
/// @file
/// Umbrella header of the application component navigation (target walkgen::navigation:
/// simulation + opencv): navigation episodes with stereo depth and the scripted expert of
/// behavioural cloning (docs/learning.md).

#include "walkgen/navigation/navigation_episode.hpp"
#include "walkgen/navigation/scripted_expert.hpp"
