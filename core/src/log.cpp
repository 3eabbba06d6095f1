#include "phyir/core/log.h"

#include <spdlog/sinks/stdout_color_sinks.h>

#include "phyir/core/error.h"

namespace phyir {

void init_logging() {
  static bool initialised = false;
  if (initialised) return;
  initialised = true;
  auto logger = spdlog::stderr_color_mt("phyir");
  logger->set_pattern("[%H:%M:%S] [%^%l%$] %v");
  spdlog::set_default_logger(logger);
}

void set_log_level(const std::string& level) {
  init_logging();
  const auto parsed = spdlog::level::from_str(level);
  if (parsed == spdlog::level::off && level != "off") {
    fail("unknown log level '{}': use trace, debug, info, warn, error or off", level);
  }
  spdlog::set_level(parsed);
}

}  // namespace phyir
