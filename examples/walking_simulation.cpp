// The robot walks in MuJoCo (thesis §9.2, figures 9.4–9.7): the closed loop of figure 6.1
// (NMPC → interpolation → Ceres IK → joint targets → MuJoCo, CoM fed back by forward kinematics,
// ZMP measured by the ankle force-torque sensors) runs the four test tasks against a target
// object: straight 2 m, curved walk to a target on the left, a chair on the way, and an
// environmental scan (the target behind the robot). walkgen::go_to_target() steers in place of
// the thesis's keyboard user.
//
//   walking_simulation [TASK...] [--out DIR] [--scale S] [--video] [--no-plot]
//     TASK: straight curved obstacle scan (default: all four)
//     --scale S  shorter (S < 1) or longer tasks: distances times S
//     --video    render a frame per NMPC tick (0.4 s) from a following camera: <task>.mp4 via
//                ffmpeg (when installed) and a strip of frames <task>_frames.png
//     --no-plot  CSV only (the plots need /usr/bin/python3 with matplotlib)
//
// Writes, per task, <task>.csv (one row per 10 ms command period: time, command, planned CoM
// and ZMP, measured ZMP, true CoM and ZMP, support-polygon margin, base height) and
// <task>.png (path from above; desired vs measured ZMP; velocity-command histograms), and
// simulation_summary.csv with one line per task. Exit status 0 only when every task reached
// its target without a fall.
#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <string>
#include <vector>

#include "support/simulated_tasks.hpp"

namespace {

bool write_ppm(const std::string& path, const walkgen::CameraImage& image) {
  std::ofstream out(path, std::ios::binary);
  out << "P6\n" << image.width << ' ' << image.height << "\n255\n";
  out.write(reinterpret_cast<const char*>(image.rgb.data()), std::streamsize(image.rgb.size()));
  return out.good();
}

void write_rows(const std::string& path, const walkgen_test::TaskResult& r) {
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

}  // namespace

int main(int argc, char** argv) {
  std::string out_dir = ".";
  double scale = 1.0;
  bool video = false, plot = true;
  std::vector<std::string> names;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--out" && i + 1 < argc) {
      out_dir = argv[++i];
    } else if (a == "--scale" && i + 1 < argc) {
      scale = std::atof(argv[++i]);
    } else if (a == "--video") {
      video = true;
    } else if (a == "--no-plot") {
      plot = false;
    } else if (a == "straight" || a == "curved" || a == "obstacle" || a == "scan") {
      names.push_back(a);
    } else {
      std::fprintf(stderr,
                   "walking_simulation: unknown argument '%s'\nusage: walking_simulation "
                   "[straight|curved|obstacle|scan ...] [--out DIR] [--scale S] [--video] "
                   "[--no-plot]\n",
                   a.c_str());
      return 2;
    }
  }
  if (!(scale > 0.0 && scale <= 5.0)) {
    std::fprintf(stderr, "walking_simulation: --scale expects a factor in (0, 5]\n");
    return 2;
  }
  const bool have_ffmpeg = video && std::system("command -v ffmpeg >/dev/null 2>&1") == 0;
  if (video && !have_ffmpeg) std::printf("walking_simulation: no ffmpeg: frames and strip only\n");

  std::ofstream summary(out_dir + "/simulation_summary.csv");
  summary << "task,reached,final_distance,time,zmp_distance_mean,zmp_distance_std,"
             "zmp_inside_fraction,min_base_height,min_obstacle_distance,qp_failures,ik_failures\n";
  int failures = 0;
  for (const auto& task : walkgen_test::section_9_2_tasks(scale)) {
    if (!names.empty() && std::find(names.begin(), names.end(), task.name) == names.end()) {
      continue;
    }
    std::printf("%s: %s, target (%.2f, %.2f), up to %.0f s\n", task.name.c_str(),
                task.description.c_str(), task.target.x(), task.target.y(), task.time_limit);
    const std::string frames_dir = out_dir + "/" + task.name + "_frames";
    if (video)
      std::system(("mkdir -p '" + frames_dir + "' && rm -f '" + frames_dir + "'/*.ppm").c_str());
    int frame = 0;
    double next_report = 10.0;
    walkgen::CameraImage image;
    const auto result = walkgen_test::run_task(
        task, 2.0,
        [&](walkgen::MujocoRobot& robot, const walkgen_test::SimLoop& loop,
            const walkgen_test::TaskResult& r) {
          const double t = r.rows.empty() ? 0.0 : r.rows.back().time;
          if (t >= next_report) {  // progress every 10 s simulated
            const auto& st = loop.mpc().state();
            std::printf("  t = %5.1f s: CoM (%5.2f, %5.2f), heading %5.2f rad, %.2f m to go\n", t,
                        st.com_x[0], st.com_y[0], st.heading(),
                        (Eigen::Vector2d(st.com_x[0], st.com_y[0]) - task.target).norm());
            next_report += 10.0;
          }
          if (!video) return;
          const Eigen::Vector2d c = walkgen_test::true_com(robot);
          if (robot.render_view(Eigen::Vector3d(c.x(), c.y(), 0.3), 2.4, 30.0, -20.0, 480, 360,
                                image)) {
            char name[64];
            std::snprintf(name, sizeof(name), "/frame_%05d.ppm", frame++);
            write_ppm(frames_dir + name, image);
          }
        });
    double mean = 0.0, sd = 0.0;
    result.zmp_distance(mean, sd);
    std::printf(
        "  %s: %s after %.1f s, true CoM %.3f m from the target; measured vs NMPC ZMP %.2f ± %.2f "
        "cm; true ZMP in the support polygon in %.2f %% of %zu samples; lowest base %.3f m; "
        "QP failures %d, IK failures %d%s\n",
        task.name.c_str(), result.reached ? "reached" : "NOT reached", result.time,
        result.final_distance, 100.0 * mean, 100.0 * sd, 100.0 * result.inside_fraction(),
        result.rows.size(), result.min_base_height, result.qp_failures, result.ik_failures,
        result.message.empty() ? "" : (" — " + result.message).c_str());
    failures += !result.reached;
    write_rows(out_dir + "/" + task.name + ".csv", result);
    summary << task.name << ',' << int(result.reached) << ',' << result.final_distance << ','
            << result.time << ',' << mean << ',' << sd << ',' << result.inside_fraction() << ','
            << result.min_base_height << ','
            << (task.obstacles.empty() ? 0.0 : result.min_obstacle_distance) << ','
            << result.qp_failures << ',' << result.ik_failures << '\n';
    std::ofstream scene(out_dir + "/" + task.name + "_scene.csv");
    scene << "kind,x,y,radius,margin\ntarget," << task.target.x() << ',' << task.target.y()
          << ",0.05,0\n";
    for (const auto& o : task.obstacles) {
      scene << "obstacle," << o.x << ',' << o.y << ',' << o.radius << ',' << o.margin << '\n';
    }
    std::fflush(stdout);  // before ffmpeg and python write to the same stream
    if (video && frame > 0 && have_ffmpeg) {
      const std::string cmd = "ffmpeg -loglevel error -y -framerate 20 -i '" + frames_dir +
                              "/frame_%05d.ppm' -pix_fmt yuv420p -vcodec libx264 '" + out_dir +
                              "/" + task.name + ".mp4'";
      if (std::system(cmd.c_str()) == 0) {
        std::printf("  wrote %s/%s.mp4 (%d frames, 20 fps = 8x real time)\n", out_dir.c_str(),
                    task.name.c_str(), frame);
      }
    }
  }
  summary.close();
  std::fflush(stdout);
  if (plot) {
    const std::string cmd = "/usr/bin/python3 '" + std::string(WALKGEN_SOURCE_DIR) +
                            "/python/plot_simulation.py' '" + out_dir + "'";
    if (std::system(cmd.c_str()) != 0) {
      std::fprintf(stderr, "walking_simulation: plotting failed (%s)\n", cmd.c_str());
      return 1;
    }
  }
  std::printf("walking_simulation: %d task(s) failed; CSV and PNG in %s\n", failures,
              out_dir.c_str());
  return failures == 0 ? 0 : 1;
}
