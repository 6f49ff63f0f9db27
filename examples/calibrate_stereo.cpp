// Stereo calibration of a folder of chessboard pairs (thesis §3.2, §10.1, Tables 10.1–10.2): the
// command-line tool. Pairs are the files left<S>.<ext> and right<S>.<ext> of the folder with the
// same suffix <S> (ext: jpg, jpeg, png, bmp, tif, tiff), in name order.
//
//   calibrate_stereo FOLDER [--board 9x6] [--square 0.025] [--out stereo_calibration.yml]
//                    [--skip-missing] [--rectified PNG]
//
//   FOLDER           the folder of left*/right* pairs (must exist)
//   --board CxR      inner corners of the chessboard, columns x rows (default 9x6)
//   --square S       the side of a square [m] (default 0.025); sets the unit of T and of depth
//   --out FILE       the calibration as YAML (default stereo_calibration.yml)
//   --skip-missing   leave out pairs where a board is not found instead of stopping
//   --rectified PNG  also write the first pair raw (top) and rectified (bottom) with horizontal
//                    lines (figure 10.3; docs/img/depth_rectified.png is a copy)
//
// Prints each pair's re-projection errors, the per-camera and stereo RMS, the mean epipolar
// error, the intrinsics, the baseline and the rectified projections, and writes the calibration
// as YAML (walkgen::save_stereo_calibration; walkgen::load_stereo_calibration reads it back). The
// file is replaced atomically and ends with the marker `complete: 1` (docs/depth.md): an
// interrupted run leaves the previous calibration, never a truncated one.
// --help lists the options. Exit code 0; 1 with the reason on stderr (unreadable images, no
// board, an unwritable file); 2 on a bad command line (one line on stderr).
#include <algorithm>
#include <cctype>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <map>
#include <string>
#include <vector>
#include <walkgen/opencv/stereo_calibration.hpp>

#include "common/cli.hpp"

namespace {

void print_matrix(const char* name, const cv::Mat& m) {
  std::printf("%s =", name);
  for (int r = 0; r < m.rows; ++r) {
    std::printf(r == 0 ? " [" : "\n%*s  ", static_cast<int>(std::strlen(name)) + 1, "");
    for (int c = 0; c < m.cols; ++c) std::printf(" %12.5g", m.at<double>(r, c));
  }
  std::printf(" ]\n");
}

}  // namespace

int main(int argc, char** argv) {
  std::string folder_name;
  walkgen::CalibrationSettings settings;
  std::string board =
      std::to_string(settings.board.columns) + "x" + std::to_string(settings.board.rows);
  std::string out = "stereo_calibration.yml";
  std::string rectified_png;

  CLI::App app{"Calibrates a stereo pair from a folder of chessboard pairs (thesis §3.2, §10.1)",
               "calibrate_stereo"};
  walkgen_examples::cli_defaults(app);
  app.add_option("FOLDER", folder_name, "folder of the pairs left<S>.<ext> and right<S>.<ext>")
      ->required()
      ->type_name("DIR")
      ->check(CLI::ExistingDirectory.description(""));
  const CLI::Validator board_format(
      [](std::string& value) {
        int columns = 0, rows = 0;
        char rest = 0;
        if (std::sscanf(value.c_str(), "%dx%d%c", &columns, &rows, &rest) != 2 || columns < 2 ||
            rows < 2) {
          return "expects COLUMNSxROWS of inner corners (each at least 2), e.g. 9x6, got '" +
                 value + "'";
        }
        return std::string();
      },
      "");
  app.add_option("--board", board, "inner corners of the chessboard, columns x rows")
      ->type_name("COLUMNSxROWS")
      ->check(board_format);
  app.add_option("--square", settings.board.square_size,
                 "side of a chessboard square [m]; sets the unit of T and of depth")
      ->check(walkgen_examples::positive);
  app.add_option("--out", out, "output YAML file of the calibration")->type_name("FILE");
  app.add_flag("--skip-missing", settings.skip_views_without_board,
               "leave out pairs where a board is not found instead of stopping");
  app.add_option("--rectified", rectified_png,
                 "also write the first pair raw (top) and rectified (bottom) to this PNG "
                 "(figure 10.3; default: none)")
      ->type_name("PNG");
  WALKGEN_CLI_PARSE(app, argc, argv);
  if (std::sscanf(board.c_str(), "%dx%d", &settings.board.columns, &settings.board.rows) != 2) {
    return 2;  // board_format accepted it: not reached
  }
  const std::filesystem::path folder = folder_name;

  // left<S>.<ext> / right<S>.<ext> pairs.
  std::map<std::string, std::string> lefts, rights;
  for (const auto& entry : std::filesystem::directory_iterator(folder)) {
    std::string ext = entry.path().extension().string();
    std::transform(ext.begin(), ext.end(), ext.begin(),
                   [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
    if (ext != ".jpg" && ext != ".jpeg" && ext != ".png" && ext != ".bmp" && ext != ".tif" &&
        ext != ".tiff") {
      continue;
    }
    const std::string stem = entry.path().stem().string();
    if (stem.rfind("left", 0) == 0) lefts[stem.substr(4)] = entry.path().string();
    if (stem.rfind("right", 0) == 0) rights[stem.substr(5)] = entry.path().string();
  }
  std::vector<std::string> left_files, right_files, suffixes;
  for (const auto& [suffix, path] : lefts) {
    const auto r = rights.find(suffix);
    if (r == rights.end()) {
      std::fprintf(stderr, "calibrate_stereo: %s has no right partner, left out\n", path.c_str());
      continue;
    }
    left_files.push_back(path);
    right_files.push_back(r->second);
    suffixes.push_back(suffix);
  }
  std::printf("calibrate_stereo: %zu pairs in %s, board %dx%d inner corners, squares %.4g m\n",
              left_files.size(), folder.string().c_str(), settings.board.columns,
              settings.board.rows, settings.board.square_size);

  walkgen::StereoCalibration c;
  try {
    c = walkgen::calibrate_stereo_files(left_files, right_files, settings);
    walkgen::save_stereo_calibration(c, out);
  } catch (const walkgen::invalid_argument& e) {
    std::fprintf(stderr, "calibrate_stereo: %s\n", e.what());
    return 1;
  }

  std::printf("\npair      left RMS [px]  right RMS [px]\n");
  for (std::size_t v = 0; v < c.views_used.size(); ++v) {
    std::printf("%-8s  %13.3f  %14.3f\n",
                suffixes[static_cast<std::size_t>(c.views_used[v])].c_str(), c.left.view_rms[v],
                c.right.view_rms[v]);
  }
  std::printf("\n%zu of %zu pairs used\n", c.views_used.size(), left_files.size());
  std::printf("re-projection RMS: left %.4f px, right %.4f px, stereo %.4f px\n", c.left.rms,
              c.right.rms, c.rms);
  std::printf("mean epipolar error: %.4f px per corner (%.4f px left + right)\n",
              c.mean_epipolar_error, 2.0 * c.mean_epipolar_error);
  std::printf("baseline |T| = %.4f m\n\n", cv::norm(c.translation));
  print_matrix("K1", c.left.camera_matrix);
  print_matrix("D1", c.left.distortion);
  print_matrix("K2", c.right.camera_matrix);
  print_matrix("D2", c.right.distortion);
  print_matrix("R", c.rotation);
  print_matrix("T", c.translation);
  print_matrix("R1", c.rectification_left);
  print_matrix("P1", c.projection_left);
  print_matrix("R2", c.rectification_right);
  print_matrix("P2", c.projection_right);
  std::printf("\nwrote %s\n", out.c_str());

  if (!rectified_png.empty()) {  // figure 10.3: the first pair, raw above, rectified below
    const std::size_t first = static_cast<std::size_t>(c.views_used.front());
    const cv::Mat l = walkgen::read_image(left_files[first], cv::IMREAD_COLOR);
    const cv::Mat r = walkgen::read_image(right_files[first], cv::IMREAD_COLOR);
    cv::Mat rl, rr, raw, rectified, picture;
    walkgen::StereoRectifier(c).rectify(l, r, rl, rr);
    cv::hconcat(l, r, raw);
    cv::hconcat(rl, rr, rectified);
    for (int y = 20; y < raw.rows; y += 40) {
      cv::line(raw, {0, y}, {raw.cols, y}, cv::Scalar(255, 128, 0), 1);
      cv::line(rectified, {0, y}, {rectified.cols, y}, cv::Scalar(0, 200, 0), 1);
    }
    cv::vconcat(raw, rectified, picture);
    cv::resize(picture, picture, cv::Size(), 0.5, 0.5, cv::INTER_AREA);
    if (!cv::imwrite(rectified_png, picture)) {
      std::fprintf(stderr, "calibrate_stereo: cannot write %s\n", rectified_png.c_str());
      return 1;
    }
    std::printf("wrote %s\n", rectified_png.c_str());
  }
  return 0;
}
