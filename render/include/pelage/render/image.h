// Frames as the renderer reads them back (util's RGBA8 image), their alpha, and PNG files (through
// util/image.h, the one image writer).
#pragma once

#include <Eigen/Core>

#include <cstdint>
#include <string>
#include <vector>

#include "pelage/util/image.h"

namespace pelage::render {

// A read-back frame: util's RGBA8 image (top row first).
using Image = Rgba8Image;

// Sets every alpha to 255.
void makeOpaque(Image& image);
// Turns a frame drawn over `background` (linear RGB) whose alpha holds each pixel's coverage a into
// straight alpha: each colour becomes c = (p - (1 - a) b) / a in linear light (clamped to [0, 1]),
// a quantised first, so that a c + (1 - a) b gives back p (of the 8-bit codes within 2 of c, the
// one whose composite is nearest p); pixels of alpha 0 become (0, 0, 0, 0). A pixel brighter than
// a of white over b (a hair's highlight, above 1 in linear light) gets the coverage that white
// needs to give p.
void unblendBackground(Image& image, const Eigen::Vector3f& background);

// Encodes `image` as PNG into memory (stb_image_write; thread-safe).
std::vector<std::uint8_t> encodePng(const Image& image);
// Writes a PNG atomically (temporary file + rename): never a truncated file. Throws InputError
// naming the file on failure (unwritable directory, disk full).
void writePng(const std::string& path, const Image& image);
// Writes a PNG (.png) or a JPEG (.jpg, .jpeg; quality 95, alpha dropped), chosen by the
// extension, atomically; InputError naming the file for another extension or a failed write.
void writeImage(const std::string& path, const Image& image);
// Reads a PNG (or any image util/image.h reads) as RGBA8; InputError naming the file if it is
// missing or not an image.
Image readPng(const std::string& path);
// True when `path` is a complete PNG file: the signature, an IHDR chunk first and an IEND chunk at
// the very end (what a run killed mid-write cannot leave under the final name anyway).
bool isCompletePng(const std::string& path);

}  // namespace pelage::render
