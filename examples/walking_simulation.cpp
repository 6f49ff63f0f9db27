// The robot walks in MuJoCo (thesis §9.2, figures 9.4–9.7): the closed loop of figure 6.1
// (NMPC → interpolation → Ceres IK → joint targets → MuJoCo, CoM fed back by forward kinematics,
// ZMP measured by the ankle force-torque sensors) runs the four test tasks against a target
// object: straight 2 m, curved walk to a target on the left, a chair on the way, and an
// environmental scan (the target behind the robot). walkgen::go_to_target() steers in place of
// the thesis's keyboard user.
//
//   walking_simulation [TASK...] [--robot NAME|PATH] [--out DIR] [--scale S] [--video]
//                      [--video-width W] [--video-height H] [--fps F] [--no-plot]
//     TASK            straight curved obstacle scan (default: all four)
//     --robot R       walkgen_humanoid (default) or unitree_g1 (models/NAME/robot.yaml), or the
//                     path of a robot description file (docs/robots.md)
//     --out DIR       output folder, created if missing (default: the working directory)
//     --scale S       distances times S, in (0, 5]: shorter (S < 1) or longer tasks
//     --video         film every task from a camera that follows the robot, one frame per NMPC
//                     tick (0.4 s walked by walkgen_humanoid): <task>.mp4 (H.264, the frames piped
//                     into ffmpeg when it is on the PATH) and <task>_frames.png, six frames side by
//                     side
//     --video-width W, --video-height H   frame size [px] (default 960 x 540; at most the
//                     robot's offscreen view, MujocoRobotSettings::view_width x view_height:
//                     a larger frame is shrunk to it, with a line that says so)
//     --fps F         frame rate of the MP4 [fps] (default 25: 0.4 s walked per frame plays at
//                     10x real time)
//     --no-plot       CSV only (the plots need /usr/bin/python3 with matplotlib)
// The command line is parsed by CLI11 (examples/common/cli.hpp): --help lists every option with
// its default and exits 0; an unknown option or a bad value exits 2 with one line on stderr.
//
// Writes, per task, <task>.csv (one row per 10 ms command period: time, command, planned CoM
// and ZMP, measured ZMP, true CoM and ZMP, support-polygon margin, base height),
// <task>_scene.csv (target and obstacles) and <task>.png (python/plot_simulation.py: the path
// from above; desired vs measured ZMP; velocity-command histograms), and
// simulation_summary.csv with one line per task. The frame strip is written through OpenCV
// (cv::imwrite) when the build has walkgen::opencv; without it the six frames go to
// <task>_frames/ as PPM files and python/plot_simulation.py puts them side by side.
// Exit status 0 only when every task reached its target without a fall and every file was
// written (with --video: the video too, unless ffmpeg is not installed, which is said once);
// 1 otherwise; 2 on a bad command line.
#include <sys/wait.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <memory>
#include <string>
#include <system_error>
#include <vector>

#include "common/cli.hpp"
#include "walkgen/simulation/simulated_tasks.hpp"
#include "walkgen/yaml/robot_description_loader.hpp"
#ifdef WALKGEN_SIMULATION_OPENCV  // examples/CMakeLists.txt: with walkgen::opencv
#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#endif

namespace {

constexpr int kStripFrames = 6;
/// The camera follows the true CoM from behind on the right, looking down enough (25° with
/// MuJoCo's vertical field of view of 45°) that the frame holds floor up to its top edge: above
/// the horizon MuJoCo draws nothing (the model has no sky), which left a black band. Distance
/// and aim are walkgen's humanoid's, scaled by the robot's CoM height against its (the G1 is
/// 1.4 times its size).
constexpr double kCameraDistance = 2.0;  ///< [m] from the point 0.3 m above the CoM's ground point
constexpr double kCameraAim = 0.3;       ///< [m] that point's height
constexpr double kCameraAzimuth = 30.0;  ///< [deg]
constexpr double kCameraElevation = -25.0;  ///< [deg]

/// The film of one task: frame size and rate.
struct VideoSettings {
  int width = 960;  ///< [px]
  int height = 540;
  double fps = 25.0;
};

/// A frame kept for the strip: half the size of the video's.
struct Thumbnail {
  double time = 0.0;  ///< [s] of the walk
  int width = 0, height = 0;
  std::vector<unsigned char> rgb;
};

/// What the shell reports of a command's end: "exit status N" or "killed by signal N".
std::string describe_status(int status) {
  if (status == -1) return "could not be started";
  if (WIFEXITED(status)) return "exit status " + std::to_string(WEXITSTATUS(status));
  if (WIFSIGNALED(status)) return "killed by signal " + std::to_string(WTERMSIG(status));
  return "status " + std::to_string(status);
}

bool succeeded(int status) { return status != -1 && WIFEXITED(status) && WEXITSTATUS(status) == 0; }

/// `image` at half its size (the mean of each 2 × 2 block).
Thumbnail half_size(const walkgen::CameraImage& image, double time) {
  Thumbnail t;
  t.time = time;
  t.width = image.width / 2;
  t.height = image.height / 2;
  t.rgb.resize(std::size_t(t.width) * std::size_t(t.height) * 3);
  const std::size_t row = std::size_t(image.width) * 3;
  for (int y = 0; y < t.height; ++y) {
    for (int x = 0; x < t.width; ++x) {
      for (int c = 0; c < 3; ++c) {
        const std::size_t s = std::size_t(2 * y) * row + std::size_t(2 * x) * 3 + std::size_t(c);
        const int sum =
            image.rgb[s] + image.rgb[s + 3] + image.rgb[s + row] + image.rgb[s + row + 3];
        t.rgb[(std::size_t(y) * std::size_t(t.width) + std::size_t(x)) * 3 + std::size_t(c)] =
            static_cast<unsigned char>((sum + 2) / 4);
      }
    }
  }
  return t;
}

/// Frames for the strip without keeping them all: every `stride`-th frame up to a few dozen
/// (the stride doubles when they are too many), and always the latest one.
class StripFrames {
 public:
  void add(Thumbnail frame) {
    if (count_++ % stride_ == 0) {
      kept_.push_back(std::move(frame));
      if (kept_.size() > 4 * kStripFrames) {  // keep every other one, take half as many
        for (std::size_t i = 1; 2 * i < kept_.size(); ++i) kept_[i] = std::move(kept_[2 * i]);
        kept_.resize((kept_.size() + 1) / 2);
        stride_ *= 2;
      }
      latest_.reset();
    } else {
      latest_ = std::make_unique<Thumbnail>(std::move(frame));
    }
  }
  /// Up to kStripFrames frames, from the first to the latest, evenly spread in time.
  std::vector<const Thumbnail*> pick() const {
    std::vector<const Thumbnail*> all;
    for (const Thumbnail& t : kept_) all.push_back(&t);
    if (latest_) all.push_back(latest_.get());
    if (all.size() <= std::size_t(kStripFrames)) return all;
    std::vector<const Thumbnail*> picks;
    const double t0 = all.front()->time, t1 = all.back()->time;
    for (int i = 0; i < kStripFrames; ++i) {
      const double t = t0 + (t1 - t0) * i / (kStripFrames - 1);
      const auto nearest = std::min_element(all.begin(), all.end(), [t](auto a, auto b) {
        return std::abs(a->time - t) < std::abs(b->time - t);
      });
      if (picks.empty() || picks.back() != *nearest) picks.push_back(*nearest);
    }
    return picks;
  }

 private:
  std::vector<Thumbnail> kept_;
  std::unique_ptr<Thumbnail> latest_;
  long count_ = 0;
  long stride_ = 1;
};

#ifndef WALKGEN_SIMULATION_OPENCV
bool write_ppm(const std::string& path, const Thumbnail& image) {
  std::ofstream out(path, std::ios::binary);
  out << "P6\n" << image.width << ' ' << image.height << "\n255\n";
  out.write(reinterpret_cast<const char*>(image.rgb.data()), std::streamsize(image.rgb.size()));
  return out.good();
}
#endif

/// The strip <task>_frames.png: with OpenCV, one PNG with each frame's time above it; without,
/// the frames as <task>_frames/frame_<time>s.ppm for python/plot_simulation.py. Either way the
/// frames of an earlier run are removed from <task>_frames/.
bool write_strip(const std::string& out_dir, const std::string& task,
                 const std::vector<const Thumbnail*>& frames, std::string& written) {
  namespace fs = std::filesystem;
  const fs::path dir = fs::path(out_dir) / (task + "_frames");
  std::error_code ec;
  if (fs::is_directory(dir, ec)) {
    for (const auto& entry : fs::directory_iterator(dir, ec)) {
      if (entry.path().extension() == ".ppm") fs::remove(entry.path(), ec);
    }
    fs::remove(dir, ec);  // only when empty
  }
  if (frames.empty()) return true;
#ifdef WALKGEN_SIMULATION_OPENCV
  const int w = frames.front()->width, h = frames.front()->height, label = 34, gap = 8;
  const int n = int(frames.size());
  cv::Mat strip(label + h, n * w + (n - 1) * gap, CV_8UC3, cv::Scalar(255, 255, 255));
  for (int i = 0; i < n; ++i) {
    const cv::Mat rgb(h, w, CV_8UC3,
                      const_cast<unsigned char*>(frames[std::size_t(i)]->rgb.data()));
    cv::cvtColor(rgb, strip(cv::Rect(i * (w + gap), label, w, h)), cv::COLOR_RGB2BGR);
    char text[32];
    std::snprintf(text, sizeof(text), "t = %.1f s", frames[std::size_t(i)]->time);
    cv::putText(strip, text, cv::Point(i * (w + gap) + 6, label - 10), cv::FONT_HERSHEY_SIMPLEX,
                0.75, cv::Scalar(0, 0, 0), 2, cv::LINE_AA);
  }
  written = (fs::path(out_dir) / (task + "_frames.png")).string();
  try {
    return cv::imwrite(written, strip);
  } catch (const cv::Exception&) {
    return false;
  }
#else
  written = dir.string() + "/*.ppm";
  if (!fs::create_directories(dir, ec) && ec) return false;
  bool ok = true;
  for (const Thumbnail* frame : frames) {
    char name[48];
    std::snprintf(name, sizeof(name), "frame_%07.1fs.ppm", frame->time);
    ok = write_ppm((dir / name).string(), *frame) && ok;
  }
  return ok;
#endif
}

/// The video of one task: frames piped into ffmpeg (raw RGB on its standard input), which
/// encodes them while the robot walks.
class VideoPipe {
 public:
  VideoPipe(const std::string& mp4, const VideoSettings& v) {
    char rate[32];
    std::snprintf(rate, sizeof(rate), "%g", v.fps);
    command_ = "ffmpeg -loglevel error -y -f rawvideo -pix_fmt rgb24 -video_size " +
               std::to_string(v.width) + "x" + std::to_string(v.height) + " -framerate " + rate +
               " -i - -an -vcodec libx264 -preset veryfast -crf 20 -pix_fmt yuv420p "
               "-movflags +faststart " +
               walkgen_examples::shell_quote(mp4);
    pipe_ = popen(command_.c_str(), "w");
  }
  ~VideoPipe() {
    if (pipe_ != nullptr) pclose(pipe_);
  }
  VideoPipe(const VideoPipe&) = delete;
  VideoPipe& operator=(const VideoPipe&) = delete;

  /// Sends a frame; false once ffmpeg stopped reading (finish() then says why).
  bool write(const walkgen::CameraImage& image) {
    if (pipe_ == nullptr || broken_) return false;
    broken_ = std::fwrite(image.rgb.data(), 1, image.rgb.size(), pipe_) != image.rgb.size();
    frames_ += !broken_;
    return !broken_;
  }
  /// Closes the pipe and waits for ffmpeg; "" when it wrote the video, else one line that names
  /// the command and how it ended.
  std::string finish() {
    const int status = pipe_ == nullptr ? -1 : pclose(pipe_);
    pipe_ = nullptr;
    if (succeeded(status) && !broken_) return "";
    return "ffmpeg failed (" + describe_status(status) +
           (broken_ ? ", stopped reading frames" : "") + "): " + command_;
  }
  int frames() const { return frames_; }

 private:
  std::string command_;
  std::FILE* pipe_ = nullptr;
  bool broken_ = false;
  int frames_ = 0;
};

void write_rows(const std::string& path, const walkgen::TaskResult& r) {
  std::ofstream csv(path);
  csv << "time,v_x,v_y,omega,com_plan_x,com_plan_y,zmp_plan_x,zmp_plan_y,zmp_measured_x,"
         "zmp_measured_y,zmp_true_x,zmp_true_y,com_true_x,com_true_y,support_margin,"
         "base_height,zmp_valid\n";
  csv.precision(6);
  for (const auto& w : r.rows) {
    csv << w.time << ',' << w.command.x() << ',' << w.command.y() << ',' << w.command.z() << ','
        << w.com_plan.x() << ',' << w.com_plan.y() << ',' << w.zmp_plan.x() << ',' << w.zmp_plan.y()
        << ',' << w.zmp_measured.x() << ',' << w.zmp_measured.y() << ',' << w.zmp_true.x() << ','
        << w.zmp_true.y() << ',' << w.com_true.x() << ',' << w.com_true.y() << ','
        << w.support_margin << ',' << w.base_height << ',' << int(w.zmp_valid) << '\n';
  }
}

/// CLI11 validator: an even number (H.264 in yuv420p halves both sides for its colours).
CLI::Validator even() {
  return CLI::Validator(
      [](std::string& s) -> std::string {
        int v = 0;
        if (CLI::detail::lexical_cast(s, v) && v % 2 == 0) return {};
        return "expected an even number of pixels, got '" + s + "'";
      },
      "EVEN");
}

}  // namespace

int main(int argc, char** argv) {
  std::string out_dir = ".";
  std::string robot_name = "walkgen_humanoid";
  double scale = 1.0;
  bool video = false, no_plot = false;
  VideoSettings film;
  std::vector<std::string> names;
  CLI::App app{
      "A robot walks the test tasks of thesis §9.2 in MuJoCo, closed loop (figure 6.1): CSV, "
      "plots, videos",
      "walking_simulation"};
  walkgen_examples::cli_defaults(app);
  app.add_option("TASK", names,
                 "tasks to walk: straight 2 m, curved (target ahead left), obstacle (a chair on "
                 "the way), scan (target behind); default: all four")
      ->check(CLI::IsMember({"straight", "curved", "obstacle", "scan"}))
      ->default_str("");
  app.add_option("--robot", robot_name,
                 "the robot: walkgen_humanoid or unitree_g1 (models/NAME/robot.yaml), or the "
                 "path of a robot description file (docs/robots.md)");
  app.add_option("--out", out_dir,
                 "output folder for <task>.csv, .png, .mp4, <task>_frames.png and "
                 "simulation_summary.csv (created if missing)");
  app.add_option("--scale", scale,
                 "the tasks' distances times this factor, in (0, 5]: shorter (< 1) or longer")
      ->check(CLI::Validator(
          [](std::string& v) -> std::string {
            double x = 0.0;
            if (CLI::detail::lexical_cast(v, x) && x > 0.0 && x <= 5.0) return {};
            return "expected a factor in (0, 5], got '" + v + "'";
          },
          "in (0 - 5]"));
  app.add_flag("--video", video,
               "film each task from a camera following the robot, one frame per NMPC tick (0.4 "
               "s walked): <task>.mp4 (needs ffmpeg) and the strip <task>_frames.png");
  app.add_option("--video-width", film.width, "frame width of --video [px], even")
      ->transform(walkgen_examples::decimal_at_least<int>(64))
      ->check(CLI::Range(64, 1920))
      ->check(even());
  app.add_option("--video-height", film.height, "frame height of --video [px], even")
      ->transform(walkgen_examples::decimal_at_least<int>(64))
      ->check(CLI::Range(64, 1080))
      ->check(even());
  app.add_option("--fps", film.fps,
                 "frame rate of <task>.mp4 [fps]; a frame is one NMPC tick (walkgen_humanoid: 0.4 "
                 "s), so 25 fps plays at 10x "
                 "real time")
      ->check(CLI::Range(1.0, 60.0));
  app.add_flag("--no-plot", no_plot,
               "CSV only, no <task>.png (plotting needs /usr/bin/python3 with matplotlib)");
  WALKGEN_CLI_PARSE(app, argc, argv);

  walkgen::RobotDescription robot;
  try {
    robot = walkgen::find_robot_description(robot_name);
  } catch (const walkgen::invalid_argument& e) {
    std::fprintf(stderr, "walking_simulation: --robot: %s\n", e.what());
    return 2;
  }
  std::error_code ec;
  std::filesystem::create_directories(out_dir, ec);
  if (!std::filesystem::is_directory(out_dir)) {
    std::fprintf(stderr, "walking_simulation: cannot create the output folder %s\n",
                 out_dir.c_str());
    return 1;
  }
  // The robot's offscreen buffer bounds the frame size (MujocoRobotSettings::view_width and
  // view_height, which walkgen::task_robot_settings sets for every task).
  const walkgen::MujocoRobotSettings view = walkgen::task_robot_settings({}, robot);
  if (video && (film.width > view.view_width || film.height > view.view_height)) {
    const double shrink =
        std::min(double(view.view_width) / film.width, double(view.view_height) / film.height);
    const int w = 2 * int(film.width * shrink / 2), h = 2 * int(film.height * shrink / 2);
    std::printf(
        "walking_simulation: the robot renders at most %d x %d px "
        "(MujocoRobotSettings::view_width/view_height of "
        "walkgen::task_robot_settings): filming %d x %d px instead of %d x %d\n",
        view.view_width, view.view_height, w, h, film.width, film.height);
    film.width = w;
    film.height = h;
  }
  const bool have_ffmpeg = video && std::system("command -v ffmpeg >/dev/null 2>&1") == 0;
  if (video && !have_ffmpeg) {
    std::printf("walking_simulation: ffmpeg is not on the PATH: no videos, frame strips only\n");
  }
  if (video) std::signal(SIGPIPE, SIG_IGN);  // a failed ffmpeg: a write error, not our end

  std::ofstream summary(out_dir + "/simulation_summary.csv");
  summary << "task,reached,final_distance,time,zmp_distance_mean,zmp_distance_std,"
             "zmp_inside_fraction,min_base_height,min_obstacle_distance,qp_failures,ik_failures,"
             "fallen,mean_speed\n";
  int failures = 0;
  bool files_ok = true;
  for (const auto& task : walkgen::section_9_2_tasks(scale)) {
    if (!names.empty() && std::find(names.begin(), names.end(), task.name) == names.end()) {
      continue;
    }
    std::printf("%s (%s): %s, target (%.2f, %.2f), up to %.0f s\n", task.name.c_str(),
                robot.name.c_str(), task.description.c_str(), task.target.x(), task.target.y(),
                task.time_limit);
    std::fflush(stdout);
    std::unique_ptr<VideoPipe> pipe;  // ffmpeg, started at the first frame
    StripFrames strip;
    bool filming = video;
    int frames = 0;
    double render_seconds = 0.0, pipe_seconds = 0.0;  // wall time of the frames [s]
    double next_report = 10.0;
    walkgen::CameraImage image;
    const double size = robot.walking.com_z / walkgen::walkgen_humanoid_description().walking.com_z;
    walkgen::TaskResult result;
    try {
      result = walkgen::run_task(
          task, robot, 2.0,
          [&](walkgen::MujocoRobot& sim, const walkgen::WalkingState<double>& st,
              const walkgen::TaskResult& r) {
            const double t = r.rows.empty() ? 0.0 : r.rows.back().time;
            if (t >= next_report) {  // progress every 10 s simulated
              std::printf("  t = %5.1f s: CoM (%5.2f, %5.2f), heading %5.2f rad, %.2f m to go\n", t,
                          st.com_x[0], st.com_y[0], st.heading(),
                          (Eigen::Vector2d(st.com_x[0], st.com_y[0]) - task.target).norm());
              std::fflush(stdout);
              next_report += 10.0;
            }
            if (!filming) return;
            using Clock = std::chrono::steady_clock;
            const auto start = Clock::now();
            const Eigen::Vector2d c = walkgen::true_com(sim);
            if (!sim.render_view(Eigen::Vector3d(c.x(), c.y(), kCameraAim * size),
                                 kCameraDistance * size, kCameraAzimuth, kCameraElevation,
                                 film.width, film.height, image)) {
              std::printf("  no video: %s\n", sim.render_cameras().message.c_str());
              filming = false;
              return;
            }
            strip.add(half_size(image, t));
            const auto rendered = Clock::now();
            if (have_ffmpeg && !pipe) {
              std::fflush(stdout);  // before ffmpeg writes to the same streams
              pipe = std::make_unique<VideoPipe>(out_dir + "/" + task.name + ".mp4", film);
            }
            if (pipe) pipe->write(image);
            ++frames;
            render_seconds += std::chrono::duration<double>(rendered - start).count();
            pipe_seconds += std::chrono::duration<double>(Clock::now() - rendered).count();
          });
    } catch (const walkgen::invalid_argument& e) {  // the robot's models cannot be loaded
      std::fprintf(stderr, "walking_simulation: --robot %s: %s\n", robot_name.c_str(), e.what());
      return 1;
    }
    double mean = 0.0, sd = 0.0;
    result.zmp_distance(mean, sd);
    std::printf(
        "  %s: %s after %.1f s, true CoM %.3f m from the target; measured vs NMPC ZMP %.2f ± %.2f "
        "cm; true ZMP in the support polygon in %.2f %% of %zu samples; lowest base %.3f m; "
        "mean speed %.3f m/s; QP failures %d, IK failures %d%s\n",
        task.name.c_str(), result.reached ? "reached" : "NOT reached", result.time,
        result.final_distance, 100.0 * mean, 100.0 * sd, 100.0 * result.inside_fraction(),
        result.rows.size(), result.min_base_height, result.mean_speed(), result.qp_failures,
        result.ik_failures, result.message.empty() ? "" : (" — " + result.message).c_str());
    failures += !result.reached;
    write_rows(out_dir + "/" + task.name + ".csv", result);
    summary << task.name << ',' << int(result.reached) << ',' << result.final_distance << ','
            << result.time << ',' << mean << ',' << sd << ',' << result.inside_fraction() << ','
            << result.min_base_height << ','
            << (task.obstacles.empty() ? 0.0 : result.min_obstacle_distance) << ','
            << result.qp_failures << ',' << result.ik_failures << ',' << int(result.fallen()) << ','
            << result.mean_speed() << '\n';
    std::ofstream scene(out_dir + "/" + task.name + "_scene.csv");
    scene << "kind,x,y,radius,margin\ntarget," << task.target.x() << ',' << task.target.y()
          << ",0.05,0\n";
    for (const auto& o : task.obstacles) {
      scene << "obstacle," << o.x << ',' << o.y << ',' << o.radius << ',' << o.margin << '\n';
    }
    if (!video) continue;
    if (frames > 0) {
      std::printf("  filmed %d frames of %d x %d px: %.0f ms each to render", frames, film.width,
                  film.height, 1000.0 * render_seconds / frames);
      if (pipe) std::printf(", %.0f ms to hand to ffmpeg", 1000.0 * pipe_seconds / frames);
      std::printf("\n");
    }
    std::string strip_path;
    if (!write_strip(out_dir, task.name, strip.pick(), strip_path)) {
      std::fprintf(stderr, "walking_simulation: cannot write the frame strip %s\n",
                   strip_path.c_str());
      files_ok = false;
    } else if (!strip_path.empty()) {
      std::printf("  wrote %s\n", strip_path.c_str());
    }
    std::fflush(stdout);
    if (pipe) {
      const int sent = pipe->frames();
      const std::string error = pipe->finish();
      if (!error.empty()) {
        std::fprintf(stderr, "walking_simulation: %s\n", error.c_str());
        files_ok = false;
      } else if (sent > 0) {
        std::printf("  wrote %s/%s.mp4 (%d frames, %g fps = %gx real time)\n", out_dir.c_str(),
                    task.name.c_str(), sent, film.fps, film.fps * robot.walking.t);
      }
    }
  }
  summary.close();
  std::fflush(stdout);
  if (!no_plot) {
    const std::string cmd = walkgen_examples::python_command("plot_simulation.py", out_dir);
    const int status = std::system(cmd.c_str());
    if (!succeeded(status)) {
      std::fprintf(stderr, "walking_simulation: plotting failed (%s): %s\n",
                   describe_status(status).c_str(), cmd.c_str());
      return 1;
    }
  }
  std::printf("walking_simulation: %d task(s) failed%s; CSV and PNG in %s\n", failures,
              files_ok ? "" : ", and files could not be written (see above)", out_dir.c_str());
  return failures == 0 && files_ok ? 0 : 1;
}
