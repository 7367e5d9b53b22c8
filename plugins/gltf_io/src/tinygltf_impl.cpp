// The one translation unit that compiles tinygltf's implementation. Image
// decoding is left out (see CMakeLists.txt): we never need pixels.
#define TINYGLTF_IMPLEMENTATION
#include <tiny_gltf.h>
