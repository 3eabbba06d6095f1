#pragma once
// The output folder of import-futurehouse and export-futurehouse: built as OUT.partial and
// renamed to OUT when whole, so OUT exists only complete. A run that fails removes its
// OUT.partial; one that is killed leaves it, and the next run deletes it first.
#include <filesystem>

namespace phyir::dataset {

class PartialFolder {
 public:
  // Throws phyir::Error when OUT exists already (an interchange never overwrites).
  explicit PartialFolder(std::filesystem::path out);
  ~PartialFolder();
  PartialFolder(const PartialFolder&) = delete;
  PartialFolder& operator=(const PartialFolder&) = delete;

  const std::filesystem::path& path() const { return partial_; }
  void commit();  // renames OUT.partial to OUT

 private:
  std::filesystem::path out_, partial_;
  bool committed_ = false;
};

}  // namespace phyir::dataset
