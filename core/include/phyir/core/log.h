#pragma once
// Logging for the whole toolkit: spdlog on stderr, one level per process (`phyir`'s log level).
#include <spdlog/spdlog.h>

#include <string>

namespace phyir {

// Accepts trace, debug, info, warn, error, off. Throws phyir::Error on anything else.
void set_log_level(const std::string& level);

// Installs the stderr logger once; safe to call repeatedly.
void init_logging();

}  // namespace phyir
