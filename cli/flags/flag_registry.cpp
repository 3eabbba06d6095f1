#include "flag_registry.h"

#include <map>
#include <vector>

namespace phyir::cli {

namespace {

// Per command, setting -> flag. Commands live as long as the process's CLI::App.
std::map<const CLI::App*, std::map<std::string, std::string>>& registry() {
  static std::map<const CLI::App*, std::map<std::string, std::string>> flags;
  return flags;
}

}  // namespace

CLI::Option* sets(CLI::App* command, const std::string& setting, CLI::Option* option) {
  registry()[command][setting] = option->get_name();
  return option;
}

void sets(CLI::App* command, const std::string& setting, const std::string& flags) {
  registry()[command][setting] = flags;
}

std::string flag_of_setting(const CLI::App& app, const std::string& setting) {
  // The command that ran: the chain of parsed subcommands, named ones only (option groups
  // are unnamed subcommands).
  std::vector<const CLI::App*> chain = {&app};
  for (bool deeper = true; deeper;) {
    deeper = false;
    for (const CLI::App* sub : chain.back()->get_subcommands())
      if (!sub->get_name().empty()) {
        chain.push_back(sub);
        deeper = true;
        break;
      }
  }
  for (auto command = chain.rbegin(); command != chain.rend(); ++command) {
    const auto flags = registry().find(*command);
    if (flags == registry().end()) continue;
    const auto flag = flags->second.find(setting);
    if (flag != flags->second.end()) return flag->second;
  }
  return {};
}

std::string setting_error_message(const CLI::App& app, const SettingError& error) {
  const std::string flag = flag_of_setting(app, error.setting());
  return flag.empty() ? error.what() : flag + ": " + error.problem();
}

}  // namespace phyir::cli
