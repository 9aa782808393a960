// The tinygltf implementation, compiled once here. The target defines TINYGLTF_NO_STB_IMAGE,
// TINYGLTF_NO_STB_IMAGE_WRITE and TINYGLTF_NO_EXTERNAL_IMAGE for every source (animation/
// CMakeLists.txt), so all of them see the same class definitions: tinygltf neither decodes nor
// loads an image; gltf_import.cpp does both, with limits, through util/image.h.
#define TINYGLTF_IMPLEMENTATION
#include <tiny_gltf.h>
