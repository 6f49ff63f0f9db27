#pragma once
/// @file
/// Depth from a stereo pair (thesis §3.1, eq. 3.1–3.8; §10.2): rectification (optional), grey
/// conversion, left padding by D columns (StereoDepthSettings::pad_left), horizontal Sobel
/// prefilter (eq. 3.1), block matching with block size N and D disparities (eq. 3.2), a right
/// matcher for the left–right consistency (eq. 3.4), the confidence-weighted least squares
/// filter (eq. 3.3–3.8) with smoothing λ and range σ, and disparity → metric depth through the
/// rectification's Q matrix. OpenCV adapter: target walkgen::opencv (Debian: libopencv-dev,
/// libopencv-contrib-dev for ximgproc); the core never includes this header.
///
/// The OpenCV pieces: cv::StereoBM with PREFILTER_XSOBEL (eq. 3.1–3.2), its right matcher from
/// cv::ximgproc::createRightMatcher, and cv::ximgproc::DisparityWLSFilter, whose confidence
/// (eq. 3.3) combines the left–right check (eq. 3.4, threshold t) with the local disparity
/// variance, and whose fast global smoother solves eq. 3.6 with the guide's bilateral weights
/// (eq. 3.7); dividing the filtered C by the filtered L is eq. 3.8.
///
/// Images: OpenCV's cv::Mat, 8-bit grey or BGR (3 channels; StereoDepthSettings::rgb_input for
/// RGB, as walkgen::CameraImage holds). Buffers are allocated on the first frame and reused:
/// frames of the same size do not allocate in walkgen's code (OpenCV's matchers still allocate
/// internally).
///
/// Errors (convention 10): empty images, images of different sizes, or settings OpenCV rejects
/// (block size even or outside 5..255, D not a positive multiple of 16) throw
/// walkgen::invalid_argument.

#include <cmath>
#include <cstdint>
#include <opencv2/calib3d.hpp>
#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>
#include <opencv2/ximgproc/disparity_filter.hpp>
#include <optional>
#include <string>

#include "walkgen/core/exceptions.hpp"
#include "walkgen/core/math.hpp"
#include "walkgen/opencv/stereo_calibration.hpp"

namespace walkgen {

/// Parameters of the depth pipeline; the defaults are the thesis's (§10.2: N = 13, D = 32,
/// λ = 10⁴, σ = 1), chosen there on figures 10.5–10.6.
struct StereoDepthSettings {
  /// N, side of the square SAD block (eq. 3.2) [px], odd, 5..255. Larger: smoother and less
  /// noisy disparity, blurred object borders (figure 10.5 a).
  int block_size = 13;
  /// D, disparities searched (eq. 3.2) [px], a positive multiple of 16. Sets the nearest
  /// measurable depth Z_min = f B / D; the leftmost D columns have no left disparity.
  int num_disparities = 32;
  /// λ, weight of the smoothness term of eq. 3.6. Larger: flatter regions, depth follows the
  /// image's edges more strictly (figure 10.6).
  double lambda = 1e4;
  /// σ, range of the bilateral weights of eq. 3.7 (in grey levels, OpenCV's sigma_color).
  /// Larger: smoothing leaks across weaker image edges (figure 10.6).
  double sigma = 1.0;
  /// t of eq. 3.4 [px]: left and right disparities that differ by more are inconsistent
  /// (OpenCV's default 24/16 px).
  double left_right_threshold = 1.5;
  /// Clamp of the Sobel prefilter's output (eq. 3.1), 1..63.
  int prefilter_cap = 31;
  /// Blocks whose summed prefiltered texture is below this are left without disparity. Block
  /// matching only (wls false): for the WLS filter OpenCV's factory sets it to 0, as the
  /// confidence (eq. 3.3–3.4) does this job on a dense D_left.
  int texture_threshold = 10;
  /// [%] a disparity whose SAD is not this much better than the second best is rejected. Block
  /// matching only (wls false), like texture_threshold.
  int uniqueness_ratio = 15;
  /// Pad both grey images on the left by D columns (border replicated) before matching, and crop
  /// after: block matching then searches the leftmost D columns too, as far as the scene's
  /// disparity there allows, instead of leaving them unknown (the band figure 10.5 loses). On
  /// Aloe at 320 px wide it lifts the density from 72 % to 92 %; it costs D columns of work.
  bool pad_left = true;
  /// Apply the confidence-weighted WLS filter (eq. 3.3–3.8); false: block matching only (the
  /// left disparity of figure 10.5 a, no right matcher).
  bool wls = true;
  /// Depth (not disparity) is set to 0 (unknown) where the confidence L of eq. 3.4 is below this
  /// (0 … 255; WLS only). 0 keeps the dense WLS depth of the thesis, which also extrapolates into
  /// textureless regions (a blank sky or wall gets the depth of its surroundings); a small
  /// threshold (e.g. 1) keeps only depth near block-matched, left–right consistent pixels, what
  /// obstacles_from_depth wants.
  double min_confidence = 0.0;
  /// The colour images are RGB (walkgen::CameraImage) rather than OpenCV's BGR.
  bool rgb_input = false;
};

/// Checks the pipeline's parameters, including those OpenCV rejects (StereoDepth's
/// constructors call this).
/// @throws walkgen::invalid_argument naming the first bad field.
inline void validate(const StereoDepthSettings& s) {
  check_argument(s.block_size >= 5 && s.block_size <= 255 && s.block_size % 2 == 1,
                 "StereoDepthSettings.block_size", "an odd N in 5..255", s.block_size);
  check_argument(s.num_disparities > 0 && s.num_disparities % 16 == 0,
                 "StereoDepthSettings.num_disparities", "a positive multiple of 16",
                 s.num_disparities);
  check_positive("StereoDepthSettings.lambda", s.lambda);
  check_positive("StereoDepthSettings.sigma", s.sigma);
  check_non_negative("StereoDepthSettings.left_right_threshold", s.left_right_threshold);
  check_non_negative("StereoDepthSettings.min_confidence", s.min_confidence);
  check_argument(s.prefilter_cap >= 1 && s.prefilter_cap <= 63, "StereoDepthSettings.prefilter_cap",
                 "a value in 1..63", s.prefilter_cap);
  check_argument(s.texture_threshold >= 0, "StereoDepthSettings.texture_threshold", "a value >= 0",
                 s.texture_threshold);
  check_argument(s.uniqueness_ratio >= 0, "StereoDepthSettings.uniqueness_ratio", "a value >= 0",
                 s.uniqueness_ratio);
}

/// Whether a frame has any depth (a numerical outcome, convention 10c: not thrown).
enum class DepthStatus : std::uint8_t {
  ok,        ///< some pixels have a depth
  no_depth,  ///< no pixel has one: a textureless or too near scene, or a wrong rectification
};

/// "ok" or "no_depth", e.g. for logs; "unknown" for a value out of range.
constexpr const char* to_string(DepthStatus status) noexcept {
  switch (status) {
    case DepthStatus::ok:
      return "ok";
    case DepthStatus::no_depth:
      return "no_depth";
  }
  return "unknown";
}

/// One frame's images, all of the (rectified) input's size (views into the pipeline's buffers).
struct StereoDepthFrame {
  DepthStatus status = DepthStatus::no_depth;  ///< of the last compute()
  const char* message = "";                    ///< why there is no depth; empty when ok
  cv::Mat left_grey, right_grey;  ///< G (CV_8U): the rectified grey images, guide of eq. 3.7
  cv::Mat disparity_left;         ///< D_left (CV_16S, 16 × px), raw block matching (eq. 3.2)
  cv::Mat disparity_right;        ///< D_right (CV_16S, 16 × px, negative), when wls
  /// Final disparity [px] (CV_32F): D_final of eq. 3.8 when wls, else D_left; ≤ 0 where unknown.
  cv::Mat disparity;
  cv::Mat confidence;  ///< L of eq. 3.4 (CV_32F, 0 … 255), when wls
  cv::Mat depth;       ///< Z [m, unit of Q] along the optical axis (CV_32F); 0 where unknown
};

/// Intrinsics of an ideal pinhole camera (eq. 3.9) [px], OpenCV pixel coordinates.
struct PinholeIntrinsics {
  double fx = 0.0, fy = 0.0;  ///< focal lengths [px]
  double cx = 0.0, cy = 0.0;  ///< principal point [px]; (0, 0) is the top-left pixel's centre
};

/// The intrinsics of a rendered camera (MuJoCo, OpenGL) of `width` × `height` pixels and vertical
/// field of view `fovy` [rad], square pixels: f = (height / 2) / tan(fovy / 2), principal point
/// at the image centre ((width − 1) / 2, (height − 1) / 2).
/// @throws walkgen::invalid_argument for non-positive sizes or fovy outside (0, π).
inline PinholeIntrinsics pinhole_from_fovy(int width, int height, double fovy) {
  check_argument(width > 0 && height > 0, "walkgen::pinhole_from_fovy: image size",
                 "positive width and height", std::to_string(width) + "x" + std::to_string(height));
  check_argument(fovy > 0.0 && fovy < kPi, "walkgen::pinhole_from_fovy: fovy",
                 "a field of view in (0, pi) rad", fovy);
  PinholeIntrinsics k;
  k.fy = 0.5 * height / std::tan(0.5 * fovy);
  k.fx = k.fy;
  k.cx = 0.5 * (width - 1);
  k.cy = 0.5 * (height - 1);
  return k;
}

/// Q of an ideal, already rectified pair (parallel cameras, same intrinsics k, the right camera
/// `baseline` [m] to the right of the left one): (u, v, d, 1) ↦ (u − c_x, v − c_y, f, d / B), so
/// Z = f B / d.
/// @throws walkgen::invalid_argument for a non-positive baseline or focal length.
inline cv::Mat ideal_disparity_to_depth(const PinholeIntrinsics& k, double baseline) {
  check_positive("walkgen::ideal_disparity_to_depth: baseline", baseline,
                 "a baseline > 0 (the right camera's distance from the left one)");
  check_positive("walkgen::ideal_disparity_to_depth: fx", k.fx);
  cv::Mat q = cv::Mat::zeros(4, 4, CV_64F);
  q.at<double>(0, 0) = 1.0;
  q.at<double>(0, 3) = -k.cx;
  q.at<double>(1, 1) = 1.0;
  q.at<double>(1, 3) = -k.cy;
  q.at<double>(2, 3) = k.fx;
  q.at<double>(3, 2) = 1.0 / baseline;
  return q;
}

/// The depth pipeline of §3.1 for one stereo rig. Construct once, then compute() per frame.
class StereoDepth {
 public:
  /// For images that are already rectified (a simulated pair, or rectified elsewhere), with the
  /// rig's disparity-to-depth matrix Q (4 × 4; ideal_disparity_to_depth for an ideal pair).
  /// @throws walkgen::invalid_argument for invalid settings or a Q that is not 4 × 4.
  StereoDepth(const StereoDepthSettings& settings, const cv::Mat& disparity_to_depth)
      : settings_(settings) {
    check_argument(
        disparity_to_depth.rows == 4 && disparity_to_depth.cols == 4,
        "walkgen::StereoDepth: disparity_to_depth", "a 4x4 matrix Q",
        std::to_string(disparity_to_depth.rows) + "x" + std::to_string(disparity_to_depth.cols));
    disparity_to_depth.convertTo(q_, CV_64F);
    create_matchers();
  }

  /// For raw images of a calibrated rig: each frame is rectified first (StereoRectifier), and
  /// depth uses the calibration's Q.
  /// @throws walkgen::invalid_argument for invalid settings or an incomplete calibration.
  StereoDepth(const StereoDepthSettings& settings, const StereoCalibration& calibration)
      : StereoDepth(settings, calibration.disparity_to_depth) {
    rectifier_.emplace(calibration);
  }

  const StereoDepthSettings& settings() const { return settings_; }
  const cv::Mat& disparity_to_depth() const { return q_; }

  /// Runs the pipeline on one pair; the returned frame lives until the next call. Its status is
  /// no_depth (with a message) when no pixel got a depth.
  /// @throws walkgen::invalid_argument when an image is empty, the images differ in size or
  ///   type, or (with a calibration) are not of the calibrated size.
  const StereoDepthFrame& compute(const cv::Mat& left, const cv::Mat& right) {
    check_argument(!left.empty(), "walkgen::StereoDepth::compute: left image", "a non-empty image",
                   "an empty one");
    check_argument(!right.empty(), "walkgen::StereoDepth::compute: right image",
                   "a non-empty image", "an empty one");
    if (left.size() != right.size()) {  // messages built only on failure: no per-frame strings
      throw invalid_argument(
          detail::expected_got("walkgen::StereoDepth::compute: right image",
                               "the left image's size " + detail::size_string(left.size()),
                               detail::size_string(right.size())));
    }
    if (left.type() != right.type() || left.depth() != CV_8U ||
        (left.channels() != 1 && left.channels() != 3)) {
      throw invalid_argument(detail::expected_got(
          "walkgen::StereoDepth::compute: images", "two 8-bit grey or two 8-bit 3-channel images",
          "types " + std::to_string(left.type()) + " and " + std::to_string(right.type())));
    }
    const cv::Mat* l = &left;
    const cv::Mat* r = &right;
    if (rectifier_) {
      rectifier_->rectify(left, right, rectified_[0], rectified_[1]);
      l = &rectified_[0];
      r = &rectified_[1];
    }
    // G (grey, the guide of eq. 3.7), padded on the left when pad_left.
    const int code = settings_.rgb_input ? cv::COLOR_RGB2GRAY : cv::COLOR_BGR2GRAY;
    const int pad = settings_.pad_left ? settings_.num_disparities : 0;
    for (int side = 0; side < 2; ++side) {
      const cv::Mat& in = side == 0 ? *l : *r;
      cv::Mat& grey = pad > 0 ? grey_[side] : padded_[side];
      if (in.channels() == 3) {
        cv::cvtColor(in, grey, code);
      } else {
        in.copyTo(grey);
      }
      if (pad > 0) cv::copyMakeBorder(grey, padded_[side], 0, 0, pad, 0, cv::BORDER_REPLICATE);
    }
    // Eq. 3.1–3.2 (and 3.3–3.8) on the padded images.
    left_matcher_->compute(padded_[0], padded_[1], disparity_[0]);
    const cv::Rect crop(pad, 0, l->cols, l->rows);
    frame_.left_grey = padded_[0](crop);
    frame_.right_grey = padded_[1](crop);
    frame_.disparity_left = disparity_[0](crop);
    if (settings_.wls) {
      right_matcher_->compute(padded_[1], padded_[0], disparity_[1]);
      wls_->filter(disparity_[0], padded_[0], filtered_, disparity_[1]);
      frame_.disparity_right = disparity_[1](crop);
      frame_.confidence = wls_->getConfidenceMap()(crop);
      filtered_(crop).convertTo(frame_.disparity, CV_32F, 1.0 / 16.0);
    } else {
      frame_.disparity_left.convertTo(frame_.disparity, CV_32F, 1.0 / 16.0);
    }
    disparity_to_depth(frame_.disparity, frame_.depth);
    if (settings_.wls && settings_.min_confidence > 0.0) {
      cv::compare(frame_.confidence, settings_.min_confidence, unconfident_, cv::CMP_LT);
      frame_.depth.setTo(0.0f, unconfident_);
    }
    const bool some = cv::countNonZero(frame_.depth) > 0;
    frame_.status = some ? DepthStatus::ok : DepthStatus::no_depth;
    frame_.message = some ? "" : "no pixel has a depth (no texture, too near, or not rectified)";
    return frame_;
  }

  /// The last frame.
  const StereoDepthFrame& frame() const { return frame_; }

 private:
  void create_matchers() {
    const StereoDepthSettings& s = settings_;
    validate(s);
    cv::Ptr<cv::StereoBM> bm = cv::StereoBM::create(s.num_disparities, s.block_size);
    bm->setPreFilterType(cv::StereoBM::PREFILTER_XSOBEL);  // eq. 3.1
    bm->setPreFilterCap(s.prefilter_cap);
    bm->setTextureThreshold(s.texture_threshold);
    bm->setUniquenessRatio(s.uniqueness_ratio);
    left_matcher_ = bm;
    if (s.wls) {
      wls_ = cv::ximgproc::createDisparityWLSFilter(left_matcher_);
      wls_->setLambda(s.lambda);
      wls_->setSigmaColor(s.sigma);
      wls_->setLRCthresh(static_cast<int>(std::lround(16.0 * s.left_right_threshold)));
      right_matcher_ = cv::ximgproc::createRightMatcher(left_matcher_);
      // The two factories above set texture_threshold and uniqueness_ratio to 0 (dense D_left).
    }
  }

  /// Z = Q₂₃ / (Q₃₂ d + Q₃₃) for each valid disparity d > 0, 0 elsewhere (the Z of
  /// cv::reprojectImageTo3D without X, Y).
  void disparity_to_depth(const cv::Mat& disparity, cv::Mat& depth) const {
    depth.create(disparity.size(), CV_32F);
    const double f = q_.at<double>(2, 3);
    const double a = q_.at<double>(3, 2);
    const double b = q_.at<double>(3, 3);
    for (int v = 0; v < disparity.rows; ++v) {
      const float* d = disparity.ptr<float>(v);
      float* z = depth.ptr<float>(v);
      for (int u = 0; u < disparity.cols; ++u) {
        const double w = a * d[u] + b;
        z[u] = d[u] > 0.0f && w > 0.0 ? static_cast<float>(f / w) : 0.0f;
      }
    }
  }

  StereoDepthSettings settings_;
  cv::Mat q_;
  std::optional<StereoRectifier> rectifier_;
  cv::Ptr<cv::StereoMatcher> left_matcher_, right_matcher_;
  cv::Ptr<cv::ximgproc::DisparityWLSFilter> wls_;
  cv::Mat rectified_[2], grey_[2], padded_[2], disparity_[2], filtered_, unconfident_;
  StereoDepthFrame frame_;
};

/// A disparity map against ground truth (the Middlebury measures of §10.2's comparison).
struct DisparityScore {
  double density = 0.0;  ///< fraction of ground-truth pixels with a disparity
  double bad = 0.0;      ///< fraction of ground-truth pixels off by > threshold or without one
  double mae = 0.0;      ///< mean absolute error over ground-truth pixels with a disparity [px]
};

/// Scores `disparity` (CV_32F, <= 0 unknown) against `truth` (CV_32F, 0 unknown) of the same
/// size: a pixel is bad when its error exceeds bad_threshold [px] or it has no disparity.
/// @throws walkgen::invalid_argument for other types or sizes, or no ground truth at all.
inline DisparityScore score_disparity(const cv::Mat& disparity, const cv::Mat& truth,
                                      double bad_threshold = 2.0) {
  check_argument(disparity.type() == CV_32F && truth.type() == CV_32F,
                 "walkgen::score_disparity: types", "CV_32F disparity and ground truth",
                 "another type");
  check_argument(disparity.size() == truth.size(), "walkgen::score_disparity: sizes", "equal sizes",
                 "different ones");
  std::size_t known = 0, valid = 0, bad = 0;
  double abs_sum = 0.0;
  for (int v = 0; v < truth.rows; ++v) {
    for (int u = 0; u < truth.cols; ++u) {
      const float t = truth.at<float>(v, u);
      if (!(t > 0.0f)) continue;
      ++known;
      const float d = disparity.at<float>(v, u);
      if (!(d > 0.0f)) {
        ++bad;
        continue;
      }
      ++valid;
      const double e = std::abs(static_cast<double>(d) - t);
      abs_sum += e;
      if (e > bad_threshold) ++bad;
    }
  }
  check_argument(known > 0, "walkgen::score_disparity: ground truth", "some known pixels", "none");
  DisparityScore s;
  s.density = static_cast<double>(valid) / static_cast<double>(known);
  s.bad = static_cast<double>(bad) / static_cast<double>(known);
  s.mae = valid > 0 ? abs_sum / static_cast<double>(valid) : 0.0;
  return s;
}

}  // namespace walkgen
