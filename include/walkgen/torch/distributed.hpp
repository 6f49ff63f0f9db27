#pragma once
/// @file
/// Data-parallel PPO across processes and machines on PyTorch's c10d: walkgen::PpoCommunicator
/// implemented by a Gloo process group (c10d::ProcessGroupGloo) that meets at a TCPStore, as
/// torchrun's processes do. Each process steps its share of the environments; TorchPpo sums the
/// advantage statistics and the gradients of the processes' loss shares over the group
/// (walkgen/torch/ppo.hpp).
///
/// Network: rank 0's TCPStore listens on master_port on every interface (c10d 1.13 has no
/// setting for its listening address), so use a port that a firewall keeps private; Gloo's own
/// connections follow the device rule below. A one-process run starts no server.
///
/// Target walkgen::torch_distributed (CMake option WALKGEN_WITH_DISTRIBUTED: libtorch plus
/// Debian's libgloo-dev, which holds the Gloo headers that libtorch's c10d headers include).
///
/// @code
///   walkgen::DistributedSettings d = walkgen::distributed_settings_from_environment();
///   walkgen::TorchGlooCommunicator group(d);   // waits for every rank (d.timeout)
///   ppo.set_communicator(&group);             // rank 0's weights reach every rank
/// @endcode
/// The rendezvous follows torchrun's environment variables: RANK, WORLD_SIZE, MASTER_ADDR,
/// MASTER_PORT; rank 0 serves the TCPStore at MASTER_ADDR:MASTER_PORT. Gloo's own connections
/// use the loopback device when MASTER_ADDR is a loopback address, the interface named by
/// GLOO_SOCKET_IFNAME when set, and otherwise the address this machine's hostname resolves to.

#ifndef USE_C10D_GLOO
#define USE_C10D_GLOO 1
#endif

#include <torch/torch.h>
#include <torch/csrc/distributed/c10d/ProcessGroupGloo.hpp>
#include <torch/csrc/distributed/c10d/TCPStore.hpp>

#include <chrono>
#include <climits>
#include <cstdint>
#include <cstdlib>
#include <string>
#include <vector>

#include "walkgen/core/decimal.hpp"
#include "walkgen/core/exceptions.hpp"
#include "walkgen/torch/ppo.hpp"

namespace walkgen {

/// Where and who a process is in a distributed run.
struct DistributedSettings {
  int rank = 0;                           ///< this process, 0 … world_size − 1
  int world_size = 1;                     ///< processes in the run
  std::string master_addr = "127.0.0.1";  ///< rank 0's address (the TCPStore)
  int master_port = 29500;                ///< the TCPStore's port, 1 … 65535
  std::chrono::seconds timeout{120};      ///< waiting for the other ranks, and for each collective
};

/// Checks the settings. @throws walkgen::invalid_argument naming the first bad field.
inline void validate(const DistributedSettings& s) {
  check_argument(s.world_size >= 1, "DistributedSettings.world_size", "at least 1", s.world_size);
  check_argument(s.rank >= 0 && s.rank < s.world_size, "DistributedSettings.rank",
                 "a rank in [0, world_size - 1] = [0, " + std::to_string(s.world_size - 1) + "]",
                 s.rank);
  check_argument(!s.master_addr.empty(), "DistributedSettings.master_addr", "an address",
                 "an empty one");
  check_argument(s.master_port >= 1 && s.master_port <= 65535, "DistributedSettings.master_port",
                 "a port in [1, 65535]", s.master_port);
  check_argument(s.timeout.count() >= 1, "DistributedSettings.timeout", "at least 1 s",
                 static_cast<long long>(s.timeout.count()));
}

namespace detail {
/// A decimal integer of an environment variable, or `fallback` when it is unset.
inline int environment_integer(const char* name, int fallback, unsigned long long max) {
  const char* text = std::getenv(name);
  if (text == nullptr) return fallback;
  unsigned long long value = 0;
  check_argument(parse_decimal(text, max, &value, /*allow_plus=*/false), name,
                 "a whole number in [0, " + std::to_string(max) + "]",
                 std::string("'") + text + "'");
  return static_cast<int>(value);
}
}  // namespace detail

/// The settings from torchrun's environment variables RANK, WORLD_SIZE, MASTER_ADDR and
/// MASTER_PORT; an unset one keeps the value of `defaults`.
/// @throws walkgen::invalid_argument naming a variable that is not a number in range.
[[nodiscard]] inline DistributedSettings distributed_settings_from_environment(
    DistributedSettings defaults = {}) {
  defaults.rank = detail::environment_integer("RANK", defaults.rank, INT_MAX);
  defaults.world_size = detail::environment_integer("WORLD_SIZE", defaults.world_size, INT_MAX);
  if (const char* addr = std::getenv("MASTER_ADDR")) defaults.master_addr = addr;
  defaults.master_port = detail::environment_integer("MASTER_PORT", defaults.master_port, 65535);
  validate(defaults);
  return defaults;
}

/// A c10d Gloo process group as walkgen::PpoCommunicator. Constructing it waits until every
/// rank has joined (at most DistributedSettings::timeout).
class TorchGlooCommunicator final : public PpoCommunicator {
 public:
  /// @throws walkgen::invalid_argument on bad settings, or when the ranks cannot meet in time
  ///   (the message names the address and port).
  explicit TorchGlooCommunicator(const DistributedSettings& settings) : s_(settings) {
    validate(s_);
    try {
      c10d::TCPStoreOptions store;
      store.port = static_cast<std::uint16_t>(s_.master_port);
      store.isServer = s_.rank == 0;
      store.numWorkers = static_cast<std::size_t>(s_.world_size);
      store.waitWorkers = true;
      store.timeout = std::chrono::duration_cast<std::chrono::milliseconds>(s_.timeout);
      store_ = c10::make_intrusive<c10d::TCPStore>(s_.master_addr, store);
      auto options = c10d::ProcessGroupGloo::Options::create(
          std::chrono::duration_cast<std::chrono::milliseconds>(s_.timeout));
      options->devices.push_back(device());
      group_ = c10::make_intrusive<c10d::ProcessGroupGloo>(store_, s_.rank, s_.world_size, options);
    } catch (const std::exception& e) {
      throw invalid_argument(detail::expected_got(
          "TorchGlooCommunicator",
          "rank " + std::to_string(s_.rank) + " of " + std::to_string(s_.world_size) +
              " to meet the others at " + s_.master_addr + ":" + std::to_string(s_.master_port),
          std::string("the error: ") + first_line(e.what()),
          "is every rank started with the same WORLD_SIZE, MASTER_ADDR and MASTER_PORT?"));
    }
  }

  [[nodiscard]] int rank() const override { return s_.rank; }
  [[nodiscard]] int world_size() const override { return s_.world_size; }

  /// @throws walkgen::invalid_argument when a rank is gone (the collective timed out).
  void allreduce_sum(torch::Tensor& tensor) override {
    std::vector<torch::Tensor> t{tensor};
    run("allreduce", [&] { group_->allreduce(t)->wait(); });
  }
  /// @throws walkgen::invalid_argument when a rank is gone (the collective timed out).
  void broadcast(torch::Tensor& tensor) override {
    std::vector<torch::Tensor> t{tensor};
    run("broadcast", [&] { group_->broadcast(t)->wait(); });
  }
  /// Waits until every rank has arrived here.
  void barrier() {
    run("barrier", [&] { group_->barrier()->wait(); });
  }

 private:
  std::shared_ptr<::gloo::transport::Device> device() const {
    if (const char* name = std::getenv("GLOO_SOCKET_IFNAME"))
      return c10d::ProcessGroupGloo::createDeviceForInterface(name);
    const std::string& a = s_.master_addr;
    if (a == "localhost" || a.rfind("127.", 0) == 0 || a == "::1")
      return c10d::ProcessGroupGloo::createDeviceForHostname("127.0.0.1");
    return c10d::ProcessGroupGloo::createDefaultDevice();
  }
  template <class F>
  void run(const char* what, F&& f) {
    try {
      f();
    } catch (const std::exception& e) {
      throw invalid_argument(detail::expected_got(
          "TorchGlooCommunicator",
          std::string(what) + " over " + std::to_string(s_.world_size) + " ranks",
          std::string("the error: ") + first_line(e.what()), "did another rank stop?"));
    }
  }
  static std::string first_line(const std::string& text) { return text.substr(0, text.find('\n')); }

  DistributedSettings s_;
  c10::intrusive_ptr<c10d::Store> store_;
  c10::intrusive_ptr<c10d::ProcessGroupGloo> group_;
};

}  // namespace walkgen
