#pragma once
/// @file
/// Umbrella header of the YAML adapter (target walkgen::yaml, option WALKGEN_WITH_YAML,
/// yaml-cpp): the thesis's configuration files (Table 6.1) read into WalkingSettings
/// (docs/yaml.md). Includes this adapter's public headers and the core they need, never another
/// adapter; the core umbrella walkgen/walkgen.hpp never includes it.

#include "walkgen/yaml/robot_description_loader.hpp"
#include "walkgen/yaml/settings_loader.hpp"
