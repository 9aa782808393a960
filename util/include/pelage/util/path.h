// Names as pelage reads them: file extensions and name patterns compared without case.
#pragma once

#include <string>
#include <string_view>

namespace pelage {

// The extension of the path's file name with its dot, lower-cased ("Fox.GLB" -> ".glb"); "" when
// the file name has none. Every reader and writer that picks a format by extension asks this.
std::string lowerExtension(std::string_view path);

// `text` lower-cased (ASCII).
std::string lowerCase(std::string_view text);

// True when `name` matches the glob `pattern`, ASCII case ignored; '*' matches any run of
// characters (none included), every other character itself ("Eye*" matches "eyes_black",
// "b_Tail*" "b_Tail01_012"). Region, material and joint patterns (no-fur regions, fur regions).
bool globMatches(std::string_view pattern, std::string_view name);

}  // namespace pelage
