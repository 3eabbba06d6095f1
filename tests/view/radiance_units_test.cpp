// The radiance units (view/radiance_units.h): names, parsing, scale.
#include <gtest/gtest.h>

#include <string>

#include "phyir/core/error.h"
#include "phyir/view/radiance_units.h"

namespace pv = phyir::view;

TEST(RadianceUnits, NamesParseAndBadNamesAreNamed) {
  for (const std::string& name : pv::radiance_units_names())
    EXPECT_EQ(pv::radiance_units_name(pv::parse_radiance_units(name)), name);
  EXPECT_EQ(pv::radiance_scale(pv::RadianceUnits::kAbsolute, 5.0f), 1.0);
  EXPECT_EQ(pv::radiance_scale(pv::RadianceUnits::kInput, -2.0f), 0.25);
  try {
    pv::parse_radiance_units("relative");
    ADD_FAILURE() << "no error for an unknown unit";
  } catch (const phyir::Error& e) {
    const std::string message = e.what();
    EXPECT_NE(message.find("'relative'"), std::string::npos) << message;
    EXPECT_NE(message.find("absolute or input"), std::string::npos) << message;
  }
}
