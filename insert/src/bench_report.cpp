// insert_bench.md and insert_bench.json: per case and lighting, the mean and sample standard
// deviation over the seeds of RMSE (linear HDR, lower is better) and SSIM (display, higher is
// better), and how many seeds GT probes beat the global probe on RMSE (paired: same seed).
#include <fmt/format.h>

#include <numeric>

#include "phyir/insert/insert_bench.h"

namespace phyir::insert {

namespace {

std::string mean_sd(const std::vector<double>& v, int digits) {
  const ScoreSummary s = summarize(v);
  return fmt::format("{:.{}f} ± {:.{}f}", s.mean, digits, s.sd, digits);
}

// Seeds on which `a` scored a lower RMSE than `b`, as "k/n".
std::string wins(const CaseScores& c, const std::string& a, const std::string& b) {
  if (!c.rmse.count(a) || !c.rmse.count(b)) return "-";
  const std::vector<double>&x = c.rmse.at(a), &y = c.rmse.at(b);
  int k = 0;
  for (size_t s = 0; s < x.size(); ++s) k += x[s] < y[s];
  return fmt::format("{}/{}", k, x.size());
}

double total(const std::vector<double>& v) { return std::accumulate(v.begin(), v.end(), 0.0); }

nlohmann::json summary_json(const std::vector<double>& v) {
  const ScoreSummary s = summarize(v);
  return {{"mean", s.mean}, {"sd", s.sd}, {"per_seed", v}};
}

}  // namespace

std::string cases_table(const std::vector<CaseScores>& cases, const std::vector<std::string>& lightings) {
  std::string head = "| placement | object |", rule = "| --- | --- |";
  for (const std::string& l : lightings) head += fmt::format(" RMSE {} |", l), rule += " --- |";
  for (const std::string& l : lightings) head += fmt::format(" SSIM {} |", l), rule += " --- |";
  head += " gt < global (RMSE, seeds) | truth s | composites s |\n";
  rule += " --- | --- | --- |\n";
  std::string t = head + rule;
  for (const CaseScores& c : cases) {
    t += fmt::format("| {} | {} |", c.placement, c.object);
    for (const std::string& l : lightings) t += " " + mean_sd(c.rmse.at(l), 4) + " |";
    for (const std::string& l : lightings) t += " " + mean_sd(c.ssim.at(l), 3) + " |";
    t += fmt::format(" {} | {:.0f} | {:.0f} |\n", wins(c, "gt", "global"), total(c.truth_seconds),
                     total(c.composite_seconds));
  }
  return t;
}

std::string path_table(const std::vector<PathScores>& paths, const std::vector<std::string>& lightings) {
  std::string t = "| object | frames | truth's rms change |", rule = "| --- | --- | --- |";
  for (const std::string& l : lightings) t += fmt::format(" change error {} | rms change {} |", l, l), rule += " --- | --- |";
  t += "\n" + rule + "\n";
  for (const PathScores& p : paths) {
    t += fmt::format("| {} | {} | {:.4f} |", p.object, p.pixels.size(), p.truth_rms_change);
    for (const std::string& l : lightings) t += fmt::format(" {:.4f} | {:.4f} |", p.change_error.at(l), p.rms_change.at(l));
    t += "\n";
  }
  return t;
}

nlohmann::json case_record(const CaseScores& c, const BenchPlacement& p) {
  nlohmann::json j = {{"placement", p.name}, {"pixel", {p.x, p.y}}, {"note", p.note}, {"object", c.object},
                      {"truth_seconds", c.truth_seconds}, {"composite_seconds", c.composite_seconds}};
  for (const auto& [lighting, v] : c.rmse) j["rmse"][lighting] = summary_json(v);
  for (const auto& [lighting, v] : c.ssim) j["ssim"][lighting] = summary_json(v);
  return j;
}

nlohmann::json path_record(const PathScores& p) {
  nlohmann::json j = {{"object", p.object}, {"truth_rms_change", p.truth_rms_change}};
  for (const glm::ivec2& x : p.pixels) j["pixels"].push_back({x.x, x.y});
  for (const auto& [lighting, v] : p.change_error) j["change_error"][lighting] = v;
  for (const auto& [lighting, v] : p.rms_change) j["rms_change"][lighting] = v;
  return j;
}

}  // namespace phyir::insert
