// read_java_properties: the format of java.util.Properties.load(InputStream).
#include "assets/asset_properties.h"

#include <cctype>

#include "phyir/core/error.h"

namespace phyir::scenes {

namespace {

void append_utf8(std::string& out, unsigned code_point) {
  if (code_point < 0x80) {
    out += static_cast<char>(code_point);
  } else if (code_point < 0x800) {
    out += static_cast<char>(0xC0 | (code_point >> 6));
    out += static_cast<char>(0x80 | (code_point & 0x3F));
  } else {
    out += static_cast<char>(0xE0 | (code_point >> 12));
    out += static_cast<char>(0x80 | ((code_point >> 6) & 0x3F));
    out += static_cast<char>(0x80 | (code_point & 0x3F));
  }
}

bool is_blank(char c) { return c == ' ' || c == '\t' || c == '\f'; }
bool is_line_end(char c) { return c == '\n' || c == '\r'; }

void skip_natural_line(std::string_view text, size_t& pos, int& line) {
  while (pos < text.size() && !is_line_end(text[pos])) ++pos;
  if (pos < text.size()) {
    pos += (text[pos] == '\r' && pos + 1 < text.size() && text[pos + 1] == '\n') ? 2 : 1;
    ++line;
  }
}

// One logical line: natural lines joined where a line ends with an odd number of
// backslashes (the backslash, the line break and the next line's leading blanks dropped).
// Escapes other than the joins are kept for unescape(). Advances `pos` and `line`.
std::string next_logical_line(std::string_view text, size_t& pos, int& line) {
  std::string logical;
  while (pos < text.size()) {
    const size_t start = pos;
    size_t end = pos;
    while (end < text.size() && !is_line_end(text[end])) ++end;
    const std::string_view natural = text.substr(start, end - start);
    skip_natural_line(text, pos, line);
    size_t backslashes = 0;
    while (backslashes < natural.size() && natural[natural.size() - 1 - backslashes] == '\\') ++backslashes;
    if (backslashes % 2 == 0) {
      logical += natural;
      return logical;
    }
    logical += natural.substr(0, natural.size() - 1);
    while (pos < text.size() && is_blank(text[pos])) ++pos;  // the continuation's indent
  }
  return logical;
}

unsigned hex_digit(char c) {
  if (c >= '0' && c <= '9') return static_cast<unsigned>(c - '0');
  if (c >= 'a' && c <= 'f') return static_cast<unsigned>(c - 'a' + 10);
  if (c >= 'A' && c <= 'F') return static_cast<unsigned>(c - 'A' + 10);
  return 16;
}

// Latin-1 with Java escapes -> UTF-8.
std::string unescape(std::string_view raw, const std::string& source, int line) {
  std::string out;
  out.reserve(raw.size());
  for (size_t i = 0; i < raw.size(); ++i) {
    const unsigned char c = static_cast<unsigned char>(raw[i]);
    if (c != '\\' || i + 1 == raw.size()) {
      append_utf8(out, c);  // a Latin-1 byte is its own code point
      continue;
    }
    const char e = raw[++i];
    if (e == 'u') {
      unsigned code = 0;
      for (int k = 0; k < 4; ++k) {
        const unsigned digit = i + 1 < raw.size() ? hex_digit(raw[i + 1]) : 16;
        if (digit == 16) fail("{}: line {}: malformed \\uXXXX escape in '{}'", source, line, std::string(raw));
        code = code * 16 + digit;
        ++i;
      }
      append_utf8(out, code);
    } else {
      append_utf8(out, static_cast<unsigned char>(e == 't' ? '\t' : e == 'n' ? '\n' : e == 'r' ? '\r' : e == 'f' ? '\f' : e));
    }
  }
  return out;
}

// End of the key: the first unescaped '=', ':' or blank.
size_t key_end(std::string_view logical, size_t start) {
  for (size_t i = start; i < logical.size(); ++i) {
    if (logical[i] == '\\') {
      ++i;
    } else if (logical[i] == '=' || logical[i] == ':' || is_blank(logical[i])) {
      return i;
    }
  }
  return logical.size();
}

}  // namespace

std::map<std::string, PropertyValue> read_java_properties(std::string_view latin1, const std::string& source) {
  std::map<std::string, PropertyValue> properties;
  size_t pos = 0;
  int line = 1;
  while (pos < latin1.size()) {
    const int first_line = line;
    size_t first = pos;
    while (first < latin1.size() && is_blank(latin1[first])) ++first;
    if (first < latin1.size() && (latin1[first] == '#' || latin1[first] == '!')) {
      skip_natural_line(latin1, pos, line);  // a comment never continues onto the next line
      continue;
    }
    const std::string logical = next_logical_line(latin1, pos, line);
    size_t start = 0;
    while (start < logical.size() && is_blank(logical[start])) ++start;
    if (start == logical.size()) continue;
    const size_t end = key_end(logical, start);
    size_t value = end;
    while (value < logical.size() && is_blank(logical[value])) ++value;
    if (value < logical.size() && (logical[value] == '=' || logical[value] == ':')) ++value;
    while (value < logical.size() && is_blank(logical[value])) ++value;
    const std::string_view view(logical);
    properties[unescape(view.substr(start, end - start), source, first_line)] =
        PropertyValue{unescape(view.substr(value), source, first_line), first_line};
  }
  return properties;
}

}  // namespace phyir::scenes
