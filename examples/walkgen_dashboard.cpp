// A browser dashboard and teleoperation for a simulated robot (docs/dashboard.md): the closed
// loop of thesis figure 6.1 walks walkgen's humanoid, the Unitree G1 or any described robot in
// MuJoCo at real time (or a chosen factor) in this program's main thread; an HTTP server
// (cpp-httplib, examples/dashboard/ server.hpp) serves a single page (examples/dashboard/web/,
// embedded in the program, no CDN) that draws the feet, the planned footsteps, CoM, ZMP, support
// polygon, obstacles and path, shows the chest camera's RGB and depth, plots ZMP error, speed and
// compute time, and steers the robot with the keyboard or buttons.
//
//   walkgen_dashboard [--robot NAME|PATH] [--port P] [--bind ADDRESS] [--scene TASK [--seed S]]
//                     [--speed F] [--max-time T] [--camera-period S] [--training DIR]
//     --robot        the robot: walkgen_humanoid (default), unitree_g1 or a description file
//     --port         TCP port (default 8080; 0: any free one, printed)
//     --bind         address to listen on (default 127.0.0.1: this machine only)
//     --scene        a navigation room (straight, curved, obstacle, scan, dynamic, distractor):
//                    walls, target, chairs and the person, chairs and person as NMPC obstacles
//     --speed        simulated seconds per wall-clock second (default 1: real time)
//     --max-time     stop after this many simulated seconds (default: until Ctrl-C)
//     --camera-period  simulated seconds between camera images (default 0.8)
//     --training     a training run's folder: its CSV logs plotted live (reward, success, losses)
// API: GET / (the page), GET /api/state (JSON), POST /api/command {"vx","vy","wz"},
// POST /api/stop, GET /api/events (server-sent events), GET /api/camera/rgb.jpg and depth.jpg,
// GET /api/training (the CSV logs of --training).
// The command line is parsed by CLI11 (examples/common/cli.hpp): --help prints every option.
#include <httplib.h>

#include <atomic>
#include <chrono>
#include <csignal>
#include <cstdio>
#include <nlohmann/json.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include "common/cli.hpp"
#include "common/navigation_cli.hpp"
#include "dashboard/server.hpp"
#include "dashboard_assets.hpp"  // generated from examples/dashboard/web/ (CMakeLists.txt)
#include "walkgen/mujoco/navigation_scene.hpp"
#include "walkgen/opencv/depth_obstacles.hpp"
#include "walkgen/opencv/stereo_depth.hpp"
#include "walkgen/simulation/humanoid_loop.hpp"
#include "walkgen/simulation/simulated_tasks.hpp"
#include "walkgen/yaml/robot_description_loader.hpp"

namespace {

std::atomic<int> g_signal{0};
void on_signal(int s) { g_signal = s; }

nlohmann::json xy(double x, double y) { return nlohmann::json::array({x, y}); }
nlohmann::json pose(const walkgen::FootPose<double>& p) {
  return nlohmann::json::array({p.x, p.y, p.q});
}

/// JPEGs of the left camera: RGB, and depth coloured near (warm) to far (cold) up to 4 m.
std::pair<std::string, std::string> encode_images(const walkgen::CameraImage& c) {
  const cv::Mat rgb(c.height, c.width, CV_8UC3, const_cast<std::uint8_t*>(c.rgb.data()));
  cv::Mat bgr;
  cv::cvtColor(rgb, bgr, cv::COLOR_RGB2BGR);
  const cv::Mat depth(c.height, c.width, CV_32F, const_cast<float*>(c.depth.data()));
  cv::Mat scaled, coloured;
  depth.convertTo(scaled, CV_8U, -255.0 / 4.0, 255.0);  // 0 m -> 255, 4 m and beyond -> 0
  cv::applyColorMap(scaled, coloured, cv::COLORMAP_JET);
  std::vector<std::uint8_t> a, b;
  cv::imencode(".jpg", bgr, a, {cv::IMWRITE_JPEG_QUALITY, 85});
  cv::imencode(".jpg", coloured, b, {cv::IMWRITE_JPEG_QUALITY, 85});
  return {std::string(a.begin(), a.end()), std::string(b.begin(), b.end())};
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{
      "walkgen_dashboard: a simulated robot, its plan and cameras in a browser, "
      "steered from the page (docs/dashboard.md)"};
  walkgen_examples::cli_defaults(app);
  std::string robot_name = "walkgen_humanoid", bind = "127.0.0.1", scene_name, training_dir;
  int port = 8080;
  std::uint32_t seed = 1000;
  double speed = 1.0, max_time = 0.0, camera_period = 0.8;
  app.add_option("--robot", robot_name, "robot name (models/NAME/robot.yaml) or description file");
  app.add_option("--port", port, "TCP port (0: any free one)")->check(CLI::Range(0, 65535));
  app.add_option("--bind", bind, "address to listen on (127.0.0.1: this machine only)");
  app.add_option("--scene", scene_name, "navigation room to walk in (default: the empty floor)")
      ->check(CLI::IsMember(walkgen_examples::navigation_task_names()))
      ->default_str("");
  app.add_option("--seed", seed, "the room's layout, 0..4294967295")
      ->transform(walkgen_examples::decimal_at_least<std::uint32_t>(0));
  app.add_option("--speed", speed, "simulated seconds per wall-clock second, in (0, 100]")
      ->check(CLI::Range(1e-3, 100.0));
  app.add_option("--max-time", max_time, "stop after this many simulated seconds (0: never)")
      ->check(walkgen_examples::non_negative);
  app.add_option("--camera-period", camera_period,
                 "simulated seconds between camera images, >= 0.4 (one NMPC tick)")
      ->check(CLI::Range(0.4, 60.0));
  app.add_option("--training", training_dir,
                 "a training run's folder: its CSV logs (ppo_train --out, bc_train.py --out) "
                 "plotted live")
      ->check(CLI::ExistingDirectory);
  WALKGEN_CLI_PARSE(app, argc, argv);

  walkgen::RobotDescription robot_description;
  try {
    robot_description = walkgen::find_robot_description(robot_name);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "walkgen_dashboard: --robot: %s\n", e.what());
    return 2;
  }
  std::optional<walkgen::NavigationScene> scene;
  if (!scene_name.empty()) {
    scene = walkgen::make_navigation_scene(walkgen::navigation_task_from_string(scene_name), seed);
  }

  walkgen::MujocoRobotSettings robot_settings = walkgen::mujoco_robot_settings(robot_description);
  walkgen::WalkingSettings<double> settings = robot_description.walking;
  if (scene) {
    robot_settings.objects = scene->objects();
    settings.obstacles = scene->obstacles_at(0.0, walkgen::kNavigationObstacleMargin);
  }
  std::optional<walkgen::MujocoRobot> robot_storage;
  try {
    robot_storage.emplace(robot_settings);
  } catch (const walkgen::invalid_argument& e) {
    std::fprintf(stderr, "walkgen_dashboard: --robot %s: %s\n", robot_name.c_str(), e.what());
    return 2;
  }
  walkgen::MujocoRobot& robot = *robot_storage;
  // The plan's frame is MuJoCo's world (the humanoid's settings stay as they are).
  settings = walkgen::settings_where_standing(settings, robot);
  // The rest runs with the robot's IK (fixed-size for a 15-joint robot, else sized at run time).
  const auto serve = [&](auto& ik) -> int {
    walkgen::WalkingLoop<16, std::decay_t<decltype(ik)>> loop(
        settings, robot, ik, walkgen::loop_settings(robot_description));
    const Eigen::Vector3d limit = 0.95 * settings.max_command;

    walkgen_dashboard::Board board(limit);
    httplib::Server server;
    server.new_task_queue = [] { return new httplib::ThreadPool(32); };
    walkgen_dashboard::add_routes(server, board, walkgen_dashboard::kAssets,
                                  std::chrono::milliseconds(50),  // events at most at 20 Hz
                                  training_dir);
    const int bound =
        port == 0 ? server.bind_to_any_port(bind) : (server.bind_to_port(bind, port) ? port : -1);
    if (bound < 0) {
      std::fprintf(stderr,
                   "walkgen_dashboard: cannot listen on %s:%d (in use, or not an address "
                   "of this machine)\n",
                   bind.c_str(), port);
      return 1;
    }
    std::thread http([&server] { server.listen_after_bind(); });
    std::signal(SIGINT, on_signal);
    std::signal(SIGTERM, on_signal);
    std::printf("walkgen_dashboard: http://%s:%d/ (%s%s%s, %.3gx real time; Ctrl-C stops)\n",
                bind.c_str(), bound, robot_description.name.c_str(), scene ? " in the room " : "",
                scene ? scene_name.c_str() : "", speed);
    std::fflush(stdout);

    // The loop: one NMPC tick (settings.t of simulated time) per iteration, paced to the wall
    // clock; commands and the stop button come from the board, the state goes to it.
    int exit_code = 0;
    const walkgen::LoopTick* tick = &loop.start();
    if (tick->status != walkgen::LoopStatus::ok) {
      std::fprintf(stderr, "walkgen_dashboard: the robot does not stand: %s\n",
                   tick->message.c_str());
      exit_code = 1;
    }
    const double t0 = robot.output().time;
    const auto wall0 = std::chrono::steady_clock::now();
    Eigen::Vector3d command = Eigen::Vector3d::Zero();
    std::vector<walkgen::CircleObstacle<double>> seen;  // obstacles found in the camera's depth
    double next_image = 0.0, compute_ms = 0.0;
    long ticks = 0;
    while (exit_code == 0 && g_signal == 0 &&
           (max_time <= 0.0 || robot.output().time - t0 < max_time)) {
      const double sim = robot.output().time - t0;
      std::this_thread::sleep_until(wall0 +
                                    std::chrono::duration_cast<std::chrono::steady_clock::duration>(
                                        std::chrono::duration<double>(sim / speed)));
      if (scene) walkgen::move_person(*scene, sim, robot, loop.mpc());  // the person walks on
      if (board.take_stop()) {
        command.setZero();
        (void)loop.request_stop();
      }
      if (const auto c = board.take_command()) {
        command = *c;
        if (loop.mode() == walkgen::LoopMode::stopped && !command.isZero()) {
          (void)loop.start();  // walk on from standing
        }
        (void)loop.set_command(command);
      }
      if (sim >= next_image) {
        const walkgen::StereoImages& images = robot.render_cameras();
        if (images.status == walkgen::RenderStatus::ok) {
          auto [rgb, depth] = encode_images(images.left);
          board.publish_images(std::move(rgb), std::move(depth));
          // What the camera sees as obstacles (walkgen::obstacles_from_depth on its depth image)
          const walkgen::CameraImage& c = images.left;
          const cv::Mat depth_image(c.height, c.width, CV_32F, const_cast<float*>(c.depth.data()));
          seen = walkgen::obstacles_from_depth(
              depth_image, walkgen::pinhole_from_fovy(c.width, c.height, c.fovy), c.pose_W_C);
        } else {
          board.set_camera_message(images.message);
        }
        next_image = sim + camera_period;
      }
      const auto start = std::chrono::steady_clock::now();
      tick = &loop.tick();
      compute_ms =
          std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start)
              .count();
      ++ticks;

      // The state the page draws.
      const auto& st = loop.mpc().state();
      const auto& samples = loop.samples();
      const Eigen::Vector2d com = walkgen::true_com(robot);
      nlohmann::json j;
      j["time"] = robot.output().time - t0;
      j["status"] = walkgen::to_string(tick->status);
      j["mode"] = walkgen::to_string(tick->mode);
      j["reason"] = walkgen::to_string(tick->reason);
      j["message"] = tick->message;
      j["command"] = {command.x(), command.y(), command.z()};
      j["max_command"] = {limit.x(), limit.y(), limit.z()};
      j["com"] = xy(com.x(), com.y());
      j["heading"] = st.heading();
      nlohmann::json zmp_plan = nlohmann::json::array(), zmp_measured = nlohmann::json::array(),
                     com_plan = nlohmann::json::array();
      double zmp_error = 0.0;
      int zmp_valid = 0;
      for (const auto& s : samples) {
        zmp_plan.push_back(xy(s.plan.zmp_x, s.plan.zmp_y));
        com_plan.push_back(xy(s.plan.com_x[0], s.plan.com_y[0]));
        if (s.zmp.valid) {
          zmp_measured.push_back(xy(s.zmp.zmp_W.x(), s.zmp.zmp_W.y()));
          zmp_error += std::hypot(s.zmp.zmp_W.x() - s.plan.zmp_x, s.zmp.zmp_W.y() - s.plan.zmp_y);
          ++zmp_valid;
        }
      }
      j["zmp_plan"] = zmp_plan;
      j["zmp_measured"] = zmp_measured;
      j["com_plan"] = com_plan;
      j["zmp"] = samples.empty() ? xy(com.x(), com.y()) : zmp_plan.back();
      j["zmp_error"] = zmp_valid > 0 ? zmp_error / zmp_valid : 0.0;
      j["speed"] = samples.empty()
                       ? 0.0
                       : std::hypot(samples.back().plan.com_x[1], samples.back().plan.com_y[1]);
      j["compute_ms"] = compute_ms;
      j["mpc_ms"] = 1e3 * tick->mpc_seconds;
      j["support"] = walkgen::to_string(st.support_foot);
      j["feet"] = {{"support", pose(st.support)},
                   {"swing", nlohmann::json::array(
                                 {st.swing.x.position, st.swing.y.position, st.swing.q.position})}};
      nlohmann::json steps = nlohmann::json::array();
      for (int i = 1; i <= loop.mpc().planned_steps(); ++i)
        steps.push_back(pose(loop.mpc().plan().footstep(i)));
      j["footsteps"] = steps;
      j["foot_size"] = {settings.foot_length, settings.foot_width};
      nlohmann::json obstacles = nlohmann::json::array();
      for (const auto& o : loop.mpc().obstacles())
        obstacles.push_back({o.x, o.y, o.radius, o.margin});
      j["obstacles"] = obstacles;
      nlohmann::json seen_json = nlohmann::json::array();
      for (const auto& o : seen) seen_json.push_back({o.x, o.y, o.radius});
      j["seen_obstacles"] = seen_json;
      j["target"] = scene ? xy(scene->target.x(), scene->target.y()) : nlohmann::json();
      j["ticks"] = ticks;
      board.publish_state(j.dump());

      if (tick->status == walkgen::LoopStatus::fallen ||
          tick->status == walkgen::LoopStatus::diverged) {
        // the page shows the fault; the server stays up until Ctrl-C or --max-time
        if (max_time <= 0.0) {
          while (g_signal == 0) std::this_thread::sleep_for(std::chrono::milliseconds(100));
        }
        break;
      }
    }
    board.close();
    server.stop();
    http.join();
    std::printf("walkgen_dashboard: %ld ticks, %.1f s simulated, last status %s%s%s\n", ticks,
                robot.output().time - t0, walkgen::to_string(tick->status),
                tick->message.empty() ? "" : ": ", tick->message.c_str());
    return exit_code;
  };
  try {
    return walkgen::with_robot_ik(robot_description, serve);
  } catch (const walkgen::invalid_argument& e) {
    std::fprintf(stderr, "walkgen_dashboard: --robot %s: %s\n", robot_name.c_str(), e.what());
    return 2;
  }
}
