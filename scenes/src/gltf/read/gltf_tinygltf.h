#pragma once
// Every file that includes tinygltf goes through this header so that all of them see
// the same configuration (the class layout depends on these macros). No stb: image
// bytes are kept as stored and decoded by OpenImageIO (gltf_textures.cpp).
#ifndef TINYGLTF_NO_STB_IMAGE
#define TINYGLTF_NO_STB_IMAGE
#endif
#ifndef TINYGLTF_NO_STB_IMAGE_WRITE
#define TINYGLTF_NO_STB_IMAGE_WRITE
#endif
#include <tiny_gltf.h>
