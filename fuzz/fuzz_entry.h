// Entry points shared by the libFuzzer targets (fuzz/fuzz_*.cpp, built with clang when
// PELAGE_FUZZ=ON) and the regression test that replays saved inputs in every build
// (tests/fuzz/fuzz_regression_test.cpp). Each reads one untrusted input the way the command line
// does. A clean rejection (pelage::util::InputError) is the expected outcome for bad input and
// returns false; anything else that escapes (another exception, a sanitizer report, a crash) is a
// finding.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

namespace pelage::fuzz {

// The fuzzed input readers, by name: creature, preset, clip, pose, gltf, mesh, image, groom,
// strokes.
const std::vector<std::string>& targetNames();

// Runs target `name` on `data`; true when the input was accepted, false when it was rejected with
// an InputError. Unknown names throw std::invalid_argument.
bool runTarget(std::string_view name, const std::uint8_t* data, std::size_t size);

// Mesh inputs carry their format in the first byte (data[0] % 4: obj, ply, off, stl), the file
// after it; image inputs are the file (PNG, JPEG, ...), their last byte also picks the texture's
// wrap modes, filter and encoding; glTF inputs starting with the GLB magic are read as .glb, others
// as .gltf (JSON).
std::string meshInput(std::string_view extension, std::string_view fileBytes);

// Groom inputs are groom files (fur/groom.h) for the target's own mesh, a 4 x 4-vertex grid; this
// is a valid one (its corpus seed, fuzz/corpus/groom/example.json, is this text).
std::string groomExample();
// Strokes inputs are grooming strokes files (fur/groom_strokes.h), applied to the groom target's
// grid; this is a valid one (its corpus seed, fuzz/corpus/strokes/example.json, is this text).
std::string strokesExample();

}  // namespace pelage::fuzz
