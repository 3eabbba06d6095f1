// CSV logs that survive a resume (train_log.h).
#include "train_log.h"

#include <cmath>
#include <sstream>

#include "phyir/core/error.h"

namespace fs = std::filesystem;

namespace phyir::model {

namespace {

std::vector<std::string> kept_lines(const fs::path& path, int64_t resumed_step) {
  std::vector<std::string> kept;
  std::ifstream in(path);
  std::string line;
  for (int i = 0; std::getline(in, line); ++i) {
    if (i == 0) {
      kept.push_back(line);
      continue;
    }
    std::istringstream row(line);
    std::string stage, epoch, step;
    std::getline(row, stage, ',');
    std::getline(row, epoch, ',');
    std::getline(row, step, ',');
    if (!step.empty() && std::stoll(step) <= resumed_step) kept.push_back(line);
  }
  return kept;
}

void write_joined(std::ofstream& out, const std::vector<std::string>& cells) {
  for (size_t i = 0; i < cells.size(); ++i) out << (i ? "," : "") << cells[i];
  out << "\n";
  out.flush();
}

}  // namespace

CsvLog::CsvLog(fs::path path, bool resume, int64_t resumed_step) : path_(std::move(path)) {
  std::vector<std::string> kept;
  if (resume && fs::is_regular_file(path_)) kept = kept_lines(path_, resumed_step);
  out_.open(path_, std::ios::trunc);
  if (!out_) fail("{}: cannot write", path_.string());
  has_header_ = !kept.empty();
  for (const auto& l : kept) out_ << l << "\n";
  out_.flush();
}

void CsvLog::header(const std::vector<std::string>& columns) {
  write_joined(out_, columns);
  has_header_ = true;
}

void CsvLog::row(const std::vector<std::string>& cells) { write_joined(out_, cells); }

std::string csv_number(double value) { return std::isnan(value) ? std::string() : fmt::format("{:.9g}", value); }

}  // namespace phyir::model
