// A dataset's views as a torch::data dataset: views listed by view::find_views, each loaded
// by load_view when the sampler asks.
#include "torch_dataset.h"

#include "phyir/core/error.h"

namespace fs = std::filesystem;

namespace phyir::model {

namespace {

// The view's path below the dataset's views/ folder (below root without one).
std::string view_id(const fs::path& root, const fs::path& folder) {
  const fs::path views = root / "views";
  const fs::path rel = fs::relative(folder, fs::is_directory(views) ? views : root);
  return rel.empty() || rel == "." ? folder.filename().generic_string() : rel.generic_string();
}

}  // namespace

ExampleSize ExampleSize::of(const ModelConfig& c) {
  return {c.input_height, c.input_width, c.render_height, c.render_width, c.probe_height, c.probe_width};
}

ModelConfig ExampleSize::model_config() const {
  ModelConfig c;
  c.input_height = height;
  c.input_width = width;
  c.render_height = probe_grid_height;
  c.render_width = probe_grid_width;
  c.probe_height = probe_height;
  c.probe_width = probe_width;
  return c;
}

ManifestDataset::ManifestDataset(const fs::path& root, std::vector<view::ViewRecord> views, const ModelConfig& config,
                                 view::RadianceUnits units)
    : views_(std::move(views)), config_(config), units_(units) {
  for (const view::ViewRecord& v : views_) ids_.push_back(view_id(root, v.dir));
}

ManifestDataset::ManifestDataset(const fs::path& root, const std::string& split, ExampleSize size) {
  for (int v : {size.height, size.width, size.probe_grid_height, size.probe_grid_width, size.probe_height,
                size.probe_width})
    if (v <= 0) fail("dataset {}: every example size must be positive", root.string());
  // Without a manifest view::find_views would scan folders: a dataset still being
  // generated has no manifest, and its half-done views must not be trained on.
  *this = ManifestDataset(root, view::read_manifest_views(root, split), size.model_config(),
                          view::RadianceUnits::kAbsolute);
}

ManifestDataset ManifestDataset::for_training(const fs::path& root, const std::string& split, int max_views,
                                              const ModelConfig& config, view::RadianceUnits units, bool with_probes) {
  std::vector<view::ViewRecord> views = view::find_views(root, split);
  if (max_views > 0 && views.size() > static_cast<size_t>(max_views)) views.resize(max_views);
  ManifestDataset d(root, std::move(views), config, units);
  d.with_probes_ = with_probes;
  return d;
}

ViewTensors ManifestDataset::get(size_t index) {
  ViewTensors v = load_view(views_.at(index), config_, units_, with_probes_);
  v.id = ids_[index];
  v.index = static_cast<int64_t>(index);
  if (census_) v.census = census_->enrol();
  return v;
}

}  // namespace phyir::model
