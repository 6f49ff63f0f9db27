#pragma once
/// @file
/// Mono and stereo camera calibration from chessboard images, rectification, and their YAML files
/// (thesis §3.2, eq. 3.9–3.15; §10.1, Tables 10.1–10.2). OpenCV adapter: target walkgen::opencv
/// (Debian: libopencv-dev, libopencv-contrib-dev); the core never includes this header.
///
/// Camera model (eq. 3.9–3.11, with the erratum of docs/design.md §5: the y row of eq. 3.11 scales
/// y_{c,d}, not x_{c,d}): K = [f_x 0 c_x; 0 f_y c_y; 0 0 1] and OpenCV's distortion vector
/// (k₁, k₂, p₁, p₂, k₃[, k₄, k₅, k₆]). Pixel coordinates are OpenCV's: (0, 0) is the centre of the
/// top-left pixel. Lengths (square size, baseline T) are in the unit of the square size, metres
/// by default.
///
/// Calibration minimises the re-projection error of the chessboard corners (eq. 3.12–3.14); the
/// RMS over all corners is reported as `rms` [px]. The stereo calibration adds the relative pose
/// (R, T) of the right camera, the essential and fundamental matrices (eq. 3.15), the mean
/// distance of each corner to the epipolar line of its partner [px], and the rectification
/// transforms R₁, R₂ and projection matrices P₁, P₂ (Table 10.2) with the disparity-to-depth
/// matrix Q that walkgen::StereoDepth uses.
///
/// Errors (convention 10): a missing or unreadable image, images of different sizes, a board
/// that is not found throw walkgen::invalid_argument naming the image. A calibration file that
/// cannot be read, is truncated, lacks a key or holds a value out of range (a matrix of another
/// shape, a non-finite entry, an image side outside 1..100000 px) throws naming the file and the
/// key; OpenCV's own exceptions never escape the loader. Calibration files are replaced
/// atomically (walkgen/core/atomic_file.hpp): an interrupted save leaves the previous file.

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <initializer_list>
#include <iterator>
#include <opencv2/calib3d.hpp>
#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <string>
#include <utility>
#include <vector>

#include "walkgen/core/atomic_file.hpp"
#include "walkgen/core/exceptions.hpp"

namespace walkgen {

/// The chessboard and how its corners are found and refined.
struct ChessboardSettings {
  int columns = 9;             ///< inner corners along a row (OpenCV's sample board: 9)
  int rows = 6;                ///< inner corners along a column (OpenCV's sample board: 6)
  double square_size = 0.025;  ///< a in eq. 3.12 [m]; sets the unit of T and of depth
  /// Half side of cv::cornerSubPix's search window [px] (11: a 23 × 23 window). Smaller for
  /// small or low-resolution boards.
  int subpixel_half_window = 11;
};

/// Which camera parameters the calibration estimates.
struct CalibrationSettings {
  ChessboardSettings board;
  /// f_x = f_y (square pixels): one focal length to estimate, more robust with few views.
  bool fix_aspect_ratio = true;
  /// Stereo only: both cameras share one focal length (identical lenses).
  bool same_focal_length = true;
  /// Stereo only: p₁ = p₂ = 0 (eq. 3.10–3.11 without the tangential terms).
  bool zero_tangent_distortion = true;
  /// Stereo only: OpenCV's rational model with k₃..k₅ fixed at 0 (k₁, k₂, k₆ estimated).
  bool rational_model = true;
  /// Rectification's free scaling (cv::stereoRectify's alpha): 0 keeps only valid pixels, 1 keeps
  /// every source pixel, -1 OpenCV's default.
  double rectify_alpha = -1.0;
  /// A view without a detected board: false throws (naming the image), true leaves it out (the
  /// result lists the views used).
  bool skip_views_without_board = false;
};

/// Checks the board (find_chessboard() and the calibrations call this).
/// @throws walkgen::invalid_argument naming the first bad field.
inline void validate(const ChessboardSettings& b) {
  check_argument(b.columns >= 2, "ChessboardSettings.columns", "at least 2 inner corners",
                 b.columns);
  check_argument(b.rows >= 2, "ChessboardSettings.rows", "at least 2 inner corners", b.rows);
  check_positive("ChessboardSettings.square_size", b.square_size);
  check_argument(b.subpixel_half_window >= 1, "ChessboardSettings.subpixel_half_window",
                 "a half window >= 1 px", b.subpixel_half_window);
}

/// Checks a calibration's settings, its board included (the calibrations call this).
/// @throws walkgen::invalid_argument naming the first bad field.
inline void validate(const CalibrationSettings& s) {
  validate(s.board);
  check_argument(s.rectify_alpha == -1.0 || (s.rectify_alpha >= 0.0 && s.rectify_alpha <= 1.0),
                 "CalibrationSettings.rectify_alpha", "-1 (OpenCV's default) or a value in [0, 1]",
                 s.rectify_alpha);
}

/// Whether a calibration's numbers can be used (convention 10c: a numerical outcome, not thrown).
enum class CalibrationStatus : std::uint8_t {
  ok,          ///< every matrix and error is finite
  non_finite,  ///< OpenCV returned NaN or inf (degenerate views): do not use the result
};

/// "ok" or "non_finite", e.g. for logs; "unknown" for a value out of range.
constexpr const char* to_string(CalibrationStatus status) noexcept {
  switch (status) {
    case CalibrationStatus::ok:
      return "ok";
    case CalibrationStatus::non_finite:
      return "non_finite";
  }
  return "unknown";
}

/// One camera's intrinsics (Table 10.1) and how well they fit.
struct MonoCalibration {
  CalibrationStatus status = CalibrationStatus::ok;
  const char* message = "";  ///< which numbers are not finite; empty when ok
  cv::Size image_size;
  cv::Mat camera_matrix;  ///< K (3 × 3, CV_64F), eq. 3.9
  cv::Mat distortion;  ///< (k₁, k₂, p₁, p₂, k₃[, …]) (1 × n, CV_64F), eq. 3.10–3.11
  double rms = 0.0;    ///< RMS re-projection error over all corners [px]
  std::vector<double> view_rms;  ///< RMS re-projection error of each view used [px]
  std::vector<int> views_used;   ///< indices of the input views that were used
};

/// A calibrated and rectified stereo pair (Tables 10.1–10.2).
struct StereoCalibration {
  CalibrationStatus status = CalibrationStatus::ok;  ///< ok: both cameras' and the pair's too
  const char* message = "";  ///< which numbers are not finite; empty when ok
  MonoCalibration left;
  MonoCalibration right;
  cv::Mat rotation;     ///< R (3 × 3): right camera from left camera
  cv::Mat translation;  ///< T (3 × 1) [square-size unit]: right camera from left camera
  cv::Mat essential;    ///< E (3 × 3)
  cv::Mat fundamental;  ///< F (3 × 3), eq. 3.15: x_rightᵀ F x_left = 0
  cv::Mat rectification_left, rectification_right;  ///< R₁, R₂ (3 × 3), Table 10.2
  cv::Mat projection_left, projection_right;        ///< P₁, P₂ (3 × 4), Table 10.2
  cv::Mat disparity_to_depth;                       ///< Q (4 × 4): (u, v, d, 1) → (X, Y, Z, W)
  double rms = 0.0;                                 ///< stereo RMS re-projection error [px]
  /// Mean distance of an undistorted corner to the epipolar line of its partner [px], over
  /// both images' corners. (OpenCV's stereo_calib sample adds the left and right distances of a
  /// pair and reports twice this.)
  double mean_epipolar_error = 0.0;
  std::vector<int> views_used;  ///< indices of the input pairs that were used
};

/// Reads an image (cv::imread flags, default grey).
/// @throws walkgen::invalid_argument when the file is missing, unreadable or empty.
inline cv::Mat read_image(const std::string& path, int flags = cv::IMREAD_GRAYSCALE) {
  // Checked first: OpenCV logs a warning to stderr for a file it cannot open.
  check_argument(std::filesystem::is_regular_file(path), "walkgen::read_image",
                 "a readable image file", "'" + path + "' (missing)");
  cv::Mat image = cv::imread(path, flags);
  check_argument(!image.empty(), "walkgen::read_image", "a readable image file",
                 "'" + path + "' (missing, unreadable or empty)");
  return image;
}

namespace detail {

inline cv::Mat to_grey(const cv::Mat& image) {
  if (image.channels() == 1) return image;
  cv::Mat grey;
  cv::cvtColor(image, grey, image.channels() == 4 ? cv::COLOR_BGRA2GRAY : cv::COLOR_BGR2GRAY);
  return grey;
}

inline std::string size_string(const cv::Size& s) {
  return std::to_string(s.width) + "x" + std::to_string(s.height);
}

inline std::string view_name(const std::vector<std::string>& names, std::size_t i) {
  return i < names.size() ? "'" + names[i] + "'" : "view " + std::to_string(i);
}

/// The board's corners in its own frame (eq. 3.12): (w a, h a, 0).
inline std::vector<cv::Point3f> board_points(const ChessboardSettings& b) {
  std::vector<cv::Point3f> points;
  points.reserve(static_cast<std::size_t>(b.columns * b.rows));
  for (int h = 0; h < b.rows; ++h) {
    for (int w = 0; w < b.columns; ++w) {
      points.emplace_back(static_cast<float>(w * b.square_size),
                          static_cast<float>(h * b.square_size), 0.0f);
    }
  }
  return points;
}

/// Sum of squared re-projection errors and corner count of one view.
inline std::pair<double, std::size_t> reprojection(const std::vector<cv::Point3f>& object,
                                                   const std::vector<cv::Point2f>& image,
                                                   const cv::Mat& rvec, const cv::Mat& tvec,
                                                   const cv::Mat& k, const cv::Mat& d) {
  std::vector<cv::Point2f> projected;
  cv::projectPoints(object, rvec, tvec, k, d, projected);
  double sum = 0.0;
  for (std::size_t i = 0; i < image.size(); ++i) {
    const cv::Point2f e = image[i] - projected[i];
    sum += static_cast<double>(e.x) * e.x + static_cast<double>(e.y) * e.y;
  }
  return {sum, image.size()};
}

/// True when every entry of every matrix is finite (an empty matrix is).
inline bool all_finite(std::initializer_list<cv::Mat> matrices) {
  for (const cv::Mat& m : matrices) {
    if (!cv::checkRange(m)) return false;
  }
  return true;
}

/// A camera's status: ok when its intrinsics and errors are finite.
inline void set_status(MonoCalibration& c) {
  bool finite = all_finite({c.camera_matrix, c.distortion}) && std::isfinite(c.rms);
  for (double e : c.view_rms) finite = finite && std::isfinite(e);
  c.status = finite ? CalibrationStatus::ok : CalibrationStatus::non_finite;
  c.message = finite ? "" : "OpenCV returned a non-finite camera matrix, distortion or error";
}

/// A view without the board: an error naming `where`, unless such views may be skipped.
inline void check_board_found(bool skip_allowed, const ChessboardSettings& board,
                              const std::string& where) {
  check_argument(skip_allowed, where.c_str(),
                 "a visible " + std::to_string(board.columns) + "x" + std::to_string(board.rows) +
                     " inner-corner chessboard",
                 "none found",
                 "check the board size in ChessboardSettings, or set skip_views_without_board");
}

}  // namespace detail

/// Finds the chessboard's inner corners with sub-pixel accuracy (the corner detection of §3.2).
/// @param image grey or BGR image.
/// @param found false when the board is not in the image (corners then empty).
/// @throws walkgen::invalid_argument when the image is empty or the settings are invalid.
inline std::vector<cv::Point2f> find_chessboard(const cv::Mat& image,
                                                const ChessboardSettings& board, bool& found) {
  validate(board);
  check_argument(!image.empty(), "walkgen::find_chessboard: image", "a non-empty image",
                 "an empty one");
  const cv::Mat grey = detail::to_grey(image);
  std::vector<cv::Point2f> corners;
  const cv::Size pattern(board.columns, board.rows);
  found = cv::findChessboardCorners(
      grey, pattern, corners,
      cv::CALIB_CB_ADAPTIVE_THRESH | cv::CALIB_CB_NORMALIZE_IMAGE | cv::CALIB_CB_FAST_CHECK);
  if (!found) {
    corners.clear();
    return corners;
  }
  const int w = board.subpixel_half_window;
  cv::cornerSubPix(grey, corners, cv::Size(w, w), cv::Size(-1, -1),
                   cv::TermCriteria(cv::TermCriteria::COUNT + cv::TermCriteria::EPS, 30, 0.01));
  return corners;
}

/// Calibrates one camera from views of the chessboard (eq. 3.9–3.14): K with f_x = f_y when
/// fix_aspect_ratio, and (k₁, k₂, p₁, p₂, k₃).
/// @param names optional names of the views (file names), used in error messages.
/// @return the calibration; status non_finite (and a message) when OpenCV's fit is not finite.
/// @throws walkgen::invalid_argument for invalid settings (validate()), empty images, images of
///   different sizes, a view without the board (unless skip_views_without_board) or fewer than
///   3 usable views.
inline MonoCalibration calibrate_camera(const std::vector<cv::Mat>& images,
                                        const CalibrationSettings& settings = {},
                                        const std::vector<std::string>& names = {}) {
  validate(settings);
  check_argument(images.size() >= 3, "walkgen::calibrate_camera: images", "at least 3 views",
                 images.size());
  MonoCalibration result;
  std::vector<std::vector<cv::Point2f>> image_points;
  const std::vector<cv::Point3f> board = detail::board_points(settings.board);
  for (std::size_t i = 0; i < images.size(); ++i) {
    const std::string where = "walkgen::calibrate_camera: " + detail::view_name(names, i);
    check_argument(!images[i].empty(), where.c_str(), "a non-empty image", "an empty one");
    if (i == 0) result.image_size = images[i].size();
    check_argument(images[i].size() == result.image_size, where.c_str(),
                   "the size of the first view, " + detail::size_string(result.image_size),
                   detail::size_string(images[i].size()));
    bool found = false;
    std::vector<cv::Point2f> corners = find_chessboard(images[i], settings.board, found);
    if (!found) {
      detail::check_board_found(settings.skip_views_without_board, settings.board, where);
      continue;
    }
    image_points.push_back(std::move(corners));
    result.views_used.push_back(static_cast<int>(i));
  }
  check_argument(image_points.size() >= 3, "walkgen::calibrate_camera: views with a board",
                 "at least 3", image_points.size());
  const std::vector<std::vector<cv::Point3f>> object_points(image_points.size(), board);
  result.camera_matrix = cv::Mat::eye(3, 3, CV_64F);
  int flags = 0;
  if (settings.fix_aspect_ratio) flags |= cv::CALIB_FIX_ASPECT_RATIO;
  std::vector<cv::Mat> rvecs, tvecs;
  result.rms = cv::calibrateCamera(object_points, image_points, result.image_size,
                                   result.camera_matrix, result.distortion, rvecs, tvecs, flags);
  result.distortion = result.distortion.reshape(1, 1);
  for (std::size_t v = 0; v < image_points.size(); ++v) {
    const auto [sum, n] = detail::reprojection(object_points[v], image_points[v], rvecs[v],
                                               tvecs[v], result.camera_matrix, result.distortion);
    result.view_rms.push_back(std::sqrt(sum / static_cast<double>(n)));
  }
  detail::set_status(result);
  return result;
}

/// Calibrates a stereo pair from simultaneous views of the chessboard and rectifies it (§3.2,
/// eq. 3.15; §10.1): both intrinsics, R, T, E, F, R₁, R₂, P₁, P₂ and Q. Intrinsics start from
/// cv::initCameraMatrix2D and are refined jointly with the relative pose.
/// @param names optional names of the pairs (e.g. the left file names) for error messages.
/// @return the calibration; status non_finite (and a message) when a number of OpenCV's fit
///   (intrinsics, pose, rectification, errors) is not finite.
/// @throws walkgen::invalid_argument for invalid settings (validate()), differing numbers of
///   left and right views, empty images, images of different sizes, a pair without the board in
///   both images (unless skip_views_without_board) or fewer than 3 usable pairs.
inline StereoCalibration calibrate_stereo(const std::vector<cv::Mat>& left,
                                          const std::vector<cv::Mat>& right,
                                          const CalibrationSettings& settings = {},
                                          const std::vector<std::string>& names = {}) {
  validate(settings);
  check_argument(left.size() == right.size(), "walkgen::calibrate_stereo: right views",
                 "as many as left views (" + std::to_string(left.size()) + ")", right.size());
  check_argument(left.size() >= 3, "walkgen::calibrate_stereo: pairs", "at least 3 pairs",
                 left.size());
  StereoCalibration result;
  cv::Size size;
  std::vector<std::vector<cv::Point2f>> points_left, points_right;
  const std::vector<cv::Point3f> board = detail::board_points(settings.board);
  for (std::size_t i = 0; i < left.size(); ++i) {
    for (int side = 0; side < 2; ++side) {
      const cv::Mat& image = side == 0 ? left[i] : right[i];
      const std::string where = std::string("walkgen::calibrate_stereo: ") +
                                (side == 0 ? "left " : "right ") + detail::view_name(names, i);
      check_argument(!image.empty(), where.c_str(), "a non-empty image", "an empty one");
      if (i == 0 && side == 0) size = image.size();
      check_argument(image.size() == size, where.c_str(),
                     "the size of the first left view, " + detail::size_string(size),
                     detail::size_string(image.size()));
    }
    bool found_left = false, found_right = false;
    std::vector<cv::Point2f> l = find_chessboard(left[i], settings.board, found_left);
    std::vector<cv::Point2f> r = find_chessboard(right[i], settings.board, found_right);
    if (!found_left || !found_right) {
      const std::string where = std::string("walkgen::calibrate_stereo: ") +
                                (found_left ? "right " : "left ") + detail::view_name(names, i);
      detail::check_board_found(settings.skip_views_without_board, settings.board, where);
      continue;
    }
    points_left.push_back(std::move(l));
    points_right.push_back(std::move(r));
    result.views_used.push_back(static_cast<int>(i));
  }
  check_argument(points_left.size() >= 3, "walkgen::calibrate_stereo: pairs with a board",
                 "at least 3", points_left.size());
  const std::vector<std::vector<cv::Point3f>> object_points(points_left.size(), board);

  // With fix_aspect_ratio the guess has f_x = f_y, which CALIB_FIX_ASPECT_RATIO then keeps.
  const double aspect = settings.fix_aspect_ratio ? 1.0 : 0.0;
  cv::Mat k1 = cv::initCameraMatrix2D(object_points, points_left, size, aspect);
  cv::Mat k2 = cv::initCameraMatrix2D(object_points, points_right, size, aspect);
  cv::Mat d1, d2;
  int flags = cv::CALIB_USE_INTRINSIC_GUESS;
  if (settings.fix_aspect_ratio) flags |= cv::CALIB_FIX_ASPECT_RATIO;
  if (settings.same_focal_length) flags |= cv::CALIB_SAME_FOCAL_LENGTH;
  if (settings.zero_tangent_distortion) flags |= cv::CALIB_ZERO_TANGENT_DIST;
  if (settings.rational_model) {
    flags |= cv::CALIB_RATIONAL_MODEL | cv::CALIB_FIX_K3 | cv::CALIB_FIX_K4 | cv::CALIB_FIX_K5;
  }
  cv::Mat rotation, translation, essential, fundamental;
  result.rms = cv::stereoCalibrate(
      object_points, points_left, points_right, k1, d1, k2, d2, size, rotation, translation,
      essential, fundamental, flags,
      cv::TermCriteria(cv::TermCriteria::COUNT + cv::TermCriteria::EPS, 100, 1e-5));
  result.rotation = rotation;
  result.translation = translation;
  result.essential = essential;
  result.fundamental = fundamental;
  result.left.image_size = result.right.image_size = size;
  result.left.camera_matrix = k1;
  result.right.camera_matrix = k2;
  result.left.distortion = d1.reshape(1, 1);
  result.right.distortion = d2.reshape(1, 1);
  result.left.views_used = result.right.views_used = result.views_used;

  // Each camera's own fit with the joint intrinsics (poses from solvePnP), for the report.
  for (int side = 0; side < 2; ++side) {
    MonoCalibration& mono = side == 0 ? result.left : result.right;
    const auto& points = side == 0 ? points_left : points_right;
    double sum = 0.0;
    std::size_t count = 0;
    for (std::size_t v = 0; v < points.size(); ++v) {
      cv::Mat rvec, tvec;
      cv::solvePnP(object_points[v], points[v], mono.camera_matrix, mono.distortion, rvec, tvec);
      const auto [s, n] = detail::reprojection(object_points[v], points[v], rvec, tvec,
                                               mono.camera_matrix, mono.distortion);
      mono.view_rms.push_back(std::sqrt(s / static_cast<double>(n)));
      sum += s;
      count += n;
    }
    mono.rms = std::sqrt(sum / static_cast<double>(count));
  }

  // Epipolar check (eq. 3.15): distance of each undistorted corner to its partner's line.
  double error = 0.0;
  std::size_t count = 0;
  for (std::size_t v = 0; v < points_left.size(); ++v) {
    std::vector<cv::Point2f> ul, ur;
    cv::undistortPoints(points_left[v], ul, k1, result.left.distortion, cv::noArray(), k1);
    cv::undistortPoints(points_right[v], ur, k2, result.right.distortion, cv::noArray(), k2);
    std::vector<cv::Vec3f> lines_in_right, lines_in_left;
    cv::computeCorrespondEpilines(ul, 1, fundamental, lines_in_right);
    cv::computeCorrespondEpilines(ur, 2, fundamental, lines_in_left);
    for (std::size_t j = 0; j < ul.size(); ++j) {
      error += std::abs(ul[j].x * lines_in_left[j][0] + ul[j].y * lines_in_left[j][1] +
                        lines_in_left[j][2]) +
               std::abs(ur[j].x * lines_in_right[j][0] + ur[j].y * lines_in_right[j][1] +
                        lines_in_right[j][2]);
      count += 2;
    }
  }
  result.mean_epipolar_error = error / static_cast<double>(count);

  cv::stereoRectify(k1, result.left.distortion, k2, result.right.distortion, size, rotation,
                    translation, result.rectification_left, result.rectification_right,
                    result.projection_left, result.projection_right, result.disparity_to_depth,
                    cv::CALIB_ZERO_DISPARITY, settings.rectify_alpha, size);
  detail::set_status(result.left);
  detail::set_status(result.right);
  const bool finite = result.left.status == CalibrationStatus::ok &&
                      result.right.status == CalibrationStatus::ok && std::isfinite(result.rms) &&
                      std::isfinite(result.mean_epipolar_error) &&
                      detail::all_finite({result.rotation, result.translation, result.essential,
                                          result.fundamental, result.rectification_left,
                                          result.rectification_right, result.projection_left,
                                          result.projection_right, result.disparity_to_depth});
  result.status = finite ? CalibrationStatus::ok : CalibrationStatus::non_finite;
  result.message =
      finite ? "" : "OpenCV returned a non-finite intrinsic, pose, rectification or error";
  return result;
}

/// Reads the pairs (left_paths[i], right_paths[i]) and calibrates them (calibrate_stereo).
/// @throws walkgen::invalid_argument as calibrate_stereo, naming the files, and for a missing
///   or unreadable file.
inline StereoCalibration calibrate_stereo_files(const std::vector<std::string>& left_paths,
                                                const std::vector<std::string>& right_paths,
                                                const CalibrationSettings& settings = {}) {
  check_argument(
      left_paths.size() == right_paths.size(), "walkgen::calibrate_stereo_files: right files",
      "as many as left files (" + std::to_string(left_paths.size()) + ")", right_paths.size());
  std::vector<cv::Mat> left, right;
  for (std::size_t i = 0; i < left_paths.size(); ++i) {
    left.push_back(read_image(left_paths[i]));
    right.push_back(read_image(right_paths[i]));
  }
  return calibrate_stereo(left, right, settings, left_paths);
}

// --- YAML files (cv::FileStorage) ---------------------------------------------------------------
//
// The file that save_stereo_calibration writes (format 2), in this order:
//
//   walkgen_calibration_format: 2       the format; present: the end marker below is required
//   image_width, image_height           [px], integers in 1..100000
//   K1, D1, K2, D2                      !!opencv-matrix: K 3x3, D 1xn (n in 4, 5, 8, 12, 14)
//   R, T, E, F                          3x3, 3x1, 3x3, 3x3
//   R1, R2, P1, P2, Q                   3x3, 3x3, 3x4, 3x4, 4x4
//   rms, mean_epipolar_error, rms_left, rms_right    [px], finite numbers >= 0
//   complete: 1                         the end marker, written last
//
// A matrix is a map of rows, cols (integers), dt (d or f: double or float) and data (rows x cols
// finite numbers, row by row), OpenCV's !!opencv-matrix. A file cut anywhere before its last line
// lacks the end marker; content alone cannot tell (rms 4.09 and 4.0912 are both numbers).

namespace detail {

constexpr int kStereoCalibrationFormat = 2;                    ///< walkgen_calibration_format
constexpr int kMaxCalibrationImageSide = 100000;               ///< [px]
constexpr std::uintmax_t kMaxCalibrationFileBytes = 1u << 20;  ///< 1 MiB; a saved file: ~2.5 kB

inline std::string file_node_kind(const cv::FileNode& n) {
  if (n.empty() || n.isNone()) return "nothing";
  if (n.isInt()) return "the integer " + std::to_string(static_cast<int>(n));
  if (n.isReal()) return "the number " + std::to_string(static_cast<double>(n));
  if (n.isString()) {  // at most 40 characters, bytes outside printable ASCII as \xNN
    const std::string text = static_cast<std::string>(n);
    std::string shown;
    for (std::size_t i = 0; i < text.size() && i < 40; ++i) {
      const auto byte = static_cast<unsigned char>(text[i]);
      if (byte >= 0x20 && byte < 0x7f) {
        shown += text[i];
      } else {
        const char* hex = "0123456789abcdef";
        shown += std::string("\\x") + hex[byte >> 4] + hex[byte & 15];
      }
    }
    return "the text '" + shown + (text.size() > 40 ? "...'" : "'");
  }
  if (n.isSeq()) return "a sequence";
  if (n.isMap()) return "a map";
  return "a node of OpenCV type " + std::to_string(n.type());
}

/// Reads the keys of one calibration file; each error names the file and the key.
class CalibrationFileReader {
 public:
  explicit CalibrationFileReader(const std::string& path) : path_(path) {}

  void set_root(const cv::FileNode& root) { root_ = root; }
  bool has(const char* key) const {
    if (!root_.isMap()) return false;
    const cv::FileNode n = root_[key];
    return !n.empty() && !n.isNone();
  }
  /// "walkgen::load_stereo_calibration: '<path>'[, key '<key>']" (the key being read).
  std::string where() const {
    return "walkgen::load_stereo_calibration: '" + path_ + "'" +
           (key_.empty() ? std::string() : ", key '" + key_ + "'");
  }

  cv::FileNode node(const std::string& key, const char* hint = kMissingHint) {
    key_ = key;
    cv::FileNode n;
    if (root_.isMap()) n = root_[key];
    if (n.empty() || n.isNone()) {
      fail("the key",
           root_.isMap()
               ? "a file without it"
               : "a file whose top level is " + file_node_kind(root_) + ", not a map of keys",
           hint);
    }
    return n;
  }

  int integer(const std::string& key, int lo, int hi) {
    const cv::FileNode n = node(key);
    const std::string range = "an integer in " + std::to_string(lo) + ".." + std::to_string(hi);
    check(n.isInt(), range, file_node_kind(n));
    const int v = static_cast<int>(n);
    check(v >= lo && v <= hi, range, v);
    return v;
  }

  double non_negative(const std::string& key) {
    const cv::FileNode n = node(key);
    check(n.isInt() || n.isReal(), "a finite number >= 0", file_node_kind(n));
    const double v = static_cast<double>(n);
    check(std::isfinite(v) && v >= 0.0, "a finite number >= 0", v);
    return v;
  }

  /// A rows x cols matrix (cols: one of `cols`) as CV_64F; sizes, type and count are checked
  /// before anything is allocated.
  cv::Mat matrix(const std::string& key, int rows, std::initializer_list<int> cols) {
    const cv::FileNode n = node(key);
    std::string shape = std::to_string(rows) + "x";
    if (cols.size() == 1) {
      shape += std::to_string(*cols.begin());
    } else {
      shape += "n matrix, n in {";
      for (const int c : cols) shape += (c == *cols.begin() ? "" : ", ") + std::to_string(c);
      shape += "}";
    }
    shape = "a " + shape + (cols.size() == 1 ? " matrix" : "");
    check(n.isMap(), shape + " (!!opencv-matrix: rows, cols, dt, data)", file_node_kind(n));
    const cv::FileNode r = n["rows"], c = n["cols"], dt = n["dt"], data = n["data"];
    check(r.isInt(), shape, "rows: " + file_node_kind(r));
    check(c.isInt(), shape, "cols: " + file_node_kind(c));
    const int nr = static_cast<int>(r), nc = static_cast<int>(c);
    check(nr == rows && std::find(cols.begin(), cols.end(), nc) != cols.end(), shape,
          std::to_string(nr) + "x" + std::to_string(nc));
    check(dt.isString() &&
              (static_cast<std::string>(dt) == "d" || static_cast<std::string>(dt) == "f"),
          "dt: d or f (double or float)", "dt: " + file_node_kind(dt));
    const std::size_t count = static_cast<std::size_t>(nr) * static_cast<std::size_t>(nc);
    check(data.isSeq(), "data: a sequence of " + std::to_string(count) + " numbers",
          "data: " + file_node_kind(data));
    check(data.size() == count, "data: " + std::to_string(count) + " numbers (rows x cols)",
          std::to_string(data.size()));
    cv::Mat m(nr, nc, CV_64F);
    std::size_t i = 0;
    for (cv::FileNodeIterator it = data.begin(); it != data.end() && i < count; ++it, ++i) {
      const cv::FileNode e = *it;
      const std::string at = "data[" + std::to_string(i) + "]: ";
      check(e.isInt() || e.isReal(), "finite numbers", at + file_node_kind(e));
      const double v = static_cast<double>(e);
      check(std::isfinite(v), "finite numbers", at + std::to_string(v));
      m.at<double>(static_cast<int>(i) / nc, static_cast<int>(i) % nc) = v;
    }
    check(i == count, "data: " + std::to_string(count) + " numbers", std::to_string(i));
    return m;
  }

  /// The end marker of format 2: complete: 1, written last.
  void end_marker() {
    const cv::FileNode n =
        node("complete",
             "the file is truncated (a save that was interrupted, a copy cut short): "
             "calibrate again or restore the file");
    check(n.isInt() && static_cast<int>(n) == 1, "1 (the end marker)", file_node_kind(n));
  }

  template <typename Expected, typename Got>
  void check(bool ok, const Expected& expected, const Got& got, const char* hint = nullptr) {
    if (!ok) fail(expected, got, hint);
  }
  template <typename Expected, typename Got>
  [[noreturn]] void fail(const Expected& expected, const Got& got, const char* hint = nullptr) {
    throw invalid_argument(expected_got(where().c_str(), expected, got, hint));
  }

 private:
  static constexpr const char* kMissingHint =
      "a truncated file, or one not written by walkgen::save_stereo_calibration";
  std::string path_, key_;
  cv::FileNode root_;
};

inline StereoCalibration read_stereo_calibration(CalibrationFileReader& in) {
  if (in.has("walkgen_calibration_format")) {
    const cv::FileNode format = in.node("walkgen_calibration_format");
    in.check(format.isInt() && static_cast<int>(format) == kStereoCalibrationFormat,
             std::to_string(kStereoCalibrationFormat), file_node_kind(format),
             "written by another walkgen version?");
    in.end_marker();  // first: a truncated file is named as such
  }
  StereoCalibration c;
  const int width = in.integer("image_width", 1, kMaxCalibrationImageSide);
  const int height = in.integer("image_height", 1, kMaxCalibrationImageSide);
  c.left.image_size = c.right.image_size = cv::Size(width, height);
  const std::initializer_list<int> distortion = {4, 5, 8, 12, 14};  // OpenCV's models
  c.left.camera_matrix = in.matrix("K1", 3, {3});
  c.left.distortion = in.matrix("D1", 1, distortion);
  c.right.camera_matrix = in.matrix("K2", 3, {3});
  c.right.distortion = in.matrix("D2", 1, distortion);
  c.rotation = in.matrix("R", 3, {3});
  c.translation = in.matrix("T", 3, {1});
  c.essential = in.matrix("E", 3, {3});
  c.fundamental = in.matrix("F", 3, {3});
  c.rectification_left = in.matrix("R1", 3, {3});
  c.rectification_right = in.matrix("R2", 3, {3});
  c.projection_left = in.matrix("P1", 3, {4});
  c.projection_right = in.matrix("P2", 3, {4});
  c.disparity_to_depth = in.matrix("Q", 4, {4});
  c.rms = in.non_negative("rms");
  c.mean_epipolar_error = in.non_negative("mean_epipolar_error");
  c.left.rms = in.non_negative("rms_left");
  c.right.rms = in.non_negative("rms_right");
  return c;
}

}  // namespace detail

namespace detail {

/// The first line (1-based) of `text` that is not shaped like a line save_stereo_calibration
/// writes, or 0. OpenCV's YAML parser loops forever on some malformed documents (e.g. a line
/// `---%YAML:1.0` before `-$--`, found by tests/fuzz/fuzz_stereo_calibration.cpp), so only text
/// made of these lines reaches it: `%YAML:1.0`, `---`, then `key: number` or
/// `key: !!opencv-matrix` at column 0 (key of letters, digits, '_'), the matrix fields
/// `   rows: N`, `   cols: N`, `   dt: x`, `   data: [ numbers`, and indented continuation lines
/// of numbers, commas and the closing ']'.
/// `key` receives the top-level key whose block holds that line ("" in the header).
inline std::size_t calibration_text_problem(const std::string& text, std::string* key) {
  const auto is_key_char = [](char c) {
    return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '_';
  };
  const auto only = [](const std::string& s, std::size_t from, const char* allowed) {
    return s.find_first_not_of(allowed, from) == std::string::npos;
  };
  constexpr const char* kNumberChars = "0123456789eE.+-";
  constexpr const char* kListChars = "0123456789eE.+-, ]";
  std::size_t start = 0, number = 0;
  while (start < text.size()) {
    std::size_t end = text.find('\n', start);
    if (end == std::string::npos) end = text.size();
    std::string line = text.substr(start, end - start);
    start = end + 1;
    ++number;
    if (!line.empty() && line.back() == '\r') line.pop_back();
    if (!line.empty() && is_key_char(line[0])) {  // a new block: name it by its key
      std::size_t k = 0;
      while (k < line.size() && is_key_char(line[k])) ++k;
      *key = line.substr(0, k);
    }
    bool ok = false;
    if (number == 1) {
      ok = line == "%YAML:1.0";
    } else if (number == 2) {
      ok = line == "---";
    } else if (line.empty()) {
      ok = true;
    } else if (is_key_char(line[0])) {  // key: value
      std::size_t k = 0;
      while (k < line.size() && is_key_char(line[k])) ++k;
      ok = line.compare(k, 2, ": ") == 0 && k + 2 < line.size() &&
           (line.compare(k + 2, std::string::npos, "!!opencv-matrix") == 0 ||
            only(line, k + 2, kNumberChars));
    } else if (line.compare(0, 3, "   ") == 0 && line.size() > 3 && line[3] != ' ') {
      const std::string field = line.substr(3);
      if (field.compare(0, 6, "rows: ") == 0 || field.compare(0, 6, "cols: ") == 0) {
        ok = field.size() > 6 && only(field, 6, "0123456789");
      } else if (field.compare(0, 4, "dt: ") == 0) {
        ok = field.size() == 5 && field[4] >= 'a' && field[4] <= 'z';
      } else if (field.compare(0, 7, "data: [") == 0) {
        ok = only(field, 7, kListChars);
      }
    } else if (line[0] == ' ') {  // continuation of a data list
      ok = only(line, 0, kListChars);
    }
    if (!ok) return number;
  }
  return 0;
}

}  // namespace detail

/// Reads a file written by save_stereo_calibration (the format above). A file without
/// walkgen_calibration_format (written before the end marker existed, format 1) loads when every
/// key is present and valid; such a file cut inside its last number (rms_right) cannot be told
/// from a complete one: save it again to add the marker.
/// @throws walkgen::invalid_argument naming the file, and the key where one is at fault, when
///   the file is missing, larger than 1 MiB, not text, has a line shaped otherwise than those
///   save_stereo_calibration writes (see detail::calibration_text_problem), is not YAML, is
///   truncated (no end marker), or a
///   key is missing or out of range: an image side outside 1..100000 px, a matrix of another
///   shape or type, with a data count other than rows x cols or a non-finite entry, an rms that
///   is negative or not finite. Every error of OpenCV's parser becomes this exception too.
[[nodiscard]] inline StereoCalibration load_stereo_calibration(const std::string& path) {
  constexpr const char* where = "walkgen::load_stereo_calibration";
  std::error_code ec;
  check_argument(std::filesystem::is_regular_file(path, ec), where, "a readable YAML file",
                 "'" + path + "' (missing)");
  const std::uintmax_t bytes = std::filesystem::file_size(path, ec);
  check_argument(!ec && bytes <= detail::kMaxCalibrationFileBytes, where,
                 "a calibration file of at most 1 MiB",
                 "'" + path + "' (" + (ec ? ec.message() : std::to_string(bytes) + " bytes") + ")");
  std::ifstream file(path, std::ios::binary);
  std::string text((std::istreambuf_iterator<char>(file)), std::istreambuf_iterator<char>());
  check_argument(!file.bad() && text.size() == bytes, where, "a readable YAML file",
                 "'" + path + "' (unreadable)");
  const std::size_t nul = text.find('\0');
  check_argument(nul == std::string::npos, where, "a text file",
                 "'" + path + "' (a NUL byte at offset " + std::to_string(nul) + ")");
  std::string key;
  if (const std::size_t line = detail::calibration_text_problem(text, &key)) {
    check_argument(false, where, "a file as walkgen::save_stereo_calibration writes it",
                   "'" + path + "' (line " + std::to_string(line) + ", in " +
                       (key.empty() ? std::string("the header") : "key '" + key + "'") +
                       ", is shaped otherwise)",
                   "only %YAML:1.0, ---, key: number, key: !!opencv-matrix and its rows, cols, "
                   "dt and data lines are read");
  }
  detail::CalibrationFileReader reader(path);
  try {
    // From memory, as YAML: no XML or JSON parser, no .gz or '?' handling of the file name.
    cv::FileStorage fs(
        text, cv::FileStorage::READ | cv::FileStorage::MEMORY | cv::FileStorage::FORMAT_YAML);
    check_argument(fs.isOpened(), where, "a YAML file written by cv::FileStorage",
                   "'" + path + "' (unreadable)");
    reader.set_root(fs.root());
    return detail::read_stereo_calibration(reader);
  } catch (const invalid_argument&) {
    throw;
  } catch (const cv::Exception& e) {
    throw invalid_argument(detail::expected_got(
        reader.where().c_str(), "a YAML file written by walkgen::save_stereo_calibration",
        "OpenCV's error '" + e.err + "'"));
  } catch (const std::exception& e) {  // OpenCV's parser also lets std::length_error escape
    throw invalid_argument(detail::expected_got(
        reader.where().c_str(), "a YAML file written by walkgen::save_stereo_calibration",
        std::string("an error parsing it: ") + e.what()));
  }
}

/// Writes a stereo calibration as YAML (cv::FileStorage) in the format above: the keys
/// walkgen_calibration_format (2), image_width, image_height, K1, D1, K2, D2, R, T, E, F, R1, R2,
/// P1, P2, Q, rms, mean_epipolar_error, rms_left, rms_right, and last the end marker complete: 1.
/// The file is replaced atomically (walkgen::write_atomically): written to a temporary file in
/// the same folder, read back with load_stereo_calibration, then renamed over `path`. A save
/// that fails or is interrupted (a crash, a full disk) leaves the previous file as it was.
/// @throws walkgen::invalid_argument naming `path` when the folder is missing or not writable,
///   the file cannot be written completely, or it would not load (a matrix of the wrong shape,
///   non-finite values, an image side outside 1..100000 px, a negative rms): the previous file,
///   if any, is then unchanged.
inline void save_stereo_calibration(const StereoCalibration& c, const std::string& path) {
  constexpr const char* where = "walkgen::save_stereo_calibration";
  write_atomically(path, [&](const std::string& temp) {
    try {
      cv::FileStorage fs(temp, cv::FileStorage::WRITE | cv::FileStorage::FORMAT_YAML);
      check_argument(fs.isOpened(), where, "a writable file", "'" + path + "'");
      fs << "walkgen_calibration_format" << detail::kStereoCalibrationFormat;
      fs << "image_width" << c.left.image_size.width << "image_height" << c.left.image_size.height;
      fs << "K1" << c.left.camera_matrix << "D1" << c.left.distortion;
      fs << "K2" << c.right.camera_matrix << "D2" << c.right.distortion;
      fs << "R" << c.rotation << "T" << c.translation << "E" << c.essential << "F" << c.fundamental;
      fs << "R1" << c.rectification_left << "R2" << c.rectification_right;
      fs << "P1" << c.projection_left << "P2" << c.projection_right << "Q" << c.disparity_to_depth;
      fs << "rms" << c.rms << "mean_epipolar_error" << c.mean_epipolar_error;
      fs << "rms_left" << c.left.rms << "rms_right" << c.right.rms;
      fs << "complete" << 1;
      fs.release();
    } catch (const cv::Exception& e) {
      throw invalid_argument(
          detail::expected_got(where, "a calibration OpenCV can write to '" + path + "'",
                               "OpenCV's error '" + e.err + "'"));
    }
    try {  // cv::FileStorage does not report write errors (a full disk): read the file back.
      (void)load_stereo_calibration(temp);
    } catch (const invalid_argument& e) {
      throw invalid_argument(detail::expected_got(
          where, "'" + path + "' written completely, with a calibration that loads",
          std::string("an error reading it back: ") + e.what(),
          "the previous file, if any, is unchanged"));
    }
  });
}

/// Rectification maps of a calibrated pair: remaps raw left/right images onto the common image
/// plane of P₁, P₂ (§3.2, figure 10.3), where epipolar lines are image rows.
class StereoRectifier {
 public:
  /// @throws walkgen::invalid_argument when the calibration lacks its matrices.
  explicit StereoRectifier(const StereoCalibration& c) : size_(c.left.image_size) {
    check_argument(!c.left.camera_matrix.empty() && !c.rectification_left.empty() &&
                       !c.projection_right.empty() && size_.area() > 0,
                   "walkgen::StereoRectifier", "a calibration with K, D, R1, R2, P1, P2",
                   "missing matrices", "use calibrate_stereo or load_stereo_calibration");
    cv::initUndistortRectifyMap(c.left.camera_matrix, c.left.distortion, c.rectification_left,
                                c.projection_left, size_, CV_16SC2, map_left_[0], map_left_[1]);
    cv::initUndistortRectifyMap(c.right.camera_matrix, c.right.distortion, c.rectification_right,
                                c.projection_right, size_, CV_16SC2, map_right_[0], map_right_[1]);
  }

  /// Rectifies a raw pair of the calibrated size.
  /// @throws walkgen::invalid_argument when an image is empty or not of the calibrated size.
  void rectify(const cv::Mat& left, const cv::Mat& right, cv::Mat& left_rectified,
               cv::Mat& right_rectified) const {
    for (const cv::Mat* m : {&left, &right}) {
      if (m->size() != size_) {  // the message only on failure: no per-frame strings
        throw invalid_argument(detail::expected_got(
            m == &left ? "walkgen::StereoRectifier: left image"
                       : "walkgen::StereoRectifier: right image",
            "the calibrated size " + detail::size_string(size_), detail::size_string(m->size())));
      }
    }
    cv::remap(left, left_rectified, map_left_[0], map_left_[1], cv::INTER_LINEAR);
    cv::remap(right, right_rectified, map_right_[0], map_right_[1], cv::INTER_LINEAR);
  }

  const cv::Size& image_size() const { return size_; }

 private:
  cv::Size size_;
  cv::Mat map_left_[2], map_right_[2];
};

}  // namespace walkgen
