// One frame of a model: pose -> forward kinematics -> skin deformation -> fur (distance culling
// and, when asked, the CPU fur model). The Model and the Fur (parameters and grown roots) are the
// constant part; FrameState holds everything that changes per frame, sized on first use and reused,
// so evaluating a frame neither allocates nor throws after the first call.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "pelage/anatomy/pose.h"
#include "pelage/fur/colors.h"
#include "pelage/fur/culling.h"
#include "pelage/fur/fur_params.h"
#include "pelage/fur/generate.h"
#include "pelage/fur/roots.h"
#include "pelage/scene/camera.h"
#include "pelage/scene/model.h"
#include "pelage/skin/deform.h"

namespace pelage::scene {

// A creature's fur: validated parameters and the roots grown from them on the model's skin.
// Constant during playback; regrown (a new generation) when the hair count, undercoat share or
// seed change. Other parameters (styles, lengths, stiffness, materials...) apply per frame.
struct Fur {
  fur::FurParams params;
  fur::Groom groom;  // the images params.maps names, the vertex values of params.regions
  fur::FurRoots roots;
  fur::FurColors colors;              // each hair's colour (fur/colors.h)
  std::uint64_t generation = 0;       // unique per growFur call: renderers re-upload roots
  std::uint64_t colorGeneration = 0;  // unique per growFur and recolorFur: re-upload colours
};

// Validates `params` (InputError naming `source`, the field and the range), reads the groom maps,
// resolves the regions on the creature (fur/groom.h), grows the roots and colours them.
Fur growFur(const Model& model, fur::FurParams params,
            const std::string& source = "fur parameters");
// The same on a given per-vertex groom (a brushing session's: groom_editor.h) in place of the one
// params' groom file and regions resolve to.
Fur growFur(const Model& model, fur::FurParams params, fur::VertexGroom vertex,
            const std::string& source);

// New hair colours for `params`, whose only changes from fur.params are in the coats' colour
// models, materials or maps.color (!rootsDiffer): the roots stay (no new generation).
void recolorFur(const Model& model, Fur& fur, fur::FurParams params,
                const std::string& source = "fur parameters");

// True when going from `a` to `b` needs new roots (count, density, undercoat share, seed, the
// density and length maps, or the regions).
bool rootsDiffer(const fur::FurParams& a, const fur::FurParams& b);
// True when going from `a` to `b` needs new hair colours (colour models, materials, maps.color).
bool colorsDiffer(const fur::FurParams& a, const fur::FurParams& b);

// Longest hair the parameters can produce on the model (m): the largest vertex fur length times
// the global, coat and region scales. Used to pad bounds for camera framing.
float maxHairLength(const Model& model, const fur::FurParams& params);

struct FrameState {
  anatomy::Pose pose;
  anatomy::BodyState body;
  skin::DeformedSkin skin;
  Eigen::AlignedBox3f skinBounds;  // of the deformed skin positions

  // Fur (evaluateFur): culling for the camera, drawn hairs per coat, and the CPU model's buffers
  // when they were asked for.
  fur::FurView furView;
  float cullFactor = 1.0f;  // c of sec. 3.3
  std::array<std::int64_t, fur::kCoatCount> drawnHairs{0, 0};
  bool cpuFur = false;  // `fur` holds this frame's hairs
  fur::FurWorkspace furWorkspace;
  fur::FurFrame fur;
  std::array<std::vector<std::int32_t>, fur::kCoatCount> drawnStartScratch;
};

// Evaluates the model in `pose`: forward kinematics, skinning, bounds.
void evaluateFrame(const Model& model, const anatomy::Pose& pose, FrameState& frame);

// Evaluates clip `clip` (an index into model.clips) at `seconds`: a looping clip wraps and adds its
// root motion per completed cycle, a clamped one holds its ends (animation::sampleClip); then as
// evaluateFrame. PELAGE_CHECK fails for an index out of range.
void evaluateClipFrame(const Model& model, int clip, double seconds, FrameState& frame);

// The frame's fur seen by `camera` (after evaluateFrame): culling by the creature's scale on screen
// (sec. 3.3; fur/culling.h) and drawn counts; with `cpuHairs`, the hairs themselves by the CPU fur
// model (fur::generateFur). Without it the counts are still exact (the GPU applies the same
// culling rule).
void evaluateFur(const Model& model, const Fur& fur, const Camera& camera, bool cpuHairs,
                 FrameState& frame);
// The same for an explicit view (a viewing distance rather than a camera; FurView{}: every hair).
void evaluateFur(const Model& model, const Fur& fur, const fur::FurView& view, bool cpuHairs,
                 FrameState& frame);

}  // namespace pelage::scene
