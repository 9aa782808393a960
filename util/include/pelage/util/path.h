// File names as pelage reads them: extensions compared without case.
#pragma once

#include <string>
#include <string_view>

namespace pelage {

// The extension of the path's file name with its dot, lower-cased ("Fox.GLB" -> ".glb"); "" when
// the file name has none. Every reader and writer that picks a format by extension asks this.
std::string lowerExtension(std::string_view path);

// `text` lower-cased (ASCII).
std::string lowerCase(std::string_view text);

}  // namespace pelage
