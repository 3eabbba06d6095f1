#pragma once
// Java .properties text (java.util.Properties.load): Latin-1 bytes, '#' and '!' comments,
// key and value separated by '=', ':' or white space, backslash escapes (\uXXXX, \t, \n,
// \r, \f, and \x for any other x), a trailing odd backslash continuing the line on the
// next with its leading white space dropped. Sweet Home 3D's catalogs are read this way.
#include <map>
#include <string>
#include <string_view>

namespace phyir::scenes {

struct PropertyValue {
  std::string text;  // UTF-8
  int line = 0;      // 1-based line where the key starts
};

// Key (UTF-8) -> value; a repeated key keeps its last value, as Java does. Throws
// phyir::Error naming `source` and the line for a malformed \uXXXX escape.
std::map<std::string, PropertyValue> read_java_properties(std::string_view latin1, const std::string& source);

}  // namespace phyir::scenes
