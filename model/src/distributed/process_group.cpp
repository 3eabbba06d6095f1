// The Gloo process group of data-parallel training (process_group.h).
#include "process_group.h"

// Debian's LibTorch is built with Gloo; its c10d header declares the Gloo group only under this
// macro (the headers come from libgloo-dev).
#define USE_C10D_GLOO 1
#include <torch/csrc/distributed/c10d/FileStore.hpp>
#include <torch/csrc/distributed/c10d/ProcessGroupGloo.hpp>
#include <torch/csrc/distributed/c10d/TCPStore.hpp>

#include <filesystem>

#include "phyir/core/error.h"
#include "phyir/core/setting_error.h"
#include "phyir/core/log.h"

namespace phyir::model {

struct ProcessGroup::Gloo {
  c10::intrusive_ptr<c10d::Store> store;
  c10::intrusive_ptr<c10d::ProcessGroupGloo> group;
};

namespace {

struct TcpAddress {
  std::string host;
  uint16_t port = 0;
};

TcpAddress parse_tcp(const std::string& rendezvous) {
  const std::string rest = rendezvous.substr(4);
  const size_t colon = rest.rfind(':');
  if (colon == std::string::npos || colon == 0 || colon + 1 == rest.size())
    fail_setting("distributed.rendezvous", "'{}': expected tcp:HOST:PORT", rendezvous);
  int port = 0;
  try {
    size_t used = 0;
    port = std::stoi(rest.substr(colon + 1), &used);
    if (used != rest.size() - colon - 1) port = 0;
  } catch (const std::exception&) {
    port = 0;
  }
  if (port < 1 || port > 65535) fail_setting("distributed.rendezvous", "'{}': the port must be 1-65535", rendezvous);
  return {rest.substr(0, colon), static_cast<uint16_t>(port)};
}

c10::intrusive_ptr<c10d::Store> make_store(const DistributedOptions& o) {
  const std::chrono::milliseconds timeout(int64_t{1000} * o.timeout_seconds);
  if (o.rendezvous.rfind("file:", 0) == 0) {
    const std::string path = o.rendezvous.substr(5);
    if (path.empty()) fail_setting("distributed.rendezvous", "'{}': expected file:PATH", o.rendezvous);
    if (!std::filesystem::is_directory(std::filesystem::absolute(path).parent_path()))
      fail_setting("distributed.rendezvous", "'{}': the folder of {} does not exist", o.rendezvous, path);
    auto store = c10::make_intrusive<c10d::FileStore>(path, o.world_size);
    store->setTimeout(timeout);
    return store;
  }
  if (o.rendezvous.rfind("tcp:", 0) == 0) {
    const TcpAddress a = parse_tcp(o.rendezvous);
    c10d::TCPStoreOptions t;
    t.port = a.port;
    t.isServer = o.rank == 0;
    t.numWorkers = static_cast<size_t>(o.world_size);
    t.waitWorkers = true;
    t.timeout = timeout;
    return c10::make_intrusive<c10d::TCPStore>(a.host, t);
  }
  fail_setting("distributed.rendezvous", "'{}': expected file:PATH or tcp:HOST:PORT", o.rendezvous);
}

// This host's Gloo device: the address the host name resolves to, else the loopback device
// (a single machine without name resolution still trains).
std::shared_ptr<::gloo::transport::Device> make_device() {
  try {
    return c10d::ProcessGroupGloo::createDefaultDevice();
  } catch (const std::exception& e) {
    spdlog::warn("Gloo: no device for this host name ({}); using 127.0.0.1", e.what());
    return c10d::ProcessGroupGloo::createDeviceForHostname("127.0.0.1");
  }
}

}  // namespace

std::unique_ptr<ProcessGroup> ProcessGroup::join(const DistributedOptions& o) {
  if (o.world_size < 1) fail_setting("distributed.world_size", "{} must be at least 1", o.world_size);
  if (o.rank < 0 || o.rank >= o.world_size) fail_setting("distributed.rank", "{} must be in 0..{}", o.rank, o.world_size - 1);
  if (o.timeout_seconds < 1)
    fail_setting("distributed.timeout_seconds", "{} must be at least 1 second", o.timeout_seconds);
  auto gloo = std::make_unique<Gloo>();
  try {
    gloo->store = make_store(o);
    auto options = c10d::ProcessGroupGloo::Options::create();
    options->devices.push_back(make_device());
    options->timeout = std::chrono::milliseconds(int64_t{1000} * o.timeout_seconds);
    gloo->group = c10::make_intrusive<c10d::ProcessGroupGloo>(gloo->store, o.rank, o.world_size, options);
  } catch (const phyir::Error&) {
    throw;
  } catch (const std::exception& e) {
    fail("rank {} of {}: could not join the other ranks at {} within {} s: {}", o.rank, o.world_size,
         o.rendezvous, o.timeout_seconds, e.what());
  }
  return std::unique_ptr<ProcessGroup>(new ProcessGroup(o, std::move(gloo)));
}

ProcessGroup::ProcessGroup(const DistributedOptions& o, std::unique_ptr<Gloo> gloo)
    : rank_(o.rank), size_(o.world_size), timeout_seconds_(o.timeout_seconds), rendezvous_(o.rendezvous),
      gloo_(std::move(gloo)) {}

ProcessGroup::~ProcessGroup() = default;

void ProcessGroup::run(const char* operation, const char* what, const std::function<void()>& collective) {
  try {
    collective();
  } catch (const std::exception& e) {
    // Gloo says "Connection reset by peer" when a rank died, "Timed out" when one hangs.
    fail("rank {} of {}: {} of {} failed: {} (another rank died or did not arrive within the {} s timeout; "
         "see its log)",
         rank_, size_, operation, what, e.what(), timeout_seconds_);
  }
}

namespace {

// Gloo reduces CPU tensors: others are reduced through a contiguous CPU copy.
template <typename Op>
void on_cpu(torch::Tensor& t, Op op) {
  if (t.device().is_cpu() && t.is_contiguous()) {
    op(t);
    return;
  }
  torch::Tensor staged = t.to(torch::kCPU).contiguous();
  op(staged);
  t.copy_(staged);
}

}  // namespace

void ProcessGroup::sum(torch::Tensor& t, const char* what) {
  run("sum", what, [&] {
    on_cpu(t, [&](torch::Tensor& c) {
      std::vector<torch::Tensor> ts{c};
      gloo_->group->allreduce(ts)->wait();
    });
  });
}

void ProcessGroup::max(torch::Tensor& t, const char* what) {
  run("maximum", what, [&] {
    on_cpu(t, [&](torch::Tensor& c) {
      std::vector<torch::Tensor> ts{c};
      c10d::AllreduceOptions options;
      options.reduceOp = c10d::ReduceOp::MAX;
      gloo_->group->allreduce(ts, options)->wait();
    });
  });
}

void ProcessGroup::broadcast(torch::Tensor& t, int root, const char* what) {
  run("broadcast", what, [&] {
    on_cpu(t, [&](torch::Tensor& c) {
      std::vector<torch::Tensor> ts{c};
      c10d::BroadcastOptions options;
      options.rootRank = root;
      gloo_->group->broadcast(ts, options)->wait();
    });
  });
}

void ProcessGroup::barrier(const char* what) {
  run("barrier", what, [&] { gloo_->group->barrier()->wait(); });
}

}  // namespace phyir::model
