// The vocabulary of a navigation episode (walkgen/navigation/navigation_episode.hpp): how it
// ended (NavigationStatus and its to_string()) and the options it checks before it runs. The
// episodes themselves run in examples/record_demonstrations and examples/bc_evaluate.
#include "walkgen/navigation/navigation_episode.hpp"

#include <gtest/gtest.h>

#include <array>

#include "support/enum_strings.hpp"
#include "support/expect_error.hpp"

namespace {

using walkgen::NavigationOptions;
using walkgen::NavigationStatus;

TEST(NavigationEpisode, StatusStrings) {
  walkgen_test::expect_enum_strings(std::array<NavigationStatus, 7>{
      NavigationStatus::reached, NavigationStatus::collided, NavigationStatus::fallen,
      NavigationStatus::diverged, NavigationStatus::timed_out, NavigationStatus::render_unavailable,
      NavigationStatus::fault});
  static_assert(to_string(NavigationStatus::render_unavailable)[0] == 'r');
  EXPECT_STREQ(to_string(NavigationStatus::timed_out), "timed_out");
  const walkgen::NavigationResult nothing{};  // nothing happened: no flag is set
  EXPECT_FALSE(nothing.reached || nothing.collided || nothing.fell);
  EXPECT_EQ(nothing.status, NavigationStatus::timed_out);
}

TEST(NavigationEpisode, OptionsAreValidatedBeforeAnythingRuns) {
  using O = NavigationOptions;
  walkgen_test::expect_rejected<O>(
      O(),
      {{[](O& o) { o.time_limit = -1.0; }, {"NavigationOptions.time_limit", ">= 0", "-1"}},
       {[](O& o) { o.reach_distance = 0.0; }, {"NavigationOptions.reach_distance", "> 0", "0"}},
       {[](O& o) { o.max_restarts = -1; }, {"NavigationOptions.max_restarts", ">= 0", "-1"}}});
  O bad;
  bad.reach_distance = -0.3;
  const walkgen::NavigationScene scene =
      walkgen::make_navigation_scene(walkgen::NavigationTask::straight, 1);
  walkgen_test::expect_invalid_argument(
      [&] {
        (void)walkgen::run_navigation_episode(
            scene, [](const walkgen::NavigationObservation&) { return Eigen::Vector3d::Zero(); },
            bad);
      },
      {"NavigationOptions.reach_distance", "-0.3"});
}

}  // namespace
