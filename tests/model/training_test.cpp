// Training stages, exact resume, the NaN stop and inference on a tiny synthetic dataset.
#include <unistd.h>

#include <fstream>

#include "data.h"
#include "nets.h"
#include "phyir/core/error.h"
#include "phyir/core/image_io.h"
#include "phyir/model/training.h"
#include "render_layer.h"

namespace pm = phyir::model;
namespace fs = std::filesystem;

namespace {

// A view folder as the dataset writes it, 64 x 32, probes on a 32 x 16 grid of 4 x 8 texels.
void write_view(const fs::path& dir, int seed) {
  fs::create_directories(dir);
  const int H = 32, W = 64, gh = 16, gw = 32, h = 4, w = 8;
  torch::manual_seed(seed);
  const auto dirs = pm::pixel_directions(H, W, torch::TensorOptions());  // [H,W,3]
  const auto d = dirs.permute({2, 0, 1});
  const auto depth = (2.0 + 0.5 * d[1] + 0.2 * seed).unsqueeze(0);
  const auto normal = -d;
  const auto base = torch::stack({0.5 + 0.3 * d[0], 0.4 + 0.1 * torch::rand({H, W}), torch::full({H, W}, 0.3 + 0.1 * seed)});
  const auto rough = (0.3 + 0.4 * (d[1] > 0).to(torch::kFloat)).unsqueeze(0);
  const auto metal = (d[0] > 0.5).to(torch::kFloat).unsqueeze(0);
  const auto color = base * (1.2 + 0.5 * d[1]);
  const auto tdirs = pm::pixel_directions(h, w, torch::TensorOptions());
  const auto probe = (1.0 + 0.5 * tdirs.select(-1, 1) + 0.1 * seed).view({1, 1, 1, h, w, 1}).expand({1, gh, gw, h, w, 3});
  pm::write_tensor_image(dir / "color.exr", color);
  pm::write_tensor_image(dir / "input.png", color.clamp(0.0, 1.0).pow(1.0 / 2.2));
  pm::write_tensor_image(dir / "depth.exr", depth, {"Y"});
  pm::write_tensor_image(dir / "normal.exr", normal, {"X", "Y", "Z"});
  pm::write_tensor_image(dir / "basecolor.exr", base);
  pm::write_tensor_image(dir / "roughness.exr", rough, {"Y"});
  pm::write_tensor_image(dir / "metalness.exr", metal, {"Y"});
  pm::write_tensor_image(dir / "mask_geometry.exr", torch::ones({1, H, W}), {"Y"});
  pm::write_tensor_image(dir / "probes.exr", pm::probes_to_mosaic(probe.contiguous())[0]);
  pm::write_tensor_image(dir / "probe_mask.exr", torch::ones({1, gh, gw}), {"Y"});
}

fs::path dataset() {
  static const fs::path root = [] {
    const fs::path r = fs::temp_directory_path() / ("phyir_model_test_data_" + std::to_string(::getpid()));
    fs::remove_all(r);
    write_view(r / "room0" / "view0", 0);
    write_view(r / "room0" / "view1", 1);
    write_view(r / "room1" / "view0", 2);
    return r;
  }();
  return root;
}

// Removes the test's scratch folders (checkpoints are tens of MB) when the suite ends.
class CleanUp : public ::testing::Environment {
 public:
  void TearDown() override {
    std::error_code ec;
    fs::remove_all(fs::temp_directory_path() / ("phyir_model_test_" + std::to_string(::getpid())), ec);
    fs::remove_all(fs::temp_directory_path() / ("phyir_model_test_data_" + std::to_string(::getpid())), ec);
  }
};
::testing::Environment* const clean_up = ::testing::AddGlobalTestEnvironment(new CleanUp);

fs::path scratch(const std::string& name) {
  const fs::path p = fs::temp_directory_path() / ("phyir_model_test_" + std::to_string(::getpid())) / name;
  fs::remove_all(p);
  return p;
}

pm::TrainOptions options(const std::string& out, pm::Stage stage) {
  pm::TrainOptions o;
  o.data_dir = dataset().string();
  o.out_dir = out;
  o.stage = stage;
  o.config.input_height = 32;
  o.config.input_width = 64;
  o.config.render_height = 16;
  o.config.render_width = 32;
  o.config.probe_height = 4;
  o.config.probe_width = 8;
  o.config.diffuse_samples = 4;
  o.config.specular_samples = 4;
  o.threads = 1;
  o.config.width_divisor = 4;
  o.progress = false;
  o.seed = 5;
  return o;
}

// Every parameter and buffer of the three networks in a checkpoint, flattened.
std::vector<torch::Tensor> checkpoint_tensors(const std::string& path) {
  torch::serialize::InputArchive archive;
  archive.load_from(path);
  std::vector<torch::Tensor> out;
  for (const char* name : {"gmnet", "lnet", "gsnet"}) {
    torch::serialize::InputArchive sub;
    archive.read(name, sub);
    std::shared_ptr<torch::nn::Module> m;
    if (std::string(name) == "gmnet") m = pm::GMNet(4).ptr();
    else if (std::string(name) == "lnet") m = pm::LNet(4, 8, 4).ptr();
    else m = pm::GSNet(2).ptr();
    m->load(sub);
    for (const auto& p : m->parameters()) out.push_back(p.detach().clone());
    for (const auto& b : m->buffers()) out.push_back(b.detach().clone());
  }
  return out;
}

bool same_tensors(const std::vector<torch::Tensor>& a, const std::vector<torch::Tensor>& b) {
  if (a.size() != b.size()) return false;
  for (size_t i = 0; i < a.size(); ++i)
    if (!torch::equal(a[i], b[i])) return false;
  return true;
}

}  // namespace

TEST(ModelData, LoadsViewFoldersAtNetworkResolution) {
  const auto folders = pm::find_view_folders(dataset());
  ASSERT_EQ(folders.size(), 3u);
  pm::ModelConfig c = options("", pm::Stage::kGMNet).config;
  const pm::ViewTensors v = pm::load_view(folders[0], c);
  EXPECT_EQ(v.image.sizes(), torch::IntArrayRef({3, 32, 64}));
  EXPECT_EQ(v.color_lo.sizes(), torch::IntArrayRef({3, 16, 32}));
  ASSERT_TRUE(v.probes.defined());
  EXPECT_EQ(v.probes.sizes(), torch::IntArrayRef({16, 32, 4, 8, 3}));
  // The probes hold 1 + 0.5 y at their texel centres.
  const auto tdirs = pm::pixel_directions(4, 8, torch::TensorOptions());
  EXPECT_NEAR(v.probes[3][5][1][2][0].item<float>(), 1.0 + 0.5 * tdirs[1][2][1].item<float>(), 1e-5);
  EXPECT_EQ(v.probe_mask.sum().item<float>(), 16 * 32);
}

TEST(ModelTrain, GMNetLossFallsAndResumeIsExact) {
  // A: 3 epochs straight. B: 1 epoch, then resume to 3. C: stop mid-epoch (step 2), resume to 3.
  const fs::path a = scratch("gm_a"), b = scratch("gm_b"), c = scratch("gm_c");
  pm::TrainOptions o = options(a.string(), pm::Stage::kGMNet);
  o.epochs = 3;
  o.batch_size = 2;
  o.learning_rate = 1e-3;
  o.plot_script = std::string(PHYIR_SOURCE_ROOT) + "/scripts/plot_training.py";
  const pm::TrainSummary sa = pm::train(o);
  EXPECT_EQ(sa.steps, 6);
  ASSERT_EQ(sa.epoch_losses.size(), 3u);
  std::printf("[ModelTrain] gmnet epoch losses %.5f %.5f %.5f\n", sa.epoch_losses[0], sa.epoch_losses[1], sa.epoch_losses[2]);
  EXPECT_LT(sa.last_loss, sa.first_loss);
  EXPECT_TRUE(fs::is_regular_file(a / "train_log.csv"));
  EXPECT_TRUE(fs::is_regular_file(a / "train_log.json"));
  EXPECT_TRUE(fs::is_regular_file(a / "loss_curve.png")) << "plot: " << sa.plot;

  pm::TrainOptions ob = o;
  ob.out_dir = b.string();
  ob.plot_script.clear();
  ob.epochs = 1;
  pm::train(ob);
  ob.epochs = 3;
  ob.resume = true;
  const pm::TrainSummary sb = pm::train(ob);
  EXPECT_EQ(sb.steps, 6);

  pm::TrainOptions oc = ob;
  oc.out_dir = c.string();
  oc.resume = false;
  oc.max_steps = 3;  // stops in the middle of epoch 2
  EXPECT_EQ(pm::train(oc).steps, 3);
  oc.max_steps = 0;
  oc.resume = true;
  oc.learning_rate = 0.0;  // not given again: the checkpoint's (1e-3) and batch size (2) are kept
  oc.batch_size = 0;
  EXPECT_EQ(pm::train(oc).steps, 6);

  const auto ta = checkpoint_tensors((a / "checkpoint.pt").string());
  EXPECT_TRUE(same_tensors(ta, checkpoint_tensors((b / "checkpoint.pt").string())));
  EXPECT_TRUE(same_tensors(ta, checkpoint_tensors((c / "checkpoint.pt").string())));
  // The CSV of the resumed run has one row per step, as the straight run's.
  std::ifstream in(c / "train_log.csv");
  int rows = 0;
  for (std::string line; std::getline(in, line);) ++rows;
  EXPECT_EQ(rows, 1 + 6);
}

TEST(ModelTrain, LaterStagesRunFromTheGMNetCheckpoint) {
  const fs::path g = scratch("stage_gm"), l = scratch("stage_l"), j = scratch("stage_j"), s = scratch("stage_s");
  pm::TrainOptions o = options(g.string(), pm::Stage::kGMNet);
  o.batch_size = 3;
  pm::train(o);
  pm::TrainOptions ol = options(l.string(), pm::Stage::kLNet);
  ol.init = (g / "checkpoint.pt").string();
  ol.epochs = 4;
  ol.learning_rate = 1e-3;
  const auto sl = pm::train(ol);
  std::printf("[ModelTrain] lnet epoch losses:");
  for (double x : sl.epoch_losses) std::printf(" %.5f", x);
  std::printf("\n");
  EXPECT_LT(sl.last_loss, sl.first_loss);
  pm::TrainOptions oj = options(j.string(), pm::Stage::kJoint);
  oj.init = (l / "checkpoint.pt").string();
  oj.batch_size = 3;
  EXPECT_TRUE(std::isfinite(pm::train(oj).last_loss));
  pm::TrainOptions os = options(s.string(), pm::Stage::kGSNet);
  os.init = (j / "checkpoint.pt").string();
  os.epochs = 3;
  os.learning_rate = 1e-2;
  const auto ss = pm::train(os);
  EXPECT_LT(ss.last_loss, ss.first_loss);

  // Inference from the final checkpoint writes every output in the renderer's layout.
  const fs::path out = scratch("infer");
  pm::InferOptions io;
  io.checkpoint = (s / "checkpoint.pt").string();
  // A 128x64 panorama (twice the network's 64x32 input): the maps come back at 128x64.
  const fs::path big = scratch("infer_input") / "pano.png";
  fs::create_directories(big.parent_path());
  pm::write_tensor_image(big, torch::rand({3, 64, 128}));
  io.input = big.string();
  io.out_dir = out.string();
  io.threads = 1;
  pm::infer(io);
  for (const char* f : {"depth.exr", "normal.exr", "basecolor.exr", "roughness.exr", "metalness.exr", "probes.exr",
                        "probe_mask.exr", "rerender.exr", "input.png", "infer.json"})
    EXPECT_TRUE(fs::is_regular_file(out / f)) << f;
  const phyir::Image probes = phyir::read_image(out / "probes.exr");
  EXPECT_EQ(probes.width, 32 * 8);
  EXPECT_EQ(probes.height, 16 * 4);
  const phyir::Image depth = phyir::read_image(out / "depth.exr");
  EXPECT_EQ(depth.width, 128);
  EXPECT_EQ(depth.height, 64);
  EXPECT_EQ(depth.channels, 1);
  for (const char* f : {"normal.exr", "basecolor.exr", "roughness.exr", "metalness.exr", "input.png"}) {
    const phyir::Image m = phyir::read_image(out / f);
    EXPECT_EQ(m.width, 128) << f;
    EXPECT_EQ(m.height, 64) << f;
  }
  const phyir::Image normal = phyir::read_image(out / "normal.exr");
  for (size_t i = 0; i + 2 < normal.pixels.size(); i += 3 * 97) {  // unit normals after the upsampling
    const double len = std::sqrt(normal.pixels[i] * normal.pixels[i] + normal.pixels[i + 1] * normal.pixels[i + 1] +
                                 normal.pixels[i + 2] * normal.pixels[i + 2]);
    EXPECT_NEAR(len, 1.0, 1e-4);
  }
}

TEST(ModelTrain, NonFiniteLossStopsWithAClearMessage) {
  pm::TrainOptions o = options(scratch("nan").string(), pm::Stage::kGMNet);
  o.learning_rate = 1e30;  // the weights overflow after one step
  o.batch_size = 1;
  o.epochs = 2;
  try {
    pm::train(o);
    FAIL() << "expected a non-finite loss to stop training";
  } catch (const phyir::Error& e) {
    const std::string msg = e.what();
    EXPECT_NE(msg.find("the loss is"), std::string::npos) << msg;
    EXPECT_NE(msg.find("last good checkpoint"), std::string::npos) << msg;
  }
}

TEST(ModelTrain, BadOptionsAreReported) {
  EXPECT_THROW(pm::parse_stage("gsnett"), phyir::Error);
  pm::TrainOptions o = options(scratch("bad").string(), pm::Stage::kGMNet);
  o.config.input_height = 48;  // not a multiple of 32
  EXPECT_THROW(pm::train(o), phyir::Error);
  const auto d = pm::stage_defaults(pm::Stage::kGSNet);
  EXPECT_EQ(d.learning_rate, 5e-4);
  EXPECT_EQ(d.batch_size, 16);
  EXPECT_EQ(pm::stage_defaults(pm::Stage::kJoint).weights.coherence, 0.1);
}

TEST(ModelData, ManifestSplitsAndDeepFolders) {
  // docs/dataset.md: DIR/manifest.json lists views (dir relative to DIR, split); the views
  // live three levels down (views/<scene>/<vNNN>).
  const fs::path root = scratch("manifest");
  write_view(root / "views" / "s" / "v000", 0);
  write_view(root / "views" / "s" / "v001", 1);
  EXPECT_EQ(pm::find_view_folders(root).size(), 2u);  // no manifest: found by scanning
  std::ofstream(root / "manifest.json")
      << R"({"views": [{"id": "s/v000", "dir": "views/s/v000", "split": "train"},
                       {"id": "s/v001", "dir": "views/s/v001", "split": "val"}]})";
  const auto train = pm::find_view_folders(root, "train");
  ASSERT_EQ(train.size(), 1u);
  EXPECT_EQ(train[0], root / "views" / "s" / "v000");
  EXPECT_EQ(pm::find_view_folders(root, "").size(), 2u);
  EXPECT_THROW(pm::find_view_folders(root, "test"), phyir::Error);
}
