// ManifestDataset (model/src/data/torch_dataset.h) on a tiny dataset made by the real pipeline
// (`phyir scenes generate` + `phyir dataset generate --preset tiny`, probes included):
// shapes, value ranges, every tensor equal to its EXR/PNG file (read here with OIIO and
// indexed by hand), area averaging at half resolution, splits as in the manifest, and a
// DataLoader with a RandomSampler visiting each example exactly once.
#include <unistd.h>

#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <set>

#include "phyir/core/error.h"
#include "phyir/core/image.h"
#include "phyir/core/image_io.h"
#include "torch_dataset.h"

namespace pm = phyir::model;
namespace fs = std::filesystem;
using nlohmann::json;

namespace {

// The tiny preset: 64 x 32 panoramas, an 8 x 16 grid of 4 x 8 texel probes.
constexpr int kH = 32, kW = 64, kGh = 8, kGw = 16, kPh = 4, kPw = 8;
const pm::ExampleSize kNative{kH, kW, kGh, kGw, kPh, kPw};

class TorchDataset : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    const fs::path bin = PHYIR_BINARY;
    if (!fs::is_regular_file(bin)) return;
    root_ = fs::temp_directory_path() / ("phyir_torch_dataset_" + std::to_string(::getpid()));
    fs::remove_all(root_);
    fs::create_directories(root_);
    const std::string log = " > " + (root_ / "log.txt").string() + " 2>&1";
    // Three scenes so the 0.34/0.33/0.33 split has a fair chance of using several splits.
    ok_ = std::system((bin.string() + " scenes generate --out " + (root_ / "rooms").string() +
                       " --count 3 --seed 2 --preset mini" + log).c_str()) == 0 &&
          std::system((bin.string() + " dataset generate --scenes " + (root_ / "rooms").string() + " --out " +
                       (root_ / "data").string() +
                       " --preset tiny --views-per-scene 2 --split 0.34,0.33,0.33 --threads 2 --quiet" + log)
                          .c_str()) == 0;
  }
  static void TearDownTestSuite() {
    if (!root_.empty()) fs::remove_all(root_);
  }
  void SetUp() override {
    if (root_.empty()) GTEST_SKIP() << PHYIR_BINARY << " not built";
    ASSERT_TRUE(ok_) << "generating the tiny dataset failed; see " << (root_ / "log.txt");
  }
  static fs::path data() { return root_ / "data"; }
  static json manifest() {
    std::ifstream in(data() / "manifest.json");
    return json::parse(in);
  }

  static inline fs::path root_;
  static inline bool ok_ = false;
};

// [C, H, W] of a file, element by element (no torch on the reading side).
torch::Tensor file_chw(const fs::path& path) {
  const phyir::Image im = phyir::read_image(path);
  torch::Tensor t = torch::empty({im.channels, im.height, im.width});
  auto a = t.accessor<float, 3>();
  for (int c = 0; c < im.channels; ++c)
    for (int y = 0; y < im.height; ++y)
      for (int x = 0; x < im.width; ++x) a[c][y][x] = im.at(x, y, c);
  return t;
}

void expect_binary(const torch::Tensor& m, const std::string& what) {
  EXPECT_TRUE(((m == 0) | (m == 1)).all().item<bool>()) << what << " is not 0/1";
}

TEST_F(TorchDataset, ShapesAndValueRanges) {
  pm::ManifestDataset all(data(), "", kNative);
  ASSERT_EQ(all.size().value(), 6u);
  const pm::DatasetExample e = all.get(0);
  EXPECT_EQ(e.id, "room_0/v000");
  EXPECT_EQ(e.index, 0);
  using S = std::vector<int64_t>;
  EXPECT_EQ(e.image.sizes().vec(), (S{3, kH, kW}));
  EXPECT_EQ(e.depth.sizes().vec(), (S{1, kH, kW}));
  EXPECT_EQ(e.normal.sizes().vec(), (S{3, kH, kW}));
  EXPECT_EQ(e.base_color.sizes().vec(), (S{3, kH, kW}));
  EXPECT_EQ(e.roughness.sizes().vec(), (S{1, kH, kW}));
  EXPECT_EQ(e.metalness.sizes().vec(), (S{1, kH, kW}));
  for (const auto* m : {&e.mask, &e.mask_emissive, &e.mask_transparent})
    EXPECT_EQ(m->sizes().vec(), (S{1, kH, kW}));
  EXPECT_EQ(e.color_lo.sizes().vec(), (S{3, kGh, kGw}));
  EXPECT_EQ(e.render_mask.sizes().vec(), (S{1, kGh, kGw}));
  ASSERT_TRUE(e.probes.defined());
  EXPECT_EQ(e.probes.sizes().vec(), (S{kGh, kGw, kPh, kPw, 3}));
  EXPECT_EQ(e.probe_mask.sizes().vec(), (S{1, kGh, kGw}));

  for (size_t i = 0; i < all.size().value(); ++i) {
    const pm::DatasetExample x = all.get(i);
    for (const auto* t : {&x.image, &x.base_color, &x.roughness, &x.metalness}) {
      EXPECT_GE(t->min().item<float>(), 0.0f) << x.id;
      EXPECT_LE(t->max().item<float>(), 1.0f) << x.id;
    }
    EXPECT_GE(x.depth.min().item<float>(), 0.0f);
    EXPECT_GE(x.color_lo.min().item<float>(), 0.0f);
    EXPECT_GE(x.probes.min().item<float>(), 0.0f);
    EXPECT_TRUE(torch::isfinite(x.probes).all().item<bool>());
    expect_binary(x.mask, "mask_geometry");
    expect_binary(x.mask_emissive, "mask_emissive");
    expect_binary(x.mask_transparent, "mask_transparent");
    expect_binary(x.render_mask, "render_mask");
    expect_binary(x.probe_mask, "probe_mask");
    // A room seen from inside: surfaces almost everywhere, unit normals there.
    EXPECT_GT(x.mask.mean().item<float>(), 0.9f) << x.id;
    const torch::Tensor len = x.normal.norm(2, 0, true);
    EXPECT_LT(((len - 1.0).abs() * x.mask).max().item<float>(), 1e-4f) << x.id;
  }
}

TEST_F(TorchDataset, ExamplesEqualTheFilesAtTheirOwnResolution) {
  pm::ManifestDataset all(data(), "", kNative);
  for (size_t i : {size_t(1), size_t(4)}) {
    const pm::DatasetExample e = all.get(i);
    const fs::path dir = data() / "views" / e.id;
    EXPECT_TRUE(torch::equal(e.image, file_chw(dir / "input.png"))) << e.id;
    EXPECT_TRUE(torch::equal(e.depth, file_chw(dir / "depth.exr"))) << e.id;
    EXPECT_TRUE(torch::equal(e.base_color, file_chw(dir / "basecolor.exr"))) << e.id;
    EXPECT_TRUE(torch::equal(e.roughness, file_chw(dir / "roughness.exr"))) << e.id;
    EXPECT_TRUE(torch::equal(e.metalness, file_chw(dir / "metalness.exr"))) << e.id;
    EXPECT_TRUE(torch::equal(e.mask, file_chw(dir / "mask_geometry.exr"))) << e.id;
    EXPECT_TRUE(torch::equal(e.mask_emissive, file_chw(dir / "mask_emissive.exr"))) << e.id;
    EXPECT_TRUE(torch::equal(e.mask_transparent, file_chw(dir / "mask_transparent.exr"))) << e.id;
    // Normals are re-normalised by the loader; the renderer's are unit already.
    EXPECT_TRUE(torch::allclose(e.normal, file_chw(dir / "normal.exr"), 0, 1e-5)) << e.id;

    // Colour at the probe grid (8 x 16): the mean of each 4 x 4 block of color.exr.
    const phyir::Image color = phyir::read_image(dir / "color.exr");
    auto c = e.color_lo.accessor<float, 3>();
    for (int y = 0; y < kGh; ++y)
      for (int x = 0; x < kGw; ++x)
        for (int ch = 0; ch < 3; ++ch) {
          double sum = 0;
          for (int dy = 0; dy < 4; ++dy)
            for (int dx = 0; dx < 4; ++dx) sum += color.at(4 * x + dx, 4 * y + dy, ch);
          EXPECT_NEAR(c[ch][y][x], sum / 16, 1e-5 * (1 + sum / 16)) << e.id << " " << x << "," << y;
        }

    // Probe (i, j) is the 4 x 8 block at rows 4i.., columns 8j.. of the mosaic.
    const phyir::Image mosaic = phyir::read_image(dir / "probes.exr");
    ASSERT_EQ(mosaic.width, kGw * kPw);
    ASSERT_EQ(mosaic.height, kGh * kPh);
    auto p = e.probes.accessor<float, 5>();
    int mismatches = 0;
    for (int i = 0; i < kGh; ++i)
      for (int j = 0; j < kGw; ++j)
        for (int a = 0; a < kPh; ++a)
          for (int b = 0; b < kPw; ++b)
            for (int ch = 0; ch < 3; ++ch) mismatches += p[i][j][a][b][ch] != mosaic.at(j * kPw + b, i * kPh + a, ch);
    EXPECT_EQ(mismatches, 0) << e.id;
    const phyir::Image pmask = phyir::read_image(dir / "probe_mask.exr");
    auto pm_ = e.probe_mask.accessor<float, 3>();
    auto rm = e.render_mask.accessor<float, 3>();
    for (int i = 0; i < kGh; ++i)
      for (int j = 0; j < kGw; ++j)
        EXPECT_EQ(pm_[0][i][j], (pmask.at(j, i) > 0.5f && rm[0][i][j] > 0) ? 1.0f : 0.0f) << i << "," << j;
  }
}

TEST_F(TorchDataset, HalfResolutionAveragesTwoByTwoBlocks) {
  pm::ManifestDataset half(data(), "", {kH / 2, kW / 2, kGh / 2, kGw / 2, kPh / 2, kPw / 2});
  const pm::DatasetExample e = half.get(2);
  ASSERT_EQ(e.depth.sizes().vec(), (std::vector<int64_t>{1, kH / 2, kW / 2}));
  ASSERT_EQ(e.probes.sizes().vec(), (std::vector<int64_t>{kGh / 2, kGw / 2, kPh / 2, kPw / 2, 3}));
  const fs::path dir = data() / "views" / e.id;
  const phyir::Image depth = phyir::read_image(dir / "depth.exr");
  const phyir::Image rough = phyir::read_image(dir / "roughness.exr");
  auto d = e.depth.accessor<float, 3>();
  auto r = e.roughness.accessor<float, 3>();
  for (int y = 0; y < kH / 2; ++y)
    for (int x = 0; x < kW / 2; ++x) {
      const auto box = [&](const phyir::Image& im) {
        return (im.at(2 * x, 2 * y) + im.at(2 * x + 1, 2 * y) + im.at(2 * x, 2 * y + 1) + im.at(2 * x + 1, 2 * y + 1)) /
               4.0;
      };
      EXPECT_NEAR(d[0][y][x], box(depth), 1e-5 * (1 + box(depth)));
      EXPECT_NEAR(r[0][y][x], box(rough), 1e-6);
    }
  // Probes: the grid is sampled at the nearest probe (no blending of probes at different
  // positions), each probe's texels area-averaged: half-grid probe (i, j) is probe (2i+1, 2j+1).
  const phyir::Image mosaic = phyir::read_image(dir / "probes.exr");
  auto p = e.probes.accessor<float, 5>();
  for (int i = 0; i < kGh / 2; ++i)
    for (int j = 0; j < kGw / 2; ++j)
      for (int a = 0; a < kPh / 2; ++a)
        for (int b = 0; b < kPw / 2; ++b) {
          const int row = (2 * i + 1) * kPh + 2 * a, col = (2 * j + 1) * kPw + 2 * b;
          const double want = (mosaic.at(col, row) + mosaic.at(col + 1, row) + mosaic.at(col, row + 1) +
                               mosaic.at(col + 1, row + 1)) / 4.0;
          EXPECT_NEAR(p[i][j][a][b][0], want, 1e-5 * (1 + want));
        }
}

TEST_F(TorchDataset, SplitsAreTheManifests) {
  const json m = manifest();
  size_t total = 0;
  for (const std::string split : {"train", "val", "test"}) {
    std::vector<std::string> want;
    for (const json& v : m["views"])
      if (v["split"] == split) want.push_back(v["id"]);
    if (want.empty()) {
      EXPECT_THROW({ pm::ManifestDataset empty(data(), split, kNative); }, phyir::Error) << split;
      continue;
    }
    pm::ManifestDataset d(data(), split, kNative);
    EXPECT_EQ(d.ids(), want) << split;
    total += d.size().value();
  }
  EXPECT_EQ(total, m["views"].size());
}

TEST_F(TorchDataset, RandomSamplerDataLoaderVisitsEveryExampleOnce) {
  pm::ManifestDataset dataset(data(), "", kNative);
  const std::vector<std::string> ids = dataset.ids();
  auto loader = torch::data::make_data_loader<torch::data::samplers::RandomSampler>(
      std::move(dataset), torch::data::DataLoaderOptions().batch_size(4).workers(2));
  for (int epoch = 0; epoch < 2; ++epoch) {
    std::multiset<int64_t> seen;
    size_t batches = 0;
    for (std::vector<pm::DatasetExample>& examples : *loader) {
      const pm::ExampleBatch b = pm::collate(examples);
      ++batches;
      const int64_t n = static_cast<int64_t>(examples.size());
      EXPECT_EQ(b.image.sizes().vec(), (std::vector<int64_t>{n, 3, kH, kW}));
      EXPECT_EQ(b.probes.sizes().vec(), (std::vector<int64_t>{n, kGh, kGw, kPh, kPw, 3}));
      for (int64_t k = 0; k < n; ++k) {
        const int64_t index = b.index[k].item<int64_t>();
        seen.insert(index);
        EXPECT_EQ(b.ids[size_t(k)], ids.at(size_t(index)));
      }
    }
    EXPECT_EQ(batches, 2u);  // 6 examples in batches of 4
    std::multiset<int64_t> want;
    for (int64_t i = 0; i < 6; ++i) want.insert(i);
    EXPECT_EQ(seen, want) << "epoch " << epoch;
  }
}

TEST_F(TorchDataset, RefusesAFolderWithoutAManifest) {
  const fs::path unfinished = root_ / "unfinished";
  fs::create_directories(unfinished / "views");
  try {
    pm::ManifestDataset d(unfinished, "train");
    FAIL() << "no error";
  } catch (const phyir::Error& e) {
    EXPECT_NE(std::string(e.what()).find("manifest.json"), std::string::npos) << e.what();
  }
}

}  // namespace
