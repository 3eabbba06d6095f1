#include "futurehouse_folder.h"

#include "phyir/core/error.h"
#include "phyir/dataset/layout.h"

namespace phyir::dataset {

namespace fs = std::filesystem;

PartialFolder::PartialFolder(fs::path out) : out_(std::move(out)) {
  if (out_.filename().empty()) out_ = out_.parent_path();  // "dir/" names dir
  partial_ = out_;
  partial_ += ".partial";
  std::error_code ec;
  if (fs::exists(out_, ec)) fail("{}: exists already; give a new folder (nothing is overwritten)", out_.string());
  fs::remove_all(partial_, ec);
  fs::create_directories(partial_, ec);
  if (ec) fail("{}: cannot create: {}", partial_.string(), ec.message());
}

PartialFolder::~PartialFolder() {
  std::error_code ec;
  if (!committed_) fs::remove_all(partial_, ec);
}

void PartialFolder::commit() {
  sync_folder(partial_);
  std::error_code ec;
  fs::rename(partial_, out_, ec);
  if (ec) fail("{}: cannot rename {} into place: {}", out_.string(), partial_.string(), ec.message());
  const fs::path parent = out_.has_parent_path() ? out_.parent_path() : fs::path(".");
  sync_folder(parent);
  committed_ = true;
}

}  // namespace phyir::dataset
