// CatalogKeys: the catalog's values parsed the way Java's Float.parseFloat and
// Boolean.parseBoolean read them, but refusing what they would silently default.
#include "assets/asset_catalog_keys.h"

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <sstream>

#include "phyir/core/error.h"

namespace phyir::scenes {

namespace {

std::string key_name(const std::string& prefix, int index) {
  return index > 0 ? prefix + "#" + std::to_string(index) : prefix;
}

std::string trimmed(const std::string& text) {
  const auto blank = [](unsigned char c) { return std::isspace(c) != 0; };
  const auto begin = std::find_if_not(text.begin(), text.end(), blank);
  const auto end = std::find_if_not(text.rbegin(), text.rend(), blank).base();
  return begin < end ? std::string(begin, end) : std::string();
}

std::vector<std::string> split_blanks(const std::string& text) {
  std::istringstream in(text);
  std::vector<std::string> words;
  for (std::string word; in >> word;) words.push_back(word);
  return words;
}

// Java's float syntax: decimal or exponent notation, an optional f/F/d/D suffix.
std::optional<float> parse_float(std::string word) {
  if (!word.empty() && std::string("fFdD").find(word.back()) != std::string::npos) word.pop_back();
  if (word.empty() || word.find_first_of("xXnN") != std::string::npos) return std::nullopt;  // no hex, nan, inf
  errno = 0;
  char* end = nullptr;
  const float value = std::strtof(word.c_str(), &end);
  if (errno != 0 || end != word.c_str() + word.size() || !std::isfinite(value)) return std::nullopt;
  return value;
}

}  // namespace

void CatalogKeys::fail_value(const std::string& prefix, int index, const std::string& problem) const {
  const PropertyValue* value = find(prefix, index);
  if (!value) fail("{}: {} {}", archive_, key_name(prefix, index), problem);
  fail("{}: {}={} {} (line {})", archive_, key_name(prefix, index), value->text, problem, value->line);
}

const PropertyValue* CatalogKeys::find(const std::string& prefix, int index) const {
  const auto it = properties_.find(key_name(prefix, index));
  return it == properties_.end() ? nullptr : &it->second;
}

std::optional<std::string> CatalogKeys::text(const std::string& prefix, int index) const {
  const PropertyValue* value = find(prefix, index);
  if (!value) return std::nullopt;
  return value->text;
}

std::string CatalogKeys::required_text(const std::string& prefix, int index) const {
  const std::optional<std::string> value = text(prefix, index);
  if (!value || trimmed(*value).empty()) fail_value(prefix, index, "is required but missing or empty");
  return *value;
}

std::optional<float> CatalogKeys::number(const std::string& prefix, int index) const {
  const PropertyValue* value = find(prefix, index);
  if (!value) return std::nullopt;
  const std::optional<float> parsed = parse_float(trimmed(value->text));
  if (!parsed) fail_value(prefix, index, "is not a number");
  return parsed;
}

float CatalogKeys::required_number(const std::string& prefix, int index) const {
  if (!find(prefix, index)) fail_value(prefix, index, "is required but missing");
  return *number(prefix, index);
}

float CatalogKeys::required_length(const std::string& prefix, int index) const {
  const float value = required_number(prefix, index);
  if (!(value > 0.0f)) fail_value(prefix, index, "must be a length > 0 cm");
  return value;
}

std::optional<bool> CatalogKeys::boolean(const std::string& prefix, int index) const {
  const PropertyValue* value = find(prefix, index);
  if (!value) return std::nullopt;
  std::string word = trimmed(value->text);
  std::transform(word.begin(), word.end(), word.begin(), [](unsigned char c) { return std::tolower(c); });
  if (word != "true" && word != "false") fail_value(prefix, index, "is not true or false");
  return word == "true";
}

std::vector<float> CatalogKeys::numbers(const std::string& prefix, int index, int expected) const {
  const PropertyValue* value = find(prefix, index);
  if (!value) fail_value(prefix, index, "is required but missing");
  std::vector<float> result;
  for (const std::string& word : split_blanks(value->text)) {
    const std::optional<float> parsed = parse_float(word);
    if (!parsed) fail_value(prefix, index, "has '" + word + "', not a number");
    result.push_back(*parsed);
  }
  if (result.empty()) fail_value(prefix, index, "has no numbers");
  if (expected >= 0 && static_cast<int>(result.size()) != expected) {
    fail_value(prefix, index, "has " + std::to_string(result.size()) + " numbers, expected " + std::to_string(expected));
  }
  return result;
}

std::vector<unsigned> CatalogKeys::colours(const std::string& prefix, int index, int expected) const {
  const PropertyValue* value = find(prefix, index);
  if (!value) fail_value(prefix, index, "is required but missing");
  std::vector<unsigned> result;
  for (const std::string& word : split_blanks(value->text)) {
    const bool hex = word.size() > 1 && word[0] == '#';
    char* end = nullptr;
    const unsigned long parsed = std::strtoul(word.c_str() + (hex ? 1 : 0), &end, hex ? 16 : 10);
    if (end != word.c_str() + word.size() || parsed > 0xFFFFFFul) {
      fail_value(prefix, index, "has '" + word + "', not a colour (#RRGGBB)");
    }
    result.push_back(static_cast<unsigned>(parsed));
  }
  if (static_cast<int>(result.size()) != expected) {
    fail_value(prefix, index, "has " + std::to_string(result.size()) + " colours, expected " + std::to_string(expected));
  }
  return result;
}

std::vector<int> CatalogKeys::entry_indices() const {
  std::vector<int> indices;
  for (const auto& [key, value] : properties_) {
    if (key.rfind("name#", 0) != 0) continue;
    const std::string digits = key.substr(5);
    if (digits.empty() || digits.find_first_not_of("0123456789") != std::string::npos || digits.size() > 9) continue;
    indices.push_back(std::stoi(digits));
  }
  std::sort(indices.begin(), indices.end());
  indices.erase(std::remove(indices.begin(), indices.end(), 0), indices.end());
  return indices;
}

}  // namespace phyir::scenes
