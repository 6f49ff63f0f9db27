#pragma once
/// @file
/// Umbrella header of the libtorch adapter (target walkgen::torch, option WALKGEN_WITH_TORCH):
/// PPO, its trainer over the core's environments (walkgen/learning/), and the
/// behavioural-cloning network in the loop (docs/learning.md). Includes this adapter's public
/// headers and the core they need, never another adapter; the core umbrella walkgen/walkgen.hpp
/// never includes it.

#include "walkgen/torch/ppo.hpp"
#include "walkgen/torch/training.hpp"
#include "walkgen/torch/velocity_network.hpp"
