// The GLSL files of render/src/shaders, embedded at build time (cmake/embed_files.cmake).
#pragma once

#include <cstddef>
#include <string_view>

namespace pelage::render::detail {

struct ShaderFile {
  const char* name;
  const char* text;
};
extern const ShaderFile kShaders[];
extern const std::size_t kShaderCount;

// The text of shader file `name` (e.g. "hair.vert"); PELAGE_CHECK fails for an unknown name.
std::string_view shaderSource(std::string_view name);

}  // namespace pelage::render::detail
