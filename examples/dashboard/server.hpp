#pragma once
// The dashboard's HTTP side (examples/walkgen_dashboard.cpp, docs/dashboard.md): cpp-httplib
// serves the page and its API; the simulation thread publishes snapshots (the state as JSON, the
// camera images as JPEG) into a Board and takes velocity commands from it. Handlers only copy
// what the board holds under a short lock, so a slow or vanished client never holds up the
// loop. Requests are validated with nlohmann::json: a malformed body, a missing, non-numeric,
// non-finite or out-of-range velocity is refused with 400 and changes nothing; a body over
// kMaxBody bytes gets 413 from cpp-httplib before it is read.
#include <httplib.h>

#include <Eigen/Core>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <condition_variable>
#include <cstdint>
#include <cstdlib>
#include <deque>
#include <filesystem>
#include <fstream>
#include <mutex>
#include <nlohmann/json.hpp>
#include <optional>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

namespace walkgen_dashboard {

/// Largest request body accepted [bytes]; a command is about 40.
constexpr std::size_t kMaxBody = 4096;

/// What the simulation publishes and what the page asks of it.
class Board {
 public:
  explicit Board(const Eigen::Vector3d& max_command) : max_command_(max_command) {}

  // --- the simulation thread ----------------------------------------------------------------
  /// A new state (JSON text); wakes the event streams.
  void publish_state(std::string json) {
    {
      std::lock_guard<std::mutex> lock(mutex_);
      state_ = std::move(json);
      ++generation_;
    }
    changed_.notify_all();
  }
  void publish_images(std::string rgb_jpeg, std::string depth_jpeg) {
    std::lock_guard<std::mutex> lock(mutex_);
    rgb_ = std::move(rgb_jpeg);
    depth_ = std::move(depth_jpeg);
  }
  void set_camera_message(std::string message) {
    std::lock_guard<std::mutex> lock(mutex_);
    camera_message_ = std::move(message);
  }
  /// The command the page asked for since the last call, if any.
  std::optional<Eigen::Vector3d> take_command() {
    std::lock_guard<std::mutex> lock(mutex_);
    return std::exchange(command_, std::nullopt);
  }
  /// Whether the stop button was pressed since the last call.
  bool take_stop() {
    std::lock_guard<std::mutex> lock(mutex_);
    return std::exchange(stop_, false);
  }
  /// Ends the event streams (before the server stops).
  void close() {
    {
      std::lock_guard<std::mutex> lock(mutex_);
      closed_ = true;
    }
    changed_.notify_all();
  }

  // --- the HTTP handlers ----------------------------------------------------------------------
  std::string state() const {
    std::lock_guard<std::mutex> lock(mutex_);
    return state_;
  }
  /// The state after `generation`, waiting up to `timeout`; empty when closed.
  std::pair<std::string, long> next_state(long generation, std::chrono::milliseconds timeout) {
    std::unique_lock<std::mutex> lock(mutex_);
    changed_.wait_for(lock, timeout, [&] { return closed_ || generation_ != generation; });
    if (closed_) return {std::string(), generation_};
    return {state_, generation_};
  }
  /// The JPEG of "rgb" or "depth"; empty with the reason when there is none.
  std::pair<std::string, std::string> image(const std::string& which) const {
    std::lock_guard<std::mutex> lock(mutex_);
    const std::string& jpeg = which == "rgb" ? rgb_ : depth_;
    return {jpeg, jpeg.empty() ? camera_message_ : std::string()};
  }
  /// Checks a command body; on success it replaces the pending command.
  /// @returns (HTTP status, message)
  std::pair<int, std::string> post_command(const std::string& body) {
    nlohmann::json j = nlohmann::json::parse(body, nullptr, /*allow_exceptions=*/false);
    if (j.is_discarded())
      return {400, "malformed JSON: expected {\"vx\": .., \"vy\": .., \"wz\": ..}"};
    if (!j.is_object()) return {400, "expected a JSON object {\"vx\", \"vy\", \"wz\"}"};
    Eigen::Vector3d c = Eigen::Vector3d::Zero();
    const char* names[3] = {"vx", "vy", "wz"};
    for (const auto& item : j.items()) {
      const std::string& key = item.key();
      if (key != "vx" && key != "vy" && key != "wz") {
        return {400, "unknown key '" + key + "': expected vx, vy, wz"};
      }
    }
    for (int i = 0; i < 3; ++i) {
      if (!j.contains(names[i])) continue;  // a missing velocity is 0
      const nlohmann::json& v = j[names[i]];
      if (!v.is_number()) return {400, std::string(names[i]) + ": expected a number"};
      const double x = v.get<double>();
      if (!std::isfinite(x)) return {400, std::string(names[i]) + ": expected a finite number"};
      if (std::abs(x) > max_command_[i]) {
        return {400, std::string(names[i]) + ": " + std::to_string(x) + " is beyond the limit " +
                         std::to_string(max_command_[i])};
      }
      c[i] = x;
    }
    std::lock_guard<std::mutex> lock(mutex_);
    command_ = c;
    return {200, "ok"};
  }
  void post_stop() {
    std::lock_guard<std::mutex> lock(mutex_);
    stop_ = true;
    command_ = std::nullopt;
  }

 private:
  const Eigen::Vector3d max_command_;
  mutable std::mutex mutex_;
  std::condition_variable changed_;
  std::string state_ = "{}";
  long generation_ = 0;
  std::string rgb_, depth_, camera_message_ = "no image yet";
  std::optional<Eigen::Vector3d> command_;
  bool stop_ = false;
  bool closed_ = false;
};

/// The CSV logs of a training run in `dir` (examples/ppo_train's learning_<env>.csv,
/// python/bc_train.py's training_log.csv, or any CSV of numbers with a header) as JSON:
/// {"enabled", "dir", "files": [{"name", "columns", "rows"}]}, the last kMaxRows rows of each, at
/// most kMaxFiles files (newest first). A row that is not all numbers is left out; a file that
/// cannot be read is listed with its "message". Read on each request: the run writes them as it
/// goes.
inline nlohmann::json training_logs(const std::string& dir) {
  constexpr std::size_t kMaxFiles = 8, kMaxRows = 2000;
  constexpr std::uintmax_t kMaxBytes = 8u << 20;
  namespace fs = std::filesystem;
  nlohmann::json out{{"enabled", true}, {"dir", dir}, {"files", nlohmann::json::array()}};
  std::error_code ec;
  std::vector<fs::directory_entry> csvs;
  for (const auto& e : fs::directory_iterator(dir, ec)) {
    if (e.is_regular_file(ec) && e.path().extension() == ".csv") csvs.push_back(e);
  }
  if (ec) {
    out["message"] = "cannot read the folder: " + ec.message();
    return out;
  }
  std::sort(csvs.begin(), csvs.end(), [](const auto& a, const auto& b) {
    std::error_code e1, e2;
    return a.last_write_time(e1) > b.last_write_time(e2);
  });
  if (csvs.size() > kMaxFiles) csvs.resize(kMaxFiles);
  for (const auto& e : csvs) {
    nlohmann::json file{{"name", e.path().filename().string()}};
    std::ifstream in(e.path());
    std::string line;
    if (e.file_size(ec) > kMaxBytes || !in || !std::getline(in, line)) {
      file["message"] = "not read: empty, unreadable or over 8 MB";
      out["files"].push_back(file);
      continue;
    }
    std::vector<std::string> columns;
    std::stringstream header(line);
    for (std::string c; std::getline(header, c, ',');) columns.push_back(c);
    std::deque<std::vector<double>> rows;
    while (std::getline(in, line)) {
      std::vector<double> row;
      std::stringstream cells(line);
      bool numbers = true;
      for (std::string c; std::getline(cells, c, ',');) {
        char* end = nullptr;
        const double v = std::strtod(c.c_str(), &end);
        numbers = numbers && end != c.c_str() && *end == '\0' && std::isfinite(v);
        row.push_back(v);
      }
      if (!numbers || row.size() != columns.size()) continue;
      rows.push_back(std::move(row));
      if (rows.size() > kMaxRows) rows.pop_front();
    }
    file["columns"] = columns;
    file["rows"] = rows;
    out["files"].push_back(file);
  }
  return out;
}

/// The page's files, served from memory (examples/dashboard/web/, embedded at build time).
struct Asset {
  const char* path;
  const char* content_type;
  const char* body;
};

/// Routes of the dashboard on `server` (docs/dashboard.md lists them).
/// `training_dir`: the folder of GET /api/training (empty: none, {"enabled": false}).
template <std::size_t N>
void add_routes(httplib::Server& server, Board& board, const Asset (&assets)[N],
                std::chrono::milliseconds event_period, const std::string& training_dir) {
  server.set_payload_max_length(kMaxBody);
  for (const Asset& a : assets) {
    server.Get(a.path, [a](const httplib::Request&, httplib::Response& res) {
      res.set_content(a.body, a.content_type);
      res.set_header("Cache-Control", "no-cache");
    });
  }
  server.Get("/api/state", [&board](const httplib::Request&, httplib::Response& res) {
    res.set_content(board.state(), "application/json");
  });
  server.Post("/api/command", [&board](const httplib::Request& req, httplib::Response& res) {
    const auto [status, message] = board.post_command(req.body);
    res.status = status;
    res.set_content(
        nlohmann::json{{"status", status == 200 ? "ok" : "error"}, {"message", message}}.dump(),
        "application/json");
  });
  server.Get("/api/training", [training_dir](const httplib::Request&, httplib::Response& res) {
    if (training_dir.empty()) {  // 200, so that the page's check logs no error
      res.set_content(R"({"enabled":false,"message":"no training log: start with --training DIR"})",
                      "application/json");
      return;
    }
    res.set_content(training_logs(training_dir).dump(), "application/json");
  });
  server.Post("/api/stop", [&board](const httplib::Request&, httplib::Response& res) {
    board.post_stop();
    res.set_content(R"({"status":"ok","message":"stopping"})", "application/json");
  });
  server.Get(R"(/api/camera/(rgb|depth)\.jpg)",
             [&board](const httplib::Request& req, httplib::Response& res) {
               const auto [jpeg, why] = board.image(req.matches[1]);
               if (jpeg.empty()) {
                 res.status = 503;
                 res.set_content(nlohmann::json{{"status", "error"}, {"message", why}}.dump(),
                                 "application/json");
                 return;
               }
               res.set_content(jpeg, "image/jpeg");
               res.set_header("Cache-Control", "no-store");
             });
  // Server-sent events: each new state as "data: <json>\n\n", at most once per event_period.
  server.Get(
      "/api/events", [&board, event_period](const httplib::Request&, httplib::Response& res) {
        auto generation = std::make_shared<long>(-1);
        res.set_header("Cache-Control", "no-store");
        res.set_chunked_content_provider(
            "text/event-stream",
            [&board, generation, event_period](std::size_t, httplib::DataSink& sink) {
              const auto next = std::chrono::steady_clock::now() + event_period;
              auto [state, g] = board.next_state(*generation, std::chrono::milliseconds(500));
              if (state.empty()) {  // the server is closing
                sink.done();
                return false;
              }
              if (g != *generation) {
                *generation = g;
                const std::string event = "data: " + state + "\n\n";
                if (!sink.write(event.data(), event.size())) return false;  // the client left
              } else if (!sink.write(": keep-alive\n\n", 14)) {
                return false;
              }
              std::this_thread::sleep_until(next);
              return true;
            });
      });
  server.set_exception_handler(
      [](const httplib::Request&, httplib::Response& res, std::exception_ptr) {
        res.status = 500;
        res.set_content(R"({"status":"error","message":"internal error"})", "application/json");
      });
}

}  // namespace walkgen_dashboard
