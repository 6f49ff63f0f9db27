// The depth-map parameter sweeps of thesis §10.2 (figures 10.5 and 10.6) on Middlebury Aloe at
// 320 px wide (ground truth alike): block size N × disparities D for block matching alone
// (figure 10.5 a) and with the confidence-weighted WLS filter (figure 10.5 b), then the WLS
// filter's σ × λ (figure 10.6). Each grid is a PNG of colour-coded disparities (0 … 64 px, black:
// unknown); every cell's bad-pixel rate (> 2 px, unknown counted bad) and mean absolute error
// against the ground truth go to stdout and depth_sweep.csv.
//
//   depth_parameter_sweep DATA_DIR [--out DIR] [--pad]
//
//   DATA_DIR   the folder that holds opencv_aloe_middlebury2006/ (e.g. tests/data)
//   --out DIR  output folder, created if missing (default: the working directory)
//   --pad      turn on walkgen's left padding (StereoDepthSettings::pad_left)
//
// Writes depth_sweep_bm.png, depth_sweep_wls.png, depth_sweep_sigma_lambda.png and
// depth_sweep.csv in DIR; docs/img/depth_sweep_*.png are their copies. Like the thesis's OpenCV
// pipeline the sweeps run without walkgen's left padding, so the band of D columns that block
// matching cannot search shows; --pad turns it on. --help lists the options. Exits 0; 1 on an
// unreadable image or an unwritable file; 2 on a bad command line (one line on stderr).
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>
#include <walkgen/opencv/stereo_depth.hpp>

#include "common/cli.hpp"

namespace {

cv::Mat colour(const cv::Mat& disparity, const std::string& label) {
  cv::Mat scaled, out;
  disparity.convertTo(scaled, CV_8U, 255.0 / 64.0);
  cv::applyColorMap(scaled, out, cv::COLORMAP_JET);
  out.setTo(cv::Scalar(0, 0, 0), disparity <= 0.0f);
  cv::putText(out, label, cv::Point(4, 16), cv::FONT_HERSHEY_SIMPLEX, 0.45,
              cv::Scalar(255, 255, 255), 3);
  cv::putText(out, label, cv::Point(4, 16), cv::FONT_HERSHEY_SIMPLEX, 0.45, cv::Scalar(0, 0, 0), 1);
  return out;
}

// Rows of cells to one image, 2 px white between cells.
cv::Mat grid(const std::vector<std::vector<cv::Mat>>& rows) {
  std::vector<cv::Mat> lines;
  for (const auto& row : rows) {
    std::vector<cv::Mat> cells;
    for (const cv::Mat& c : row) {
      cv::Mat padded;
      cv::copyMakeBorder(c, padded, 1, 1, 1, 1, cv::BORDER_CONSTANT, cv::Scalar(255, 255, 255));
      cells.push_back(padded);
    }
    cv::Mat line;
    cv::hconcat(cells, line);
    lines.push_back(line);
  }
  cv::Mat all;
  cv::vconcat(lines, all);
  return all;
}

}  // namespace

int main(int argc, char** argv) {
  std::string data_dir;
  std::string out = ".";
  bool pad = false;
  CLI::App app{
      "The depth-map parameter sweeps of thesis §10.2 (figures 10.5-10.6) on Middlebury "
      "Aloe",
      "depth_parameter_sweep"};
  walkgen_examples::cli_defaults(app);
  app.add_option("DATA_DIR", data_dir, "folder that holds opencv_aloe_middlebury2006/")
      ->required()
      ->type_name("DIR")
      ->check(CLI::ExistingDirectory.description(""));
  app.add_option("--out", out,
                 "output folder for depth_sweep_{bm,wls,sigma_lambda}.png and depth_sweep.csv "
                 "(created if missing)")
      ->type_name("DIR");
  app.add_flag("--pad", pad,
               "turn on walkgen's left padding (StereoDepthSettings::pad_left; the thesis's "
               "OpenCV pipeline has none)");
  WALKGEN_CLI_PARSE(app, argc, argv);
  std::error_code ec;
  std::filesystem::create_directories(out, ec);  // a failure shows when a file is written

  const std::string dir = data_dir + "/opencv_aloe_middlebury2006";
  cv::Mat left, right, truth;
  try {
    cv::resize(walkgen::read_image(dir + "/aloeL.jpg", cv::IMREAD_COLOR), left, cv::Size(), 0.25,
               0.25, cv::INTER_AREA);
    cv::resize(walkgen::read_image(dir + "/aloeR.jpg", cv::IMREAD_COLOR), right, cv::Size(), 0.25,
               0.25, cv::INTER_AREA);
    cv::Mat gt;
    cv::resize(walkgen::read_image(dir + "/aloeGT.png"), gt, left.size(), 0, 0, cv::INTER_NEAREST);
    gt.convertTo(truth, CV_32F, 0.25);
  } catch (const walkgen::invalid_argument& e) {
    std::fprintf(stderr, "depth_parameter_sweep: %s\n", e.what());
    return 1;
  }
  walkgen::PinholeIntrinsics k;
  k.fx = k.fy = 300.0;
  const cv::Mat q = walkgen::ideal_disparity_to_depth(k, 0.1);  // any: scores are in pixels

  std::ofstream csv(out + "/depth_sweep.csv");
  if (!csv) {
    std::fprintf(stderr, "depth_parameter_sweep: cannot write %s/depth_sweep.csv\n", out.c_str());
    return 1;
  }
  csv << "figure,wls,block_size,num_disparities,lambda,sigma,bad_fraction,mae_px\n";
  std::printf(
      "Aloe %dx%d, pad_left %s\nfigure  filter  N   D   lambda  sigma  bad [%%]  MAE [px]\n",
      left.cols, left.rows, pad ? "on" : "off");
  auto run = [&](const char* figure, const walkgen::StereoDepthSettings& s,
                 const std::string& label) {
    walkgen::StereoDepth depth(s, q);
    const cv::Mat disparity = depth.compute(left, right).disparity.clone();
    const walkgen::DisparityScore sc = walkgen::score_disparity(disparity, truth);
    std::printf("%-7s %-6s %3d %3d %7.0e %6.2f %8.1f %9.2f\n", figure, s.wls ? "WLS" : "BM",
                s.block_size, s.num_disparities, s.lambda, s.sigma, 100.0 * sc.bad, sc.mae);
    csv << figure << ',' << s.wls << ',' << s.block_size << ',' << s.num_disparities << ','
        << s.lambda << ',' << s.sigma << ',' << sc.bad << ',' << sc.mae << '\n';
    char text[64];
    std::snprintf(text, sizeof(text), "%s bad %.0f%%", label.c_str(), 100.0 * sc.bad);
    return colour(disparity, text);
  };

  // Figure 10.5: N x D, block matching alone (a) and with WLS (b).
  const int sizes[] = {5, 9, 13, 21};
  const int disparities[] = {16, 32, 48, 64};
  for (int wls = 0; wls < 2; ++wls) {
    std::vector<std::vector<cv::Mat>> rows;
    for (int n : sizes) {
      std::vector<cv::Mat> row;
      for (int d : disparities) {
        walkgen::StereoDepthSettings s;
        s.block_size = n;
        s.num_disparities = d;
        s.wls = wls == 1;
        s.pad_left = pad;
        row.push_back(run("10.5", s, "N " + std::to_string(n) + " D " + std::to_string(d)));
      }
      rows.push_back(row);
    }
    const std::string path = out + (wls ? "/depth_sweep_wls.png" : "/depth_sweep_bm.png");
    if (!cv::imwrite(path, grid(rows))) {
      std::fprintf(stderr, "depth_parameter_sweep: cannot write %s\n", path.c_str());
      return 1;
    }
  }

  // Figure 10.6: sigma x lambda, N 13, D 64 (Aloe's disparities reach 53 px at this size).
  const double sigmas[] = {0.5, 1.0, 2.0, 4.0};
  const double lambdas[] = {1e2, 1e3, 1e4, 1e5};
  std::vector<std::vector<cv::Mat>> rows;
  for (double sigma : sigmas) {
    std::vector<cv::Mat> row;
    for (double lambda : lambdas) {
      walkgen::StereoDepthSettings s;
      s.num_disparities = 64;
      s.sigma = sigma;
      s.lambda = lambda;
      s.pad_left = pad;
      char label[48];
      std::snprintf(label, sizeof(label), "s %.1f l 1e%d", sigma,
                    static_cast<int>(std::lround(std::log10(lambda))));
      row.push_back(run("10.6", s, label));
    }
    rows.push_back(row);
  }
  const std::string path = out + "/depth_sweep_sigma_lambda.png";
  if (!cv::imwrite(path, grid(rows))) {
    std::fprintf(stderr, "depth_parameter_sweep: cannot write %s\n", path.c_str());
    return 1;
  }
  std::printf("wrote %s/depth_sweep_{bm,wls,sigma_lambda}.png and depth_sweep.csv\n", out.c_str());
  return 0;
}
