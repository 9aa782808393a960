// Groom maps: images on the skin's UV layout that shape the fur (as Maya XGen's density and length
// maps, Blender's density masks): read once per fur, sampled at each root's texture coordinates
// (the root's barycentric point, sec. 3.2).
#pragma once

#include <string>

#include "pelage/fur/fur_params.h"
#include "pelage/skin/skin_mesh.h"
#include "pelage/skin/texture.h"

namespace pelage::fur {

// The groom maps, loaded (empty textures where the preset names none).
//  density: linear data, nearest texel (each texel a cell of constant density, so a zero texel
//    grows no hair); a triangle's hairs are proportional to its area times the map's mean over it.
//  length: linear data, bilinear; multiplies each hair's interpolated length (grey 0.5: half).
//  color: sRGB colour, bilinear; the Map colour source.
struct GroomMaps {
  skin::Texture density, length, color;
  bool any() const { return !density.empty() || !length.empty() || !color.empty(); }
};

// Reads the maps `paths` names (util/image.h limits). InputError naming the field
// ("maps.density") and the file for a missing or unreadable image, and for maps on a skin without
// texture coordinates (naming `modelName`).
GroomMaps loadGroomMaps(const GroomMapPaths& paths, const skin::SkinMesh& skin,
                        const std::string& modelName);

}  // namespace pelage::fur
