#pragma once
// The CSV logs of a run (train_log.csv: a row per step; val_log.csv: a row per validation
// pass). Their third column is the global step: a resumed run keeps the rows up to the step
// it resumes from and drops the rest, so the log reads as an uninterrupted run's.
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

namespace phyir::model {

class CsvLog {
 public:
  // Opens `path` for writing; when `resume`, keeps its header and the rows whose global step
  // (third column) is at most `resumed_step`.
  CsvLog(std::filesystem::path path, bool resume, int64_t resumed_step);

  bool has_header() const { return has_header_; }
  void header(const std::vector<std::string>& columns);
  void row(const std::vector<std::string>& cells);  // written and flushed at once
  const std::filesystem::path& path() const { return path_; }

 private:
  std::filesystem::path path_;
  std::ofstream out_;
  bool has_header_ = false;
};

std::string csv_number(double value);  // %.9g; empty for NaN (a metric the stage lacks)

}  // namespace phyir::model
