// tinygltf as smql builds it: no image codecs (smql writes no textures) and no image files read
// from disk. Every file that includes tiny_gltf.h includes it through here, since the macros change
// the declarations (TinyGLTF's members); gltf.cpp compiles the implementation.
#pragma once

#define TINYGLTF_NO_STB_IMAGE
#define TINYGLTF_NO_STB_IMAGE_WRITE
#define TINYGLTF_NO_EXTERNAL_IMAGE
#include <tiny_gltf.h>
