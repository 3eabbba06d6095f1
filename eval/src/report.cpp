#include "phyir/eval/report.h"

#include <fmt/format.h>

#include <string>
#include <vector>

#include "phyir/eval/depth_protocol.h"

namespace phyir::eval {
namespace {

using nlohmann::json;

// Which unit the radiance metrics (re-render, probes, relighting) were scored in.
std::string radiance_units_sentence(const json& j) {
  const json& s = j["settings"];
  const std::string units = s.contains("radiance_units") ? s["radiance_units"].get<std::string>() : "absolute";
  if (units == "input")
    return "Radiance metrics (re-render, probes, relighting) in each view's input units: both sides times "
           "2^exposure_stops of its input image (radiance units `input`).\n\n";
  return "Radiance metrics (re-render, probes, relighting) in absolute radiance, color.exr's unit "
         "(radiance units `absolute`).\n\n";
}

// The protocol of the depth metrics; files written before there was a choice used `toolkit`.
DepthProtocol depth_protocol_of(const json& j) {
  const json& s = j.at("settings");
  return s.contains("depth_protocol") ? parse_depth_protocol(s["depth_protocol"].get<std::string>())
                                      : DepthProtocol::kToolkit;
}

std::string cell(const json& metrics, const std::string& key, const char* format = "{:.4f}", double scale = 1.0) {
  if (!metrics.contains(key) || metrics[key].is_null()) return "-";
  return fmt::format(fmt::runtime(format), metrics[key].get<double>() * scale);
}

struct Column {
  std::string header, key, format;
};

std::string table(const json& j, const std::vector<Column>& columns, bool baselines = true) {
  std::string out = "| Method |";
  std::string rule = "| --- |";
  for (const Column& c : columns) {
    out += " " + c.header + " |";
    rule += " --- |";
  }
  out += "\n" + rule + "\n";
  for (const json& key : j.at("method_order")) {
    const json& method = j.at("methods").at(key.get<std::string>());
    if (!baselines && key != "prediction") continue;
    // Leave out a baseline row with nothing in this table.
    bool any = false;
    for (const Column& c : columns) any |= method["mean"].contains(c.key) && !method["mean"][c.key].is_null();
    if (!any) continue;
    out += "| " + method.at("label").get<std::string>() + " |";
    for (const Column& c : columns) out += " " + cell(method["mean"], c.key, c.format.c_str()) + " |";
    out += "\n";
  }
  return out;
}

const std::vector<Column>& table2() {
  static const std::vector<Column> c = {{"Base color (MSE)", "basecolor_mse", "{:.4f}"},
                                        {"Normal (mean angle)", "normal_deg", "{:.2f}°"},
                                        {"Roughness (MSE)", "roughness_mse", "{:.4f}"},
                                        {"Metalness (MSE)", "metalness_mse", "{:.4f}"},
                                        {"Re-render (MSE)", "rerender_mse", "{:.4f}"}};
  return c;
}

// The title, what was evaluated against what, and what was not.
std::string header_section(const json& j) {
  std::string r;
  r += "# PhyIR evaluation report\n\n";
  r += fmt::format("- Dataset: `{}`, split `{}`, {} views in {} scenes\n", j["dataset"].get<std::string>(),
                   j["split"].get<std::string>(), j["views"].size(), j["scenes"].size());
  r += fmt::format("- Predictions: `{}`{}\n", j["predictions"].get<std::string>(),
                   j["model"].is_null() ? "" : fmt::format(" (written by `phyir infer` from `{}`)", j["model"].get<std::string>()));
  if (!j["baseline_source"].is_null())
    r += fmt::format("- Constant-mean baseline: means of the ground truth of the {}\n", j["baseline_source"].get<std::string>());
  r += "- Every number is the mean over views of the per-view value (views where it is undefined left out). "
       "Definitions, masks and resampling: docs/eval.md.\n";
  if (!j["missing_optional_files"].empty()) {
    for (const auto& [file, views] : j["missing_optional_files"].items())
      r += fmt::format("- **Not evaluated**: `{}` missing in {} prediction folder(s) (first: {})\n", file, views.size(),
                       views[0].get<std::string>());
  }
  return r;
}

std::string materials_section(const json& j) {
  std::string r;
  r += "\n## Materials, geometry and re-rendering (layout of the paper's Table 2)\n\n";
  r += "MSE for base colour, roughness, metalness and the re-rendered image (linear HDR against `color.exr`); "
       "mean angular error in degrees for normals.\n\n";
  r += table(j, table2());
  return r;
}

std::string relighting_section(const json& j) {
  std::string r;
  r += "\n## Relighting (layout of Table 5)\n\n";
  const json& s = j["settings"];
  r += fmt::format("Spheres of Table 10's materials rendered by the path tracer lit by the predicted and by the "
                   "ground-truth probe at {} probe position(s) per view ({}x{} pixels, {} spp, same seed for both); "
                   "MAE and RMSE over the sphere's pixels and channels, linear radiance.\n\n",
                   s["relight_positions"].get<int>(), s["sphere_size"].get<int>(), s["sphere_size"].get<int>(),
                   s["sphere_spp"].get<int>());
  r += table(j, {{"Diffuse MAE", "relight_diffuse_mae", "{:.4f}"},
                 {"Diffuse RMSE", "relight_diffuse_rmse", "{:.4f}"},
                 {"Matte silver MAE", "relight_matte_silver_mae", "{:.4f}"},
                 {"Matte silver RMSE", "relight_matte_silver_rmse", "{:.4f}"},
                 {"Mirror silver MAE", "relight_mirror_silver_mae", "{:.4f}"},
                 {"Mirror silver RMSE", "relight_mirror_silver_rmse", "{:.4f}"}});
  return r;
}

std::string lighting_section(const json& j) {
  std::string r;
  r += "\n## Lighting (layout of Table 6)\n\n";
  r += "SSIM of log(1 + L) probes (eq. 7: 5x5 Gaussian window, sigma 1.5, C1 = 1e-4, C2 = 9e-4, circular padding "
       "in u), averaged over the probes valid on both sides; re-render MSE as in Table 2.\n\n";
  r += radiance_units_sentence(j);
  r += table(j, {{"SSIM ↑", "probe_ssim", "{:.4f}"}, {"Re-render error (MSE) ↓", "rerender_mse", "{:.4f}"}});
  return r;
}

std::string depth_section(const json& j, DepthProtocol depth) {
  std::string r;
  r += "\n## Depth (layout of Tables 7 and 11)\n\n";
  r += depth_protocol_description(depth) + "\n\n";
  r += table(j, {{"MAE", "depth_mae", "{:.4f}"},
                 {"Abs Rel", "depth_abs_rel", "{:.4f}"},
                 {"Sq Rel", "depth_sq_rel", "{:.4f}"},
                 {"RMSE", "depth_rmse", "{:.4f}"},
                 {depth == DepthProtocol::kToolkit ? "RMSElog (ln)" : "RMSElog (log10)", "depth_rmse_log", "{:.4f}"},
                 {"Log10", "depth_log10", "{:.4f}"},
                 {"δ1 ↑", "depth_delta1", "{:.4f}"},
                 {"δ2 ↑", "depth_delta2", "{:.4f}"},
                 {"δ3 ↑", "depth_delta3", "{:.4f}"}});
  return r;
}

std::string per_scene_section(const json& j) {
  std::string r;
  r += "\n## Per scene (the evaluated method)\n\n";
  r += "| Scene | Views | Base color | Normal | Roughness | Metalness | Re-render | Depth AbsRel | Depth δ1 | SSIM | "
       "Diffuse RMSE | Matte RMSE | Mirror RMSE |\n";
  r += "| --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- |\n";
  for (const auto& [scene, m] : j["methods"]["prediction"]["per_scene"].items()) {
    r += fmt::format("| {} | {} | {} | {} | {} | {} | {} | {} | {} | {} | {} | {} | {} |\n", scene,
                     m["views"].get<int>(), cell(m, "basecolor_mse"), cell(m, "normal_deg", "{:.2f}°"),
                     cell(m, "roughness_mse"), cell(m, "metalness_mse"), cell(m, "rerender_mse"),
                     cell(m, "depth_abs_rel"), cell(m, "depth_delta1"), cell(m, "probe_ssim"),
                     cell(m, "relight_diffuse_rmse"), cell(m, "relight_matte_silver_rmse"),
                     cell(m, "relight_mirror_silver_rmse"));
  }
  return r;
}

std::string masks_section(const json& j, DepthProtocol depth) {
  std::string r;
  r += "\n## Masks and resolutions\n\n";
  r += "- Maps and the re-render count the pixels where the ground truth sees a surface (`mask_geometry`) that is "
       "neither emissive (`mask_emissive`) nor transparent (`mask_transparent`). ";
  r += depth == DepthProtocol::kToolkit
           ? "Depth also needs ground truth > 0.\n"
           : "Depth (protocol `" + depth_protocol_name(depth) + "`) counts every pixel whose ground truth is in "
             "(0, 10] m instead, lights and glass included, as UniFuse's mask.\n";
  r += "- Prediction and ground truth are compared at the coarser of their two resolutions: the finer one is "
       "area-averaged onto it (normals renormalised); a coarse pixel counts only if every fine pixel it covers is "
       "valid.";
  r += depth == DepthProtocol::kToolkit ? "\n" : " Depth is not: see its protocol above.\n";
  r += "- Probes count where both `probe_mask.exr` are 1; grids are compared on the one with fewer probes (the "
       "other side's probe whose cell holds the cell centre), texels at the smaller texel resolution (area).\n";
  const json& pm = j["methods"]["prediction"]["mean"];
  r += fmt::format("- Mean counted per view: {} map pixels, {} depth pixels, {} re-render pixels, {} probes, {} "
                   "relighting positions.\n",
                   cell(pm, "pixels_maps", "{:.0f}"), cell(pm, "pixels_depth", "{:.0f}"),
                   cell(pm, "pixels_rerender", "{:.0f}"),
                   cell(pm, "probes_compared", "{:.0f}"), cell(pm, "relight_positions", "{:.0f}"));
  return r;
}

// Empty when the report has no figures.
std::string figures_section(const json& j) {
  std::string r;
  if (!j["figures"].empty()) {
    r += "\n## Side by side\n\n";
    r += "Columns: input / ground truth / prediction. Rows: input.png, color.exr and the re-render (tone-mapped at "
         "the view's input exposure); base colour; normal (0.5 + 0.5 n); depth (0 to the view's maximum, white = far); "
         "roughness; metalness; relit spheres at the first relighting position (diffuse, matte silver, mirror silver; "
         "ground truth in the middle column, prediction on the right).\n\n";
    for (const json& f : j["figures"]) r += fmt::format("![{}]({})\n\n", f.get<std::string>(), f.get<std::string>());
  }
  return r;
}

}  // namespace

std::string main_table_markdown(const json& j) { return table(j, table2()); }

std::string report_markdown(const json& j) {
  const DepthProtocol depth = depth_protocol_of(j);
  return header_section(j) + materials_section(j) + relighting_section(j) + lighting_section(j) +
         depth_section(j, depth) + per_scene_section(j) + masks_section(j, depth) + figures_section(j);
}

}  // namespace phyir::eval
