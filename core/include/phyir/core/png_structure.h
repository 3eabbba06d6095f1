#pragma once
// The chunk structure of a PNG held in memory, checked before a decoder sees it. libpng
// reports a read past the end of the data by longjmp from OpenImageIO's read callback,
// which in OIIO 2.4 (Debian 12) skips a destructor and leaks the error string (found by
// scripts/fuzz.sh): a truncated image inside a GLB must be refused before that, with a
// message that says what is wrong.
#include <cstddef>
#include <string>

namespace phyir {

// Empty when `bytes` is a PNG signature followed by whole chunks up to and including
// IEND; otherwise what is wrong ("truncated in chunk 3 (IDAT)", ...).
std::string png_structure_error(const unsigned char* bytes, size_t size);

}  // namespace phyir
