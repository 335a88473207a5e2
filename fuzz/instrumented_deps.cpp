// stb_image and tinygltf compiled into the fuzz targets, so that their code carries the coverage
// instrumentation and the sanitizers. Debian ships both as uninstrumented shared libraries
// (libstb.so, libtinygltf.so); definitions in the executable take precedence over theirs.
#define STB_IMAGE_IMPLEMENTATION
#define STB_IMAGE_WRITE_IMPLEMENTATION
#include <stb/stb_image.h>
#include <stb/stb_image_write.h>

#define TINYGLTF_IMPLEMENTATION
#define TINYGLTF_NO_INCLUDE_STB_IMAGE
#define TINYGLTF_NO_INCLUDE_STB_IMAGE_WRITE
#include <tiny_gltf.h>
