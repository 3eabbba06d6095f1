// The dataset pipeline arrives with issue 5; this file keeps the library target valid.
namespace phyir::dataset {
int dataset_library_version() { return 0; }
}  // namespace phyir::dataset
