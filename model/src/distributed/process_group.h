#pragma once
// Data-parallel training's process group: c10d with Gloo, as Debian's LibTorch ships it. Says
// which rank this process is, how the ranks meet (a store file on a shared file system, or a
// TCP store that rank 0 serves), and runs the few collectives training needs. Every collective
// has the group's timeout, so a rank that died or hangs ends the others with an error naming
// the operation, not a hang. Private header (torch types). Docs: docs/model-scale.md "Training on
// several processes".
#include <torch/torch.h>

#include <chrono>
#include <functional>
#include <memory>
#include <string>

#include "phyir/model/training.h"

namespace phyir::model {

class ProcessGroup {
 public:
  // Blocks until every rank joined (or the timeout). Throws phyir::Error naming the
  // rendezvous and the reason. (The trainer makes a group for 2 ranks or more; tests also
  // make one of 1.)
  static std::unique_ptr<ProcessGroup> join(const DistributedOptions& options);
  ~ProcessGroup();

  int rank() const { return rank_; }
  int size() const { return size_; }

  // In place on every rank: the elementwise sum / maximum over ranks, or rank `root`'s
  // values. Any device: tensors off the CPU go through a CPU copy (Gloo is CPU code here).
  void sum(torch::Tensor& t, const char* what);
  void max(torch::Tensor& t, const char* what);
  void broadcast(torch::Tensor& t, int root, const char* what);
  void barrier(const char* what);

 private:
  struct Gloo;  // the c10d store and group (process_group.cpp: keeps Gloo's headers there)
  ProcessGroup(const DistributedOptions& options, std::unique_ptr<Gloo> gloo);
  // Runs one collective; a Gloo error (a peer gone, a timeout) becomes a phyir::Error.
  void run(const char* operation, const char* what, const std::function<void()>& collective);

  int rank_ = 0, size_ = 1;
  int timeout_seconds_ = 0;
  std::string rendezvous_;
  std::unique_ptr<Gloo> gloo_;
};

}  // namespace phyir::model
