// Loading a glTF file with tinygltf after checking its container, and validated typed reads of its
// accessors. Every read checks indices, types, component types, counts, strides and byte ranges
// before touching a buffer, and rejects NaN/infinite floats; failures are InputErrors naming the
// file and the element.
#pragma once

#include <tiny_gltf.h>

#include <cstdint>
#include <initializer_list>
#include <string>
#include <vector>

namespace pelage::animation::gltf {

// Reads `path` (.gltf text or .glb binary, told apart by the GLB magic), validates the GLB
// container, parses it with tinygltf (textures are not decoded), then validates required
// extensions, buffer views and the node tree's indices.
tinygltf::Model loadModelFile(const std::string& path);

class Accessors {
 public:
  Accessors(const tinygltf::Model& model, std::string path)
      : model_(model), path_(std::move(path)) {}

  // Element count of accessor `index` (validated index); `what` names its use in messages.
  std::size_t count(int index, const std::string& what) const;
  // Float components (count x components of `type`), row by row. FLOAT always; BYTE/UBYTE/SHORT/
  // USHORT too when `allowNormalized` and the accessor is normalized (glTF's decoding rules).
  std::vector<float> floats(int index, int type, bool allowNormalized,
                            const std::string& what) const;
  // Unsigned integer components of one of `componentTypes` (UNSIGNED_BYTE/SHORT/INT).
  std::vector<std::uint32_t> uints(int index, int type, std::initializer_list<int> componentTypes,
                                   const std::string& what) const;

 private:
  struct View {
    const unsigned char* data = nullptr;  // first element (null: all zeros, no bufferView)
    std::size_t count = 0, stride = 0, components = 0, componentSize = 0;
    int componentType = 0;
    bool normalized = false;
  };
  View view(int index, int type, const std::string& what) const;
  [[noreturn]] void fail(const std::string& what, int index, const std::string& message) const;

  const tinygltf::Model& model_;
  std::string path_;
};

}  // namespace pelage::animation::gltf
