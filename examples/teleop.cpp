// Keyboard teleoperation of the simulated robot in the terminal (thesis §8, appendix B.3.1): the
// keys change the velocity command (v_x, v_y, ω_z) within the NMPC's limits, the closed loop of
// figure 6.1 walks the robot (walkgen's humanoid, the Unitree G1, any described robot) in MuJoCo at
// real time (or faster), the screen shows command and state, and every NMPC tick is recorded with
// its command and timestamps (for behavioural cloning). In a navigation room (thesis §11.1) it
// records teleoperated demonstrations like examples/record_demonstrations records the scripted
// expert (§7.1.2, figure 7.2).
//
//   teleop [--robot R] [--speed S] [--record FILE] [--max-time T] [--summary FILE]
//          [--room TASK [--seed S] [--demonstrations DIR]]
//     --robot R     walkgen_humanoid (default) or unitree_g1 (models/R/robot.yaml), or the path of
//                   a robot description file (docs/robots.md); needs a build with walkgen::yaml
//     --speed S     simulated seconds per wall-clock second, in (0, 1000] (default 1: real time)
//     --record FILE CSV: wall_time, sim_time, v_x, v_y, omega, key (default teleop_commands.csv)
//     --max-time T  stop after T simulated seconds [s], > 0 (default: until q)
//     --summary FILE  a few key=value lines at the end (distance walked, status, rows)
//     --room TASK   walk in the room walkgen::make_navigation_scene(TASK, S) (straight, curved,
//                   obstacle, scan, dynamic, distractor): walls, target, chairs and the person
//                   (moved each tick) in MuJoCo, chairs and person as NMPC obstacles; stops when
//                   the true CoM is within 0.3 m of the target
//     --seed S      the room's layout, a decimal integer in 0..4294967295 (default 1000)
//     --demonstrations DIR  every NMPC tick, the left RGB image, the WLS disparity of the chest
//                   stereo pair and the executed command into DIR (walkgen::DemonstrationRecorder,
//                   episode "<task>_<seed>_teleop"); needs --room and a build with walkgen::opencv
// The command line is parsed by CLI11 (examples/common/cli.hpp): --help prints every option with
// its default and exits 0; an unknown option or a bad value exits 2 with one line on stderr.
//
// Keys: Up/w faster, Down/s slower (v_x ± 0.005 m/s), Left/a turn left, Right/d turn right
// (ω ± 0.015 rad/s), z/c sideways left/right (v_y ± 0.0015 m/s), space stop, q quit.
#include <poll.h>
#include <termios.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <optional>
#include <string>
#include <thread>
#include <type_traits>
#include <vector>

#include "common/cli.hpp"
#include "common/navigation_cli.hpp"
#include "walkgen/mujoco/navigation_scene.hpp"
#include "walkgen/simulation/humanoid_loop.hpp"
#include "walkgen/simulation/simulated_tasks.hpp"
#ifdef WALKGEN_TELEOP_ROBOT_FILES  // examples/CMakeLists.txt: teleop links walkgen::yaml
#include "walkgen/yaml/robot_description_loader.hpp"
#endif
#ifdef WALKGEN_TELEOP_DEMONSTRATIONS  // examples/CMakeLists.txt: teleop links walkgen::opencv
#include "walkgen/navigation/navigation_episode.hpp"
#endif

namespace {

/// Reached: the true CoM this close to the room's target [m] (as run_navigation_episode).
constexpr double kRoomReachDistance = 0.3;

volatile std::sig_atomic_t g_stop = 0;
void on_signal(int) { g_stop = 1; }

/// Raw, non-echoing terminal input while alive (when stdin is a terminal).
class RawTerminal {
 public:
  RawTerminal() {
    if (isatty(STDIN_FILENO) == 0 || tcgetattr(STDIN_FILENO, &saved_) != 0) return;
    termios raw = saved_;
    raw.c_lflag &= ~tcflag_t(ICANON | ECHO);
    raw.c_cc[VMIN] = 0;
    raw.c_cc[VTIME] = 0;
    active_ = tcsetattr(STDIN_FILENO, TCSANOW, &raw) == 0;
  }
  ~RawTerminal() {
    if (active_) tcsetattr(STDIN_FILENO, TCSANOW, &saved_);
  }
  RawTerminal(const RawTerminal&) = delete;
  RawTerminal& operator=(const RawTerminal&) = delete;

 private:
  termios saved_{};
  bool active_ = false;
};

enum class Key { none, up, down, left, right, side_left, side_right, stop, quit };

const char* key_name(Key k) {
  switch (k) {
    case Key::up:
      return "up";
    case Key::down:
      return "down";
    case Key::left:
      return "left";
    case Key::right:
      return "right";
    case Key::side_left:
      return "side_left";
    case Key::side_right:
      return "side_right";
    case Key::stop:
      return "stop";
    case Key::quit:
      return "quit";
    default:
      return "";
  }
}

/// The keys in the bytes waiting on stdin, waiting at most timeout_ms for the first.
std::string read_input(int timeout_ms) {
  pollfd fd{STDIN_FILENO, POLLIN, 0};
  std::string bytes;
  if (poll(&fd, 1, timeout_ms) <= 0 || (fd.revents & POLLIN) == 0) return bytes;
  char buffer[64];
  const ssize_t n = read(STDIN_FILENO, buffer, sizeof(buffer));
  if (n > 0) bytes.assign(buffer, std::size_t(n));
  return bytes;
}

/// Splits input into keys: arrows arrive as ESC [ A..D (or ESC O A..D).
template <typename OnKey>
void parse_keys(const std::string& in, OnKey on_key) {
  for (std::size_t i = 0; i < in.size(); ++i) {
    const char c = in[i];
    if (c == '\x1b' && i + 2 < in.size() && (in[i + 1] == '[' || in[i + 1] == 'O')) {
      const char a = in[i + 2];
      i += 2;
      if (a == 'A') on_key(Key::up);
      if (a == 'B') on_key(Key::down);
      if (a == 'C') on_key(Key::right);
      if (a == 'D') on_key(Key::left);
      continue;
    }
    switch (c) {
      case 'w':
        on_key(Key::up);
        break;
      case 's':
        on_key(Key::down);
        break;
      case 'a':
        on_key(Key::left);
        break;
      case 'd':
        on_key(Key::right);
        break;
      case 'z':
        on_key(Key::side_left);
        break;
      case 'c':
        on_key(Key::side_right);
        break;
      case ' ':
        on_key(Key::stop);
        break;
      case 'q':
      case 'Q':
        on_key(Key::quit);
        break;
      default:
        break;
    }
  }
}

}  // namespace

int main(int argc, char** argv) {
  double speed = 1.0, max_time = std::numeric_limits<double>::infinity();
  std::string record = "teleop_commands.csv", summary_path, room, demonstrations,
              robot_name = "walkgen_humanoid";
  std::uint32_t seed = 1000;
  const std::vector<std::string> rooms = walkgen_examples::navigation_task_names();
  CLI::App app{
      "Keyboard teleoperation of a robot in MuJoCo, in the terminal (thesis §8, "
      "appendix B.3.1)",
      "teleop"};
  walkgen_examples::cli_defaults(app);
  app.add_option("--robot", robot_name,
                 "the robot: walkgen_humanoid or unitree_g1 (models/NAME/robot.yaml), or the "
                 "path of a robot description file (docs/robots.md)");
  app.add_option("--speed", speed, "simulated s per wall-clock s, in (0, 1000]; 1: real time")
      ->check(walkgen_examples::number_where("in (0, 1000]",
                                             [](double v) { return v > 0.0 && v <= 1000.0; }));
  app.add_option("--record", record, "CSV, a line per NMPC tick: times [s], command, keys");
  app.add_option("--max-time", max_time,
                 "stop after this simulated time [s], > 0 (default: none, until q)")
      ->check(walkgen_examples::positive)
      ->default_str("");
  app.add_option("--summary", summary_path,
                 "key=value lines at the end: status, pose [m, rad], ... (default: none)");
  CLI::Option* room_option =
      app.add_option("--room", room,
                     "walk in this room (§11.1) until 0.3 m from its target (default: none)")
          ->check(CLI::IsMember(rooms));
  app.add_option("--seed", seed, "the room's layout, 0..4294967295")
      ->transform(walkgen_examples::decimal_at_least<std::uint32_t>(0));
  app.add_option("--demonstrations", demonstrations,
                 "record image, disparity, command per tick into this folder (default: none)")
      ->needs(room_option);
  WALKGEN_CLI_PARSE(app, argc, argv);
  walkgen::RobotDescription description = walkgen::walkgen_humanoid_description();
  if (robot_name != description.name) {
#ifdef WALKGEN_TELEOP_ROBOT_FILES
    try {
      description = walkgen::find_robot_description(robot_name);
    } catch (const walkgen::invalid_argument& e) {
      std::fprintf(stderr, "teleop: --robot: %s\n", e.what());
      return 2;
    }
#else
    std::fprintf(stderr,
                 "teleop: --robot %s: this build reads no robot description files (it lacks "
                 "walkgen::yaml); only walkgen_humanoid\n",
                 robot_name.c_str());
    return 2;
#endif
  }
  // The room (--room), and the demonstrations recorded in it (--demonstrations).
  std::optional<walkgen::NavigationScene> scene;
  if (!room.empty()) {
    scene = walkgen::make_navigation_scene(walkgen::navigation_task_from_string(room), seed);
  }
#ifdef WALKGEN_TELEOP_DEMONSTRATIONS
  std::optional<walkgen::DemonstrationRecorder> recorder;
  std::optional<walkgen::StereoDepth> stereo;
  if (!demonstrations.empty()) {
    const std::string episode = room + "_" + std::to_string(seed) + "_teleop";
    if (std::filesystem::exists(demonstrations + "/rgb/" + episode + "_000000.png")) {
      std::fprintf(stderr,
                   "teleop: '%s' already holds the episode %s (its images would be overwritten); "
                   "choose another --seed or DIR\n",
                   demonstrations.c_str(), episode.c_str());
      return 2;
    }
    try {
      recorder.emplace(demonstrations, episode);
    } catch (const walkgen::invalid_argument& e) {
      std::fprintf(stderr, "teleop: --demonstrations: %s\n", e.what());
      return 2;
    }
  }
#else
  if (!demonstrations.empty()) {
    std::fprintf(stderr,
                 "teleop: --demonstrations needs walkgen::opencv, which this build lacks\n");
    return 2;
  }
#endif
  std::signal(SIGINT, on_signal);
  std::signal(SIGTERM, on_signal);

  walkgen::MujocoRobotSettings robot_settings = walkgen::mujoco_robot_settings(description);
  walkgen::WalkingSettings<double> settings = description.walking;
  if (scene) {
    robot_settings.objects = scene->objects();
    settings.obstacles =
        scene->obstacles_at(0.0, walkgen::kNavigationObstacleMargin);  // chairs and person
  }
  if (!demonstrations.empty() && description.cameras[0].empty()) {
    std::fprintf(stderr, "teleop: --demonstrations: the robot %s has no chest cameras\n",
                 description.name.c_str());
    return 2;
  }
  std::optional<walkgen::MujocoRobot> robot_storage;
  try {
    robot_storage.emplace(robot_settings);
  } catch (const walkgen::invalid_argument& e) {
    std::fprintf(stderr, "teleop: --robot %s: %s\n", robot_name.c_str(), e.what());
    return 2;
  }
  walkgen::MujocoRobot& robot = *robot_storage;
  // The plan's frame is MuJoCo's world (the humanoid's settings stay as they are).
  settings = walkgen::settings_where_standing(settings, robot);
  // The rest walks with the robot's IK (fixed-size for a 15-joint robot, else sized at run time).
  const auto walk = [&](auto& ik) -> int {
    walkgen::WalkingLoop<16, std::decay_t<decltype(ik)>> loop(settings, robot, ik,
                                                              walkgen::loop_settings(description));
    std::ofstream csv(record);
    if (!csv) {
      std::fprintf(stderr, "teleop: cannot write '%s'\n", record.c_str());
      return 2;
    }
    csv << "wall_time,sim_time,v_x,v_y,omega,key\n";
    csv.precision(6);
    std::printf("teleop: standing up (moving the CoM over the left foot)...\n");
    if (loop.start().status != walkgen::LoopStatus::ok) {
      std::fprintf(stderr, "teleop: %s\n", loop.last_tick().message.c_str());
      return 1;
    }
#ifdef WALKGEN_TELEOP_DEMONSTRATIONS
    if (recorder) {
      const walkgen::StereoImages& first = robot.render_cameras();
      if (first.status != walkgen::RenderStatus::ok) {
        std::fprintf(stderr, "teleop: cannot render the chest cameras: %s\n",
                     first.message.c_str());
        return 1;
      }
      stereo.emplace(walkgen::make_stereo_depth(first));
    }
#endif
    const walkgen::PlanarPose start_pose = walkgen::walking_pose(loop.mpc().state());
    const Eigen::Vector3d limit = 0.95 * settings.max_command;
    const Eigen::Vector3d step(0.005, 0.0015, 0.015);
    Eigen::Vector3d command = Eigen::Vector3d::Zero();
    const double t0 = robot.output().time;
    const auto wall0 = std::chrono::steady_clock::now();
    auto wall = [&] {
      return std::chrono::duration<double>(std::chrono::steady_clock::now() - wall0).count();
    };
    RawTerminal terminal;
    bool quit = false;
    long rows = 0;
    double zmp_sum = 0.0;
    long zmp_n = 0;
    walkgen::LoopStatus status = walkgen::LoopStatus::ok;
    std::string key_this_tick, stop_message;
    long frames = 0;
    bool reached = false;
    double target_distance = scene ? (walkgen::true_com(robot) - scene->target).norm() : 0.0;
    while (!quit && g_stop == 0 && robot.output().time - t0 < max_time) {
      // Keys until the wall clock has caught up with the simulation.
      const double sim = robot.output().time - t0;
      do {
        const double wait = sim / speed - wall();
        parse_keys(read_input(int(std::max(0.0, std::min(wait, 0.02) * 1000.0))), [&](Key k) {
          switch (k) {
            case Key::up:
              command.x() += step.x();
              break;
            case Key::down:
              command.x() -= step.x();
              break;
            case Key::left:
              command.z() += step.z();
              break;
            case Key::right:
              command.z() -= step.z();
              break;
            case Key::side_left:
              command.y() += step.y();
              break;
            case Key::side_right:
              command.y() -= step.y();
              break;
            case Key::stop:
              command.setZero();
              break;
            case Key::quit:
              quit = true;
              break;
            default:
              break;
          }
          command = command.cwiseMax(-limit).cwiseMin(limit);  // within the NMPC's limits
          for (int i = 0; i < 3; ++i) {                        // no drift from repeated ± steps
            if (std::abs(command[i]) < 1e-9) command[i] = 0.0;
          }
          key_this_tick += std::string(key_this_tick.empty() ? "" : " ") + key_name(k);
        });
      } while (!quit && g_stop == 0 && wall() < sim / speed);
      if (quit) break;
      const double t = robot.output().time - t0;
      if (scene) walkgen::move_person(*scene, t, robot, loop.mpc());  // the person walks on
#ifdef WALKGEN_TELEOP_DEMONSTRATIONS
      if (recorder) {  // what the robot sees now, and the command it executes from now
        const walkgen::StereoImages& images = robot.render_cameras();
        if (images.status != walkgen::RenderStatus::ok) {
          stop_message = "cannot render the chest cameras: " + images.message;
          break;
        }
        const cv::Mat left(images.left.height, images.left.width, CV_8UC3,
                           const_cast<std::uint8_t*>(images.left.rgb.data()));
        const cv::Mat right(images.right.height, images.right.width, CV_8UC3,
                            const_cast<std::uint8_t*>(images.right.rgb.data()));
        try {
          recorder->record(t, images.left, stereo->compute(left, right).disparity, command);
        } catch (const walkgen::invalid_argument& e) {
          stop_message = std::string("recording failed: ") + e.what();
          break;
        }
        frames = recorder->samples();
      }
#endif
      const walkgen::CommandStatus accepted = loop.set_command(command);
      if (accepted != walkgen::CommandStatus::accepted) {  // cannot be: clamped to 95 % above
        stop_message = std::string("the NMPC did not take the command as given: ") +
                       walkgen::to_string(accepted);
        break;
      }
      const walkgen::LoopTick& tick = loop.tick();
      status = tick.status;
      for (const auto& s : loop.samples()) {
        if (!s.zmp.valid) continue;
        zmp_sum += std::hypot(s.zmp.zmp_W.x() - s.plan.zmp_x, s.zmp.zmp_W.y() - s.plan.zmp_y);
        ++zmp_n;
      }
      csv << wall() << ',' << robot.output().time - t0 << ',' << command.x() << ',' << command.y()
          << ',' << command.z() << ',' << key_this_tick << '\n';
      ++rows;
      key_this_tick.clear();
      const auto& st = loop.mpc().state();
      const walkgen::PlanarPose pose = walkgen::walking_pose(st);
      if (scene) {
        target_distance = (walkgen::true_com(robot) - scene->target).norm();
        reached = target_distance <= kRoomReachDistance;
      }
      // The screen: home, clear, then the panel.
      std::printf(
          "\x1b[H\x1b[2J"
          "walkgen teleop: %s in MuJoCo (NMPC + IK closed loop), %.0fx real time\r\n"
          "  Up/w Down/s: v_x +-%.3f m/s   Left/a Right/d: omega +-%.3f rad/s\r\n"
          "  z/c: v_y +-%.4f m/s   space: stop   q: quit\r\n\r\n"
          "command   v_x %+.3f m/s   v_y %+.4f m/s   omega %+.3f rad/s   (limits %.3f %.4f "
          "%.3f)\r\n"
          "time      %.1f s simulated, %.1f s wall\r\n"
          "robot     x %+.3f m   y %+.3f m   heading %+.3f rad   base height %.3f m\r\n"
          "balance   NMPC vs measured ZMP %.2f cm (mean)   status %s   QP %s\r\n"
          "recorded  %ld ticks to %s\r\n",
          description.name.c_str(), speed, step.x(), step.z(), step.y(), command.x(), command.y(),
          command.z(), limit.x(), limit.y(), limit.z(), robot.output().time - t0, wall(), pose.x,
          pose.y, pose.yaw, robot.output().base_height,
          zmp_n > 0 ? 100.0 * zmp_sum / double(zmp_n) : 0.0, walkgen::to_string(status),
          walkgen::to_string(tick.mpc), rows, record.c_str());
      if (scene) {
        std::printf("room      %s, seed %u: target %.2f m from the CoM (reached within %.1f m)\r\n",
                    walkgen::to_string(scene->task), seed, target_distance, kRoomReachDistance);
      }
      if (!demonstrations.empty()) {
        std::printf("demos     %ld frames to %s/index.txt\r\n", frames, demonstrations.c_str());
      }
      std::fflush(stdout);
      if (status == walkgen::LoopStatus::fallen || status == walkgen::LoopStatus::diverged) break;
      if (reached) break;
    }
    if (reached) {
      std::printf("\r\nteleop: reached the target: the true CoM is %.2f m from it\r\n",
                  target_distance);
    } else if (!stop_message.empty()) {
      std::fprintf(stderr, "\r\nteleop: %s\r\n", stop_message.c_str());
    }
    if (!demonstrations.empty()) {
      std::printf("teleop: %ld demonstration frames in %s/index.txt\r\n", frames,
                  demonstrations.c_str());
    }
    csv.flush();
    const auto& st = loop.mpc().state();
    const walkgen::PlanarPose pose = walkgen::walking_pose(st);
    const double walked = std::hypot(pose.x - start_pose.x, pose.y - start_pose.y);
    std::printf("\r\nteleop: %s after %.1f s simulated; %.2f m from the start; %ld ticks in %s\r\n",
                walkgen::to_string(status), robot.output().time - t0, walked, rows, record.c_str());
    if (!summary_path.empty()) {
      std::ofstream summary(summary_path);
      summary << "status=" << walkgen::to_string(status)
              << "\nsim_time=" << robot.output().time - t0 << "\nx=" << pose.x << "\ny=" << pose.y
              << "\nheading=" << pose.yaw << "\nrows=" << rows << "\n";
      if (scene) {
        summary << "room=" << walkgen::to_string(scene->task) << "\nseed=" << seed
                << "\ntarget_distance=" << target_distance << "\nreached=" << (reached ? 1 : 0)
                << "\nframes=" << frames << "\n";
      }
    }
    const bool ok = status == walkgen::LoopStatus::ok || status == walkgen::LoopStatus::qp_failed ||
                    status == walkgen::LoopStatus::not_converged ||
                    status == walkgen::LoopStatus::relaxed;
    return ok && csv.good() && stop_message.empty() ? 0 : 1;
  };
  try {
    return walkgen::with_robot_ik(description, walk);
  } catch (const walkgen::invalid_argument& e) {
    std::fprintf(stderr, "teleop: --robot %s: %s\n", robot_name.c_str(), e.what());
    return 2;
  }
}
