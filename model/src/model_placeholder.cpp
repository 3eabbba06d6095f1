// The network arrives with issue 6; this file keeps the library target valid.
namespace phyir::model {
int model_library_version() { return 0; }
}  // namespace phyir::model
