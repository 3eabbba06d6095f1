// Streaming training data (model/src/data/view_stream.h): the stream's batches equal the batches of
// the views held in memory (the reader before streaming), whatever the worker count and read-
// ahead, from any batch of an epoch (resume); the number of decoded views alive never exceeds
// batch x (prefetch + 1), and reaches it (the workers read ahead); a worker's error arrives as
// thrown.
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <thread>

#include "augment.h"
#include "data.h"
#include "phyir/core/error.h"
#include "synthetic_view.h"
#include "torch_dataset.h"
#include "view_census.h"
#include "view_stream.h"

namespace pm = phyir::model;
namespace fs = std::filesystem;

namespace {

constexpr int kViews = 8;
constexpr uint64_t kSeed = 7;

pm::ModelConfig config() {
  pm::ModelConfig c;
  c.input_height = 32;
  c.input_width = 64;
  c.render_height = 16;
  c.render_width = 32;
  c.probe_height = 4;
  c.probe_width = 8;
  return c;
}

fs::path dataset() {
  static const fs::path root = [] {
    const fs::path r = fs::temp_directory_path() / ("phyir_model_stream_" + std::to_string(::getpid()));
    fs::remove_all(r);
    for (int k = 0; k < kViews; ++k) synthetic::write_view(r / ("room" + std::to_string(k / 3)) / ("v" + std::to_string(k)), k);
    return r;
  }();
  return root;
}

class CleanUp : public ::testing::Environment {
 public:
  void TearDown() override {
    std::error_code ec;
    fs::remove_all(fs::temp_directory_path() / ("phyir_model_stream_" + std::to_string(::getpid())), ec);
  }
};
::testing::Environment* const clean_up = ::testing::AddGlobalTestEnvironment(new CleanUp);

pm::ManifestDataset views() {
  return pm::ManifestDataset::for_training(dataset(), "", 0, config(), phyir::view::RadianceUnits::kInput);
}

pm::TrainingBatches batches(const pm::ManifestDataset& v, const pm::AugmentOptions& augment = {}) {
  return pm::TrainingBatches(v, augment, pm::yaw_divisions(config()), kSeed, phyir::view::RadianceUnits::kInput);
}

// Every batch of `epoch` from `first` on, as the stream hands them over.
std::vector<pm::Batch> stream_epoch(int workers, int prefetch, int epoch, int64_t first, int64_t batch) {
  pm::BatchStream stream(batches(views()), {workers, prefetch});
  std::vector<pm::Batch> out;
  stream.run_epoch(epoch, pm::epoch_order(kViews, kSeed, epoch), first, batch, [&](pm::Batch b) {
    out.push_back(std::move(b));
    return true;
  });
  return out;
}

bool same_batch(const pm::Batch& a, const pm::Batch& b) {
  if (a.ids != b.ids) return false;
  for (torch::Tensor pm::Batch::*m :
       {&pm::Batch::index, &pm::Batch::image, &pm::Batch::depth, &pm::Batch::normal, &pm::Batch::base_color,
        &pm::Batch::roughness, &pm::Batch::metalness, &pm::Batch::mask, &pm::Batch::mask_emissive,
        &pm::Batch::mask_transparent, &pm::Batch::color_lo, &pm::Batch::render_mask, &pm::Batch::probes,
        &pm::Batch::probe_mask}) {
    if ((a.*m).defined() != (b.*m).defined()) return false;
    if ((a.*m).defined() && !torch::equal(a.*m, b.*m)) return false;
  }
  return true;
}

}  // namespace

TEST(ModelStream, BatchesEqualTheInMemoryBatchesWhateverTheWorkers) {
  // Before streaming: every view loaded once, each batch augmented and stacked from memory.
  std::vector<pm::ViewTensors> all;
  pm::ManifestDataset d = views();
  for (size_t i = 0; i < kViews; ++i) all.push_back(d.get(i));
  const int64_t batch = 3;  // 8 views: batches of 3, 3, 2
  for (int epoch : {0, 1}) {
    const std::vector<size_t> order = pm::epoch_order(kViews, kSeed, epoch);
    std::vector<pm::Batch> expected;
    for (size_t k = 0; k * batch < order.size(); ++k) {
      const std::vector<size_t> idx(order.begin() + k * batch,
                                    order.begin() + std::min<size_t>(order.size(), (k + 1) * batch));
      expected.push_back(pm::augmented_batch(all, idx, pm::AugmentOptions{}, pm::yaw_divisions(config()), kSeed,
                                             epoch, phyir::view::RadianceUnits::kInput));
    }
    for (auto [workers, prefetch] : std::vector<std::pair<int, int>>{{0, 1}, {1, 1}, {2, 2}, {2, 5}}) {
      const std::vector<pm::Batch> got = stream_epoch(workers, prefetch, epoch, 0, batch);
      ASSERT_EQ(got.size(), expected.size());
      for (size_t k = 0; k < got.size(); ++k)
        EXPECT_TRUE(same_batch(got[k], expected[k])) << "epoch " << epoch << " batch " << k << " workers " << workers;
      // A resumed epoch starts at its checkpoint's batch.
      const std::vector<pm::Batch> resumed = stream_epoch(workers, prefetch, epoch, 1, batch);
      ASSERT_EQ(resumed.size(), expected.size() - 1);
      for (size_t k = 0; k < resumed.size(); ++k) EXPECT_TRUE(same_batch(resumed[k], expected[k + 1]));
    }
  }
  // The augmentation is on: a batch differs from the views as loaded.
  EXPECT_FALSE(torch::equal(stream_epoch(2, 2, 0, 0, 1)[0].image, pm::collate({all[pm::epoch_order(kViews, kSeed, 0)[0]]}).image));
}

TEST(ModelStream, DecodedViewsAliveNeverExceedBatchTimesPrefetchPlusOne) {
  for (auto [workers, prefetch] : std::vector<std::pair<int, int>>{{1, 1}, {2, 1}, {2, 2}, {2, 3}}) {
    const int64_t batch = 2;
    const int64_t bound = batch * (prefetch + 1);
    pm::ManifestDataset d = views();
    auto census = std::make_shared<pm::ViewCensus>();
    d.count_views(census);
    pm::BatchStream stream(batches(d), {workers, prefetch});
    int64_t k = 0, max_seen = 0;
    stream.run_epoch(0, pm::epoch_order(kViews, kSeed, 0), 0, batch, [&](pm::Batch b) {
      // Wait (on a count, not a clock) until the workers have read the next `prefetch` batches
      // ahead of this one: then the census must stand at the bound, and never above it.
      const int64_t ahead = std::min<int64_t>(kViews, (k + 1 + prefetch) * batch);
      const auto give_up = std::chrono::steady_clock::now() + std::chrono::seconds(120);
      while (census->decoded() < ahead && std::chrono::steady_clock::now() < give_up)
        std::this_thread::sleep_for(std::chrono::milliseconds(1));
      EXPECT_EQ(census->decoded(), ahead) << "step " << k;
      max_seen = std::max(max_seen, census->alive());
      EXPECT_EQ(static_cast<int64_t>(b.census.size()), batch);
      ++k;
      return true;
    });
    EXPECT_EQ(k, kViews / batch);
    EXPECT_EQ(census->decoded(), kViews);
    EXPECT_LE(census->peak(), bound) << workers << " workers, prefetch " << prefetch;
    EXPECT_EQ(max_seen, std::min<int64_t>(bound, kViews)) << "the workers did not read ahead";
    EXPECT_EQ(census->alive(), 0) << "views still alive after the epoch";
  }
  // The census sees a consumer that keeps its batches: it counts every view then.
  pm::ManifestDataset d = views();
  auto census = std::make_shared<pm::ViewCensus>();
  d.count_views(census);
  pm::BatchStream stream(batches(d), {2, 1});
  std::vector<pm::Batch> kept;
  stream.run_epoch(0, pm::epoch_order(kViews, kSeed, 0), 0, 2, [&](pm::Batch b) {
    kept.push_back(std::move(b));
    return true;
  });
  EXPECT_EQ(census->peak(), kViews);
  kept.clear();
  EXPECT_EQ(census->alive(), 0);
}

TEST(ModelStream, StopsEarlyAndRethrowsAWorkersErrorAsThrown) {
  pm::BatchStream stream(batches(views()), {2, 2});
  int steps = 0;
  stream.run_epoch(0, pm::epoch_order(kViews, kSeed, 0), 0, 2, [&](pm::Batch) { return ++steps < 2; });
  EXPECT_EQ(steps, 2);
  // A view whose depth.exr is gone: the loader's own message, not torch's wrapper.
  const fs::path broken = fs::temp_directory_path() / ("phyir_model_stream_" + std::to_string(::getpid())) / "broken";
  fs::remove_all(broken);
  synthetic::write_view(broken / "a", 0);
  synthetic::write_view(broken / "b", 1);
  fs::remove(broken / "b" / "depth.exr");
  pm::BatchStream bad(pm::TrainingBatches(pm::ManifestDataset::for_training(broken, "", 0, config(),
                                                                           phyir::view::RadianceUnits::kInput),
                                          {}, pm::yaw_divisions(config()), kSeed, phyir::view::RadianceUnits::kInput),
                      {2, 2});
  try {
    bad.run_epoch(0, {0, 1}, 0, 1, [](pm::Batch) { return true; });
    ADD_FAILURE() << "no error";
  } catch (const phyir::Error& e) {
    EXPECT_NE(std::string(e.what()).find("depth.exr: missing"), std::string::npos) << e.what();
  }
  EXPECT_THROW(pm::BatchStream(batches(views()), {-1, 2}), phyir::Error);
  EXPECT_THROW(pm::BatchStream(batches(views()), {2, 0}), phyir::Error);
}

// The measurement behind docs/model-scale.md "Streaming" (not a check: run by hand).
//   PHYIR_MEASURE_DATA=DIR PHYIR_MEASURE_MODE=stream|memory [PHYIR_MEASURE_VIEWS=N] [PHYIR_MEASURE_BATCHES=K]
//   /usr/bin/time -v model_test --gtest_also_run_disabled_tests --gtest_filter='*MeasureReaderMemory'
// reads DIR's views at the paper's sizes (input 256x512, render 128x256, probes 16x32) with
// probes, as the lnet stage does: streamed in batches of 4 (2 workers, 2 ahead) through a
// consumer that sums each batch and waits for the read-ahead to fill (the first K batches of the
// epoch), or all held in memory as training did before streaming.
TEST(ModelStream, DISABLED_MeasureReaderMemory) {
  const char* data = std::getenv("PHYIR_MEASURE_DATA");
  const char* mode = std::getenv("PHYIR_MEASURE_MODE");
  if (!data || !mode) GTEST_SKIP() << "PHYIR_MEASURE_DATA and PHYIR_MEASURE_MODE not set";
  const char* count = std::getenv("PHYIR_MEASURE_VIEWS");
  const char* batches = std::getenv("PHYIR_MEASURE_BATCHES");
  const int64_t max_batches = batches ? std::atoll(batches) : 0;
  pm::ModelConfig paper;
  paper.input_height = 256;
  paper.input_width = 512;
  paper.render_height = 128;
  paper.render_width = 256;
  paper.probe_height = 16;
  paper.probe_width = 32;
  pm::ManifestDataset d = pm::ManifestDataset::for_training(data, "", count ? std::atoi(count) : 0, paper,
                                                            phyir::view::RadianceUnits::kInput);
  auto census = std::make_shared<pm::ViewCensus>();
  d.count_views(census);
  const size_t n = d.size().value();
  const auto t0 = std::chrono::steady_clock::now();
  double checksum = 0.0;
  int64_t view_bytes = 0;
  if (std::string(mode) == "memory") {
    std::vector<pm::ViewTensors> all;
    for (size_t i = 0; i < n; ++i) all.push_back(d.get(i));
    for (torch::Tensor pm::ViewTensors::*m :
         {&pm::ViewTensors::image, &pm::ViewTensors::depth, &pm::ViewTensors::normal, &pm::ViewTensors::base_color,
          &pm::ViewTensors::roughness, &pm::ViewTensors::metalness, &pm::ViewTensors::mask,
          &pm::ViewTensors::mask_emissive, &pm::ViewTensors::mask_transparent, &pm::ViewTensors::color_lo,
          &pm::ViewTensors::render_mask, &pm::ViewTensors::probes, &pm::ViewTensors::probe_mask})
      view_bytes += static_cast<int64_t>((all[0].*m).nbytes());
    for (const auto& v : all) checksum += v.probes.sum().item<double>();
  } else {
    pm::BatchStream stream(pm::TrainingBatches(d, {}, pm::yaw_divisions(paper), kSeed, phyir::view::RadianceUnits::kInput),
                           {2, 2});
    // Each step waits until the read-ahead is full, as a training step slower than reading does.
    int64_t k = 0;
    stream.run_epoch(0, pm::epoch_order(n, kSeed, 0), 0, 4, [&](pm::Batch b) {
      checksum += b.probes.sum().item<double>();
      while (census->decoded() < std::min<int64_t>(n, (k + 3) * 4))
        std::this_thread::sleep_for(std::chrono::milliseconds(10));
      return max_batches <= 0 || ++k < max_batches;
    });
  }
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  std::ifstream status("/proc/self/status");
  std::string line, hwm;
  while (std::getline(status, line))
    if (line.rfind("VmHWM", 0) == 0) hwm = line;
  const size_t read = static_cast<size_t>(census->decoded());
  std::printf("measure %s: %zu views in the dataset, %zu read, %.1f s (%.2f s/view read), census peak %lld views, %s, one view %.1f MB, checksum %g\n",
              mode, n, read, seconds, seconds / read, static_cast<long long>(census->peak()), hwm.c_str(), view_bytes / 1e6,
              checksum);
}
