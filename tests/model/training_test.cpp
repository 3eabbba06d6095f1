// Training stages, exact resume, the NaN stop and inference on a tiny synthetic dataset.
#include <unistd.h>

#include <fstream>
#include <nlohmann/json.hpp>

#include "checkpoint.h"
#include "data.h"
#include "exposure.h"
#include "nets.h"
#include "phyir/core/error.h"
#include "phyir/core/image_io.h"
#include "phyir/dataset/manifest.h"
#include "phyir/model/training.h"
#include "phyir/view/view_record.h"
#include "lr_schedule.h"
#include "validation.h"
#include "render_layer.h"
#include "synthetic_view.h"
#include "tiny_dataset.h"

namespace pm = phyir::model;
namespace fs = std::filesystem;

namespace {

using synthetic::write_view;

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

// A dataset with a manifest: views 0-2 in train, 3-4 in val, each with a view.json exposure.
fs::path manifest_dataset() {
  static const fs::path root = [] {
    const fs::path r = fs::temp_directory_path() / ("phyir_model_test_data_" + std::to_string(::getpid())) / "manifest";
    fs::remove_all(r);
    nlohmann::json views = nlohmann::json::array();
    for (int k = 0; k < 5; ++k) {
      const std::string id = fmt::format("s{}/v000", k), dir = "views/" + id;
      const std::string split = k < 3 ? "train" : "val";
      const nlohmann::json record = {{"id", id}, {"dir", dir}, {"split", split}, {"scene", {{"name", fmt::format("s{}", k)}}},
                                     {"index", 0}, {"seed", k}, {"files", nlohmann::json::array()},
                                     {"input", {{"exposure_stops", -1.0 + 0.5 * k}, {"view", "Standard"}}}};
      write_view(r / dir, k);
      std::ofstream(r / dir / "view.json") << record.dump(2);
      views.push_back(record);
    }
    // The fields phyir::dataset::read_manifest requires (the validation pass reads it).
    nlohmann::json scenes = nlohmann::json::array(), names = nlohmann::json::array();
    for (const auto& v : views) {
      names.push_back(v["scene"]["name"]);
      scenes.push_back({{"name", v["scene"]["name"]}, {"split", v["split"]}, {"views", 1}});
    }
    std::ofstream(r / "manifest.json") << nlohmann::json({{"format", phyir::dataset::kManifestFormat},
                                                          {"format_version", phyir::dataset::kManifestVersion},
                                                          {"settings", {{"views_per_scene", 1}}},
                                                          {"scenes_dir", "scenes"},
                                                          {"shard", {{"index", 0}, {"count", 1}}},
                                                          {"scene_names", names},
                                                          {"scenes", scenes},
                                                          {"views", views}})
                                                .dump(2);
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

nlohmann::json checkpoint_meta(const fs::path& path) {
  torch::serialize::InputArchive archive;
  archive.load_from(path.string());
  c10::IValue v;
  archive.read("meta", v);
  return nlohmann::json::parse(v.toStringRef());
}

// A CSV's rows without its last column (seconds: the one that differs between runs).
std::vector<std::string> csv_rows_without_time(const fs::path& path) {
  std::vector<std::string> rows;
  std::ifstream in(path);
  for (std::string line; std::getline(in, line);) rows.push_back(line.substr(0, line.rfind(',')));
  return rows;
}

}  // namespace

TEST(ModelData, LoadsViewFoldersAtNetworkResolution) {
  const auto folders = phyir::view::find_views(dataset());
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
  // On three views the augmentation's variation between epochs exceeds what three GSNet
  // steps change; the check is that GSNet learns.
  os.augment.enabled = false;
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

TEST(ModelTrain, StreamedTrainingIsIdenticalWithZeroOneAndTwoWorkers) {
  // The same seed gives the same weights whatever the read-ahead: batches are made in the
  // sampler's order and handed over in it (view_stream.h), augmentation included.
  std::vector<std::vector<torch::Tensor>> weights;
  std::vector<std::vector<std::string>> logs;
  for (auto [workers, prefetch] : std::vector<std::pair<int, int>>{{0, 1}, {1, 1}, {2, 3}}) {
    const fs::path out = scratch(fmt::format("workers_{}_{}", workers, prefetch));
    pm::TrainOptions o = options(out.string(), pm::Stage::kGMNet);
    o.epochs = 2;
    o.batch_size = 2;  // 3 views: batches of 2 and 1
    o.learning_rate = 1e-3;
    o.workers = workers;
    o.prefetch = prefetch;
    const pm::TrainSummary s = pm::train(o);
    EXPECT_EQ(s.steps, 4);
    weights.push_back(checkpoint_tensors((out / "checkpoint.pt").string()));
    logs.push_back(csv_rows_without_time(out / "train_log.csv"));
  }
  EXPECT_TRUE(same_tensors(weights[0], weights[1])) << "0 and 1 workers";
  EXPECT_TRUE(same_tensors(weights[0], weights[2])) << "0 and 2 workers";
  EXPECT_EQ(logs[0], logs[1]);
  EXPECT_EQ(logs[0], logs[2]);
  pm::TrainOptions bad = options(scratch("workers_bad").string(), pm::Stage::kGMNet);
  bad.workers = 2;
  bad.prefetch = 0;
  EXPECT_THROW(pm::train(bad), phyir::Error);
}

// `phyir train` of one tiny GMNet epoch on the test dataset; the output folder goes last.
std::string tiny_gmnet_command(const fs::path& bin) {
  return bin.string() + " --log-level warn train --data " + dataset().string() +
         " --stage gmnet --epochs 1 --batch 2 --seed 3 --input-height 32 --input-width 64"
         " --render-height 16 --render-width 32 --probe-height 4 --probe-width 8"
         " --width-divisor 4 --threads 1 --quiet --out ";
}

TEST(ModelTrainCli, DeviceCpuEqualsTheDefaultAndAnUnavailableDeviceIsNamed) {
  const fs::path bin = PHYIR_BINARY;
  if (!fs::is_regular_file(bin)) GTEST_SKIP() << bin << " not built";
  const fs::path work = scratch("device");
  fs::create_directories(work);
  const std::string log = " >> " + (work / "log.txt").string() + " 2>&1";
  const std::string train = tiny_gmnet_command(bin);
  ASSERT_EQ(std::system((train + (work / "default").string() + log).c_str()), 0) << work / "log.txt";
  ASSERT_EQ(std::system((train + (work / "cpu").string() + " --device cpu --workers 1" + log).c_str()), 0)
      << work / "log.txt";
  EXPECT_TRUE(same_tensors(checkpoint_tensors((work / "default" / "checkpoint.pt").string()),
                           checkpoint_tensors((work / "cpu" / "checkpoint.pt").string())));
  std::ifstream in(work / "cpu" / "train_log.json");
  EXPECT_EQ(nlohmann::json::parse(in)["device"], "cpu");
  // An unknown device, and CUDA on this CPU-only LibTorch: a non-zero exit naming the flag.
  const auto fails_naming = [&](const std::string& command, const std::string& expected) {
    const fs::path err = work / "err.txt";
    EXPECT_NE(std::system((command + " > " + err.string() + " 2>&1").c_str()), 0) << command;
    std::ifstream e(err);
    const std::string text((std::istreambuf_iterator<char>(e)), std::istreambuf_iterator<char>());
    EXPECT_NE(text.find(expected), std::string::npos) << command << ":\n" << text;
  };
  fails_naming(train + (work / "tpu").string() + " --device tpu", "--device: 'tpu'");
  if (torch::cuda::is_available()) return;
  fails_naming(train + (work / "cuda").string() + " --device cuda", "--device: 'cuda': CUDA is not available");
  fails_naming(bin.string() + " infer --model " + (work / "cpu" / "checkpoint.pt").string() + " --input " +
                   (phyir::view::find_views(dataset())[0].dir / "input.png").string() + " --out " +
                   (work / "infer").string() + " --device cuda",
               "--device: 'cuda': CUDA is not available");
  EXPECT_FALSE(fs::exists(work / "cuda" / "checkpoint.pt"));
}

// Same seed, same output whatever the thread count: phyir infer (which uses every core by
// default) writes the same bytes with 1 and 2 torch threads.
TEST(ModelTrainCli, InferIsIdenticalWithOneAndTwoThreads) {
  const fs::path bin = PHYIR_BINARY;
  if (!fs::is_regular_file(bin)) GTEST_SKIP() << bin << " not built";
  const fs::path work = scratch("infer_threads");
  fs::create_directories(work);
  const std::string log = " >> " + (work / "log.txt").string() + " 2>&1";
  ASSERT_EQ(std::system((tiny_gmnet_command(bin) + (work / "run").string() + log).c_str()), 0)
      << work / "log.txt";
  const std::string input = (phyir::view::find_views(dataset())[0].dir / "input.png").string();
  for (int threads : {1, 2})
    ASSERT_EQ(std::system((bin.string() + " --log-level warn infer --model " + (work / "run" / "checkpoint.pt").string() +
                           " --input " + input + " --threads " + std::to_string(threads) + " --out " +
                           (work / ("t" + std::to_string(threads))).string() + log).c_str()), 0)
        << work / "log.txt";
  auto bytes = [](const fs::path& p) {
    std::ifstream in(p, std::ios::binary);
    return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  };
  for (const char* f : {"depth.exr", "normal.exr", "basecolor.exr", "roughness.exr", "metalness.exr", "probes.exr",
                        "rerender.exr"}) {
    const std::string one = bytes(work / "t1" / f);
    EXPECT_FALSE(one.empty()) << f;
    EXPECT_EQ(one, bytes(work / "t2" / f)) << f;
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

TEST(ModelTrain, ResumeIsExactWithScheduleValidationAndBestCheckpoint) {
  // A: 3 epochs straight with augmentation, a cosine schedule and validation every epoch.
  // C: stopped after step 3 (mid epoch 2) and resumed. D: A without validation.
  const fs::path a = scratch("val_a"), c = scratch("val_c"), d = scratch("val_d");
  pm::TrainOptions o = options(a.string(), pm::Stage::kGMNet);
  o.data_dir = manifest_dataset().string();
  o.epochs = 3;
  o.batch_size = 2;
  o.learning_rate = 1e-3;
  o.schedule.kind = "cosine";
  o.validation.every = 1;
  o.plot_script = std::string(PHYIR_SOURCE_ROOT) + "/scripts/plot_training.py";
  const pm::TrainSummary sa = pm::train(o);
  EXPECT_EQ(sa.steps, 6);  // 3 train views, batch 2
  ASSERT_EQ(sa.validations.size(), 3u);
  EXPECT_TRUE(fs::is_regular_file(a / "best.pt"));
  EXPECT_TRUE(fs::is_regular_file(a / "loss_curve.png"));

  pm::TrainOptions oc = o;
  oc.out_dir = c.string();
  oc.plot_script.clear();
  oc.max_steps = 3;
  EXPECT_EQ(pm::train(oc).steps, 3);
  oc.max_steps = 0;
  oc.resume = true;
  oc.schedule.kind.clear();  // not given again: the checkpoint's (cosine)
  oc.learning_rate = 0.0;
  EXPECT_EQ(pm::train(oc).steps, 6);
  const auto ta = checkpoint_tensors((a / "checkpoint.pt").string());
  EXPECT_TRUE(same_tensors(ta, checkpoint_tensors((c / "checkpoint.pt").string())));
  EXPECT_TRUE(same_tensors(checkpoint_tensors((a / "best.pt").string()), checkpoint_tensors((c / "best.pt").string())));
  EXPECT_EQ(checkpoint_meta(a / "checkpoint.pt")["best"], checkpoint_meta(c / "checkpoint.pt")["best"]);
  EXPECT_EQ(checkpoint_meta(c / "checkpoint.pt")["schedule"]["kind"], "cosine");
  EXPECT_EQ(csv_rows_without_time(a / "val_log.csv"), csv_rows_without_time(c / "val_log.csv"));
  EXPECT_EQ(csv_rows_without_time(a / "train_log.csv"), csv_rows_without_time(c / "train_log.csv"));

  // Validation changes nothing in training (its generator use is undone).
  pm::TrainOptions od = o;
  od.out_dir = d.string();
  od.plot_script.clear();
  od.validation.every = 0;
  EXPECT_TRUE(pm::train(od).validations.empty());
  EXPECT_TRUE(same_tensors(ta, checkpoint_tensors((d / "checkpoint.pt").string())));
  EXPECT_FALSE(fs::exists(d / "val_log.csv"));

  // In the lnet stage the rendering layer draws from torch's generator every step: there too a
  // validation pass changes nothing and a resume is exact.
  const fs::path l1 = scratch("val_l1"), l2 = scratch("val_l2"), l3 = scratch("val_l3");
  pm::TrainOptions ol = options(l1.string(), pm::Stage::kLNet);
  ol.data_dir = manifest_dataset().string();
  ol.init = (a / "checkpoint.pt").string();
  ol.epochs = 2;
  ol.batch_size = 2;
  ol.learning_rate = 1e-3;
  ol.validation.every = 1;
  ol.validation.best_metric = "probe_ssim";
  const pm::TrainSummary sl = pm::train(ol);
  ASSERT_EQ(sl.validations.size(), 2u);
  EXPECT_TRUE(std::isfinite(pm::metric_value(sl.validations[0], "probe_ssim")));
  pm::TrainOptions ol2 = ol;
  ol2.out_dir = l2.string();
  ol2.validation.every = 0;
  pm::train(ol2);
  const auto tl = checkpoint_tensors((l1 / "checkpoint.pt").string());
  EXPECT_TRUE(same_tensors(tl, checkpoint_tensors((l2 / "checkpoint.pt").string())));
  pm::TrainOptions ol3 = ol;
  ol3.out_dir = l3.string();
  ol3.max_steps = 3;
  pm::train(ol3);
  ol3.max_steps = 0;
  ol3.resume = true;
  pm::train(ol3);
  EXPECT_TRUE(same_tensors(tl, checkpoint_tensors((l3 / "checkpoint.pt").string())));
  EXPECT_EQ(csv_rows_without_time(l1 / "val_log.csv"), csv_rows_without_time(l3 / "val_log.csv"));

  // The best checkpoint is the pass with the lowest validation loss.
  size_t best = 0;
  for (size_t k = 1; k < sa.validations.size(); ++k)
    if (sa.validations[k].loss < sa.validations[best].loss) best = k;
  const nlohmann::json meta = checkpoint_meta(a / "best.pt");
  EXPECT_EQ(meta["best"]["epoch"], sa.validations[best].epoch);
  EXPECT_EQ(meta["epoch"], sa.validations[best].epoch);
  EXPECT_EQ(sa.best_epoch, sa.validations[best].epoch);
  EXPECT_DOUBLE_EQ(sa.best_value, sa.validations[best].loss);

  // A resumed run compares against the best so far: an epoch at a ruinous learning rate does
  // not replace it.
  const fs::path w = scratch("val_w");
  fs::copy(a, w);
  const auto best_a = checkpoint_tensors((w / "best.pt").string());
  pm::TrainOptions worse = o;
  worse.out_dir = w.string();
  worse.plot_script.clear();
  worse.resume = true;
  worse.epochs = 4;
  worse.learning_rate = 0.5;
  const pm::TrainSummary sw = pm::train(worse);
  ASSERT_EQ(sw.validations.size(), 1u);
  EXPECT_GT(sw.validations[0].loss, sa.best_value);
  EXPECT_EQ(sw.best_epoch, sa.best_epoch);
  EXPECT_TRUE(same_tensors(best_a, checkpoint_tensors((w / "best.pt").string())));

  // The validation log: the loss, its parts and phyir eval's metrics (finite for GMNet's maps,
  // empty for the probes and the re-render, which an untrained LNet does not predict).
  std::ifstream in(a / "val_log.csv");
  std::string header;
  std::getline(in, header);
  for (const char* column : {"train_loss", "val_loss", "val_basecolor", "basecolor_mse", "normal_deg", "depth_abs_rel",
                             "probe_ssim", "rerender_mse", "lr"})
    EXPECT_NE(header.find(column), std::string::npos) << column << " in " << header;
  for (const auto& [name, value] : sa.validations[0].metrics) {
    if (name == "probe_ssim" || name == "rerender_mse") EXPECT_TRUE(std::isnan(value)) << name;
    else EXPECT_TRUE(std::isfinite(value)) << name;
  }
  std::ifstream json_in(a / "train_log.json");
  const nlohmann::json log = nlohmann::json::parse(json_in);
  EXPECT_EQ(log["validation_passes"].size(), 3u);
  EXPECT_EQ(log["validation_views"], 2);

  // The learning rate of every step is the schedule's.
  std::ifstream steps(a / "train_log.csv");
  std::string line;
  std::getline(steps, line);
  const pm::LrSchedule sched = pm::make_schedule(o.schedule, nullptr, 1e-3, 3, 2);
  for (int64_t k = 0; std::getline(steps, line); ++k) {
    const size_t last = line.rfind(','), before = line.rfind(',', last - 1);
    EXPECT_NEAR(std::stod(line.substr(before + 1, last - before - 1)), sched.at(k), 1e-12) << k;
  }
}

// --target-units: recorded in the checkpoint's configuration, inherited through --init unless
// given again (one GMNet stage can start both arms of the exposure study), refused on a resume
// that would change it; a checkpoint from before the switch reads as input units.
TEST(ModelTrain, TargetUnitsAreRecordedInheritedAndFixedOnResume) {
  const fs::path g = scratch("units_gm"), l_in = scratch("units_l_in"), l_abs = scratch("units_l_abs");
  pm::TrainOptions o = options(g.string(), pm::Stage::kGMNet);
  o.max_steps = 1;
  o.target_units = "absolute";
  pm::train(o);
  EXPECT_EQ(pm::read_checkpoint_config((g / "checkpoint.pt").string()).target_units, "absolute");
  pm::TrainOptions ol = options(l_in.string(), pm::Stage::kLNet);
  ol.init = (g / "checkpoint.pt").string();
  ol.max_steps = 1;
  ol.target_units = "input";
  pm::train(ol);
  EXPECT_EQ(pm::read_checkpoint_config((l_in / "checkpoint.pt").string()).target_units, "input");
  ol.out_dir = l_abs.string();
  ol.target_units.clear();
  pm::train(ol);
  EXPECT_EQ(pm::read_checkpoint_config((l_abs / "checkpoint.pt").string()).target_units, "absolute");
  ol.resume = true;
  ol.max_steps = 2;
  ol.target_units = "input";
  EXPECT_THROW(pm::train(ol), phyir::Error);
  nlohmann::json old = pm::config_to_json(pm::ModelConfig{});
  old.erase("target_units");
  EXPECT_EQ(pm::config_from_json(old).target_units, "input");
}

TEST(ModelTrain, LearningRateSchedules) {
  pm::LrScheduleOptions o;
  const pm::LrSchedule constant = pm::make_schedule(o, nullptr, 1e-4, 10, 5);
  EXPECT_EQ(constant.kind, "constant");
  EXPECT_EQ(constant.at(0), 1e-4);
  EXPECT_EQ(constant.at(49), 1e-4);
  o.kind = "step";
  const pm::LrSchedule step = pm::make_schedule(o, nullptr, 1e-4, 9, 5);  // every 3 epochs (a third)
  EXPECT_EQ(step.step_epochs, 3);
  EXPECT_DOUBLE_EQ(step.at(14), 1e-4);       // epoch 3 (0-based 2)
  EXPECT_DOUBLE_EQ(step.at(15), 1e-5);       // epoch 4
  EXPECT_DOUBLE_EQ(step.at(44), 1e-6);
  o.kind = "cosine";
  o.min_fraction = 0.01;
  const pm::LrSchedule cosine = pm::make_schedule(o, nullptr, 1e-4, 10, 5);
  EXPECT_DOUBLE_EQ(cosine.at(0), 1e-4);
  EXPECT_NEAR(cosine.at(49), 1e-6, 1e-18);
  EXPECT_NEAR(cosine.at(1000), 1e-6, 1e-18);  // past the planned end: the last rate
  EXPECT_LT(cosine.at(30), cosine.at(20));
  // Resumed without --lr-schedule: the checkpoint's kind and parameters.
  const pm::LrSchedule resumed = pm::make_schedule(pm::LrScheduleOptions{}, step.to_json(), 1e-4, 9, 5);
  EXPECT_EQ(resumed.kind, "step");
  EXPECT_EQ(resumed.step_epochs, 3);
  o.kind = "exponential";
  EXPECT_THROW(pm::make_schedule(o, nullptr, 1e-4, 10, 5), phyir::Error);
  pm::TrainOptions bad = options(scratch("bad_metric").string(), pm::Stage::kGMNet);
  bad.validation.best_metric = "accuracy";
  EXPECT_THROW(pm::train(bad), phyir::Error);
}

TEST(ModelTrainCli, ManifestDatasetWithAValSplitEndToEnd) {
  // `phyir train` on a dataset of the real pipeline: GMNet then LNet with validation on its
  // val split and the best checkpoint kept; `phyir infer` on a val view in absolute units
  // (its view.json's exposure) and in the input's units.
  const tiny::Dataset& data = tiny::dataset();
  if (data.root.empty() && data.error.empty()) GTEST_SKIP() << PHYIR_BINARY << " not built";
  ASSERT_TRUE(data.error.empty()) << data.error;
  const fs::path val_view = data.view("val"), work = scratch("cli");
  fs::create_directories(work);
  ASSERT_FALSE(val_view.empty());
  ASSERT_FALSE(data.view("train").empty());
  const std::string bin = std::string(PHYIR_BINARY) + " --log-level warn ";
  const std::string net = " --input-height 32 --input-width 64 --render-height 16 --render-width 32 --probe-height 4"
                          " --probe-width 8 --diffuse-samples 8 --specular-samples 4 --width-divisor 4 --threads 1 --quiet";
  const std::string log = " >> " + (work / "log.txt").string() + " 2>&1";
  ASSERT_EQ(std::system((bin + "train --data " + data.root.string() + " --out " + (work / "gm").string() +
                         " --stage gmnet --epochs 2 --batch 1 --lr 1e-3 --lr-schedule cosine" + net + log).c_str()), 0)
      << work / "log.txt";
  ASSERT_EQ(std::system((bin + "train --data " + data.root.string() + " --out " + (work / "l").string() +
                         " --stage lnet --epochs 1 --batch 1 --lr 1e-3 --best-metric probe_ssim --init " +
                         (work / "gm" / "checkpoint.pt").string() + " --threads 1 --quiet" + log).c_str()), 0)
      << work / "log.txt";
  for (const char* run : {"gm", "l"}) {
    EXPECT_TRUE(fs::is_regular_file(work / run / "best.pt")) << run;
    std::ifstream in(work / run / "train_log.json");
    const nlohmann::json j = nlohmann::json::parse(in);
    ASSERT_FALSE(j["validation_passes"].empty()) << run;
    EXPECT_TRUE(j["validation_passes"][0]["normal_deg"].is_number()) << run;
  }
  std::ifstream in(work / "l" / "train_log.json");
  const nlohmann::json lj = nlohmann::json::parse(in);
  EXPECT_TRUE(lj["validation_passes"][0]["probe_ssim"].is_number());
  EXPECT_TRUE(lj["validation_passes"][0]["rerender_mse"].is_number());
  EXPECT_EQ(lj["best"]["metric"], "probe_ssim");

  // Inference: absolute radiance from the view's recorded exposure, or the input's units.
  const std::string model = " --model " + (work / "l" / "best.pt").string();
  const auto infer = [&](const fs::path& input, const std::string& out, const std::string& extra) {
    EXPECT_EQ(std::system((bin + "infer" + model + " --input " + input.string() + " --out " + (work / out).string() +
                           " --seed 3" + extra + log).c_str()), 0);
    std::ifstream f(work / out / "infer.json");
    return nlohmann::json::parse(f)["radiance"];
  };
  const double stops = phyir::view::read_view(val_view).input.stops;
  const nlohmann::json abs = infer(val_view / "input.png", "abs", "");
  EXPECT_EQ(abs["unit"], "absolute");
  EXPECT_NEAR(abs["exposure_stops"].get<double>(), stops, 1e-6);
  const nlohmann::json rel = infer(val_view / "input.png", "rel", " --radiance input");
  EXPECT_EQ(rel["unit"], "input");
  const torch::Tensor pa = pm::image_to_tensor(phyir::read_image(work / "abs" / "probes.exr"));
  const torch::Tensor pr = pm::image_to_tensor(phyir::read_image(work / "rel" / "probes.exr"));
  EXPECT_TRUE(torch::allclose(pa, pr * std::exp2(-stops), 1e-5, 1e-9));
  // Without view.json or --exposure the unit is the input's; --exposure makes it absolute.
  fs::create_directories(work / "bare");
  fs::copy_file(val_view / "input.png", work / "bare" / "pano.png");
  EXPECT_EQ(infer(work / "bare" / "pano.png", "bare_out", "")["unit"], "input");
  const nlohmann::json given = infer(work / "bare" / "pano.png", "given_out", " --exposure 1.5");
  EXPECT_EQ(given["unit"], "absolute");
  EXPECT_EQ(given["exposure_source"], "given");
}
