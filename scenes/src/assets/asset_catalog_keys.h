#pragma once
// Typed access to the key#N values of one catalog: every failure names the archive, the
// key with its value and the line ("Scopia.sh3f: width#12=abc is not a number (line 340)").
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "assets/asset_properties.h"

namespace phyir::scenes {

class CatalogKeys {
 public:
  CatalogKeys(const std::map<std::string, PropertyValue>& properties, std::string archive_name)
      : properties_(properties), archive_(std::move(archive_name)) {}

  const std::string& archive() const { return archive_; }
  // The value of prefix#index (or of `prefix` alone when index is 0), if written.
  const PropertyValue* find(const std::string& prefix, int index) const;
  std::optional<std::string> text(const std::string& prefix, int index) const;
  std::string required_text(const std::string& prefix, int index) const;
  std::optional<float> number(const std::string& prefix, int index) const;
  float required_number(const std::string& prefix, int index) const;
  // Sizes: a number > 0.
  float required_length(const std::string& prefix, int index) const;
  std::optional<bool> boolean(const std::string& prefix, int index) const;
  // Space-separated numbers (light sources, sashes, modelRotation); `expected` < 0 means any
  // count, otherwise the count must match.
  std::vector<float> numbers(const std::string& prefix, int index, int expected = -1) const;
  // Space-separated colours, "#RRGGBB" or a decimal integer, as 0xRRGGBB.
  std::vector<unsigned> colours(const std::string& prefix, int index, int expected) const;
  // Indices N with a name#N key, ascending.
  std::vector<int> entry_indices() const;

  [[noreturn]] void fail_value(const std::string& prefix, int index, const std::string& problem) const;

 private:
  const std::map<std::string, PropertyValue>& properties_;
  std::string archive_;
};

}  // namespace phyir::scenes
