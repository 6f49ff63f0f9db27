#pragma once
/// @file
/// The behavioural-cloning network in the control loop (thesis §7.1.2, figure 8.2): a U-Net-LSTM
/// trained in Python (python/bc_train.py) and exported as TorchScript turns each new frame of the
/// chest cameras (left RGB + WLS disparity) into a velocity command (v_x, ω_z) for the NMPC,
/// keeping the features of the last frames between calls. libtorch adapter (walkgen::torch).
///
/// Pre-processing, identical to python/bc_train.py: RGB (240 × 320) and disparity are averaged
/// over 4 × 4 blocks to 60 × 80, RGB scaled to [0, 1], disparity [px] divided by 32, stacked to
/// four channels. The module must have the methods `encode(frames (N, 4, 60, 80))` → features
/// (N, hidden) and `head(features (1, T, hidden), oldest first)` → output (1, 2) in [−1, 1], and
/// the int attributes `hidden` and `sequence` (T). Each frame is encoded once; the LSTM runs over
/// the latest `sequence` features from a zero state, as in training (the first frame of an
/// episode stands in for the frames before it). The output times max_command is the command.

#include <torch/script.h>
#include <torch/torch.h>

#include <Eigen/Core>
#include <cmath>
#include <string>

#include "walkgen/core/exceptions.hpp"
#include "walkgen/robot/robot.hpp"

namespace walkgen {

struct VelocityNetworkSettings {
  /// (v_x [m/s], ω_z [rad/s]) of an output of ±1: Heicub's max_command, as in bc_train.py.
  Eigen::Vector2d max_command = Eigen::Vector2d(0.034, 0.075);
  double disparity_scale = 32.0;  ///< [px] divides the disparity (D of the thesis)
  int block = 4;                  ///< downsampling: the mean of block × block pixels
};

/// Checks the network's pre-processing settings (VelocityNetwork's constructor calls this).
/// @throws walkgen::invalid_argument naming the first bad field.
inline void validate(const VelocityNetworkSettings& s) {
  check_argument(s.max_command.allFinite(), "VelocityNetworkSettings.max_command",
                 "finite limits (v_x [m/s], ω_z [rad/s])", "NaN or inf");
  check_positive("VelocityNetworkSettings.disparity_scale", s.disparity_scale, "a scale > 0 px");
  check_argument(s.block >= 1, "VelocityNetworkSettings.block", "a block of >= 1 px", s.block);
}

/// A TorchScript velocity network with its recurrent state. Not thread-safe.
class VelocityNetwork {
 public:
  /// @throws walkgen::invalid_argument for invalid settings (validate()), or when the file
  ///   cannot be loaded or lacks `step` or `hidden` (naming the file).
  explicit VelocityNetwork(const std::string& path,
                           VelocityNetworkSettings settings = VelocityNetworkSettings())
      : settings_(std::move(settings)) {
    validate(settings_);
    try {
      module_ = torch::jit::load(path);
    } catch (const std::exception& e) {
      check_argument(false, "VelocityNetwork: model", "a TorchScript file (python/bc_train.py)",
                     "'" + path + "' (" + first_line(e.what()) + ")");
    }
    check_argument(module_.find_method("encode").has_value() &&
                       module_.find_method("head").has_value() && module_.hasattr("hidden") &&
                       module_.hasattr("sequence"),
                   "VelocityNetwork: model",
                   "a module with encode(frames), head(features), `hidden` and `sequence` "
                   "(python/bc_train.py)",
                   "'" + path + "'");
    hidden_ = module_.attr("hidden").toInt();
    sequence_ = module_.attr("sequence").toInt();
    check_argument(hidden_ >= 1 && sequence_ >= 1, "VelocityNetwork: model",
                   "hidden >= 1 and sequence >= 1", "'" + path + "'");
    module_.eval();
    reset();
  }

  /// Forgets the past frames (a new episode).
  void reset() { window_ = torch::Tensor(); }

  /// The command (v_x, 0, ω_z) after one more frame: `left` the left camera's RGB image,
  /// `disparity` its WLS disparity [px] (width × height floats, row-major, ≤ 0 unknown).
  /// @throws walkgen::invalid_argument when the sizes do not match or are not multiples of the
  ///   block.
  Eigen::Vector3d step(const CameraImage& left, const float* disparity) {
    const int b = settings_.block;
    check_argument(left.width > 0 && left.height > 0 && left.width % b == 0 &&
                       left.height % b == 0 &&
                       left.rgb.size() == std::size_t(left.width) * std::size_t(left.height) * 3 &&
                       disparity != nullptr,
                   "VelocityNetwork::step: image", "RGB with sides multiple of the block",
                   std::to_string(left.width) + "x" + std::to_string(left.height));
    const int h = left.height / b, w = left.width / b;
    if (frame_.numel() != 4 * h * w) frame_ = torch::zeros({1, 4, h, w});
    float* f = frame_.data_ptr<float>();
    const double area = double(b) * double(b);
    for (int v = 0; v < h; ++v) {
      for (int u = 0; u < w; ++u) {
        double sum[4] = {0.0, 0.0, 0.0, 0.0};
        for (int dv = 0; dv < b; ++dv) {
          const std::size_t row = std::size_t(v * b + dv) * std::size_t(left.width);
          for (int du = 0; du < b; ++du) {
            const std::size_t p = row + std::size_t(u * b + du);
            for (int ch = 0; ch < 3; ++ch) sum[ch] += left.rgb[3 * p + std::size_t(ch)];
            // The recorder stores disparity × 16 as 16-bit: unknown (≤ 0) is 0 there too.
            sum[3] += std::floor(std::max(0.0f, disparity[p]) * 16.0f + 0.5f) / 16.0f;
          }
        }
        const std::size_t i = std::size_t(v) * std::size_t(w) + std::size_t(u);
        for (int ch = 0; ch < 3; ++ch)
          f[std::size_t(ch) * std::size_t(h * w) + i] = float(sum[ch] / area / 255.0);
        f[3 * std::size_t(h * w) + i] = float(sum[3] / area / settings_.disparity_scale);
      }
    }
    torch::NoGradGuard no_grad;
    const torch::Tensor feature = module_.get_method("encode")({frame_}).toTensor().unsqueeze(1);
    window_ = window_.defined() ? torch::cat({window_.narrow(1, 1, sequence_ - 1), feature}, 1)
                                : feature.expand({1, sequence_, hidden_}).contiguous();
    const torch::Tensor y = module_.get_method("head")({window_}).toTensor();
    const float vx = y[0][0].item<float>(), wz = y[0][1].item<float>();
    check_argument(std::isfinite(vx) && std::isfinite(wz), "VelocityNetwork::step: output",
                   "finite values", "NaN or inf");
    return {settings_.max_command.x() * vx, 0.0, settings_.max_command.y() * wz};
  }

  std::int64_t hidden() const { return hidden_; }
  std::int64_t sequence() const { return sequence_; }

 private:
  static std::string first_line(const std::string& s) { return s.substr(0, s.find('\n')); }

  VelocityNetworkSettings settings_;
  torch::jit::Module module_;
  std::int64_t hidden_ = 0, sequence_ = 1;
  torch::Tensor window_, frame_;  ///< the latest `sequence` features (1, T, hidden); the input
};

}  // namespace walkgen
