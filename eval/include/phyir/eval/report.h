#pragma once
// report.md from metrics.json's content: tables laid out like the paper's Tables 2
// (materials, normal, re-render), 5 (relighting), 6 (probes) and 7/11 (depth), a per-scene
// breakdown, the masks and resampling used, and the side-by-side figures.
#include <string>

#include <nlohmann/json.hpp>

namespace phyir::eval {

std::string report_markdown(const nlohmann::json& metrics);

// The main table (Table 2's layout) alone, as in the report (for the CLI's summary).
std::string main_table_markdown(const nlohmann::json& metrics);

}  // namespace phyir::eval
