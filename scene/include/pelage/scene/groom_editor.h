// Brushing on the creature (issue 28): what the viewer's brushes need apart from GL and widgets.
//  - startingGroom: the per-vertex groom strokes start from (the one `pelage groom` edits);
//  - pickSkin: the skin point under a pixel of the frame as drawn, with its rest position, where
//    strokes are recorded (fur/groom_strokes.h);
//  - GroomEditor: a groom under strokes as they are drawn, with undo and redo. Its groom is always
//    applyGroomStrokes(start, strokes()) bit for bit, so its strokes replayed by `pelage groom` on
//    the same start write the same groom file.
#pragma once

#include <Eigen/Core>

#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "pelage/fur/groom.h"
#include "pelage/fur/groom_strokes.h"
#include "pelage/scene/camera.h"
#include "pelage/scene/frame.h"
#include "pelage/scene/model.h"

namespace pelage::scene {

// The fur's per-vertex groom (its groom file and regions: fur::resolveVertexGroom) with the skin's
// fur lengths where it has none. InputError naming `source` as resolveVertexGroom does.
fur::VertexGroom startingGroom(const Model& model, const fur::FurParams& params,
                               const std::string& source);

// A point of the skin under the cursor.
struct SkinHit {
  int triangle = -1;
  Eigen::Vector3f barycentric = Eigen::Vector3f::Zero();  // weights of the triangle's vertices
  Eigen::Vector3f position = Eigen::Vector3f::Zero();     // on the frame's deformed skin
  Eigen::Vector3f rest = Eigen::Vector3f::Zero();         // the same point on the rest skin
  float distance = 0.0f;                                  // from the camera's eye (metres)
};

// The nearest skin triangle (either face) on the ray from `camera`'s eye through the pixel
// (x, y) of its viewport (pixels from the top-left corner, as a window's cursor); nullopt where the
// ray misses the skin. `frame` holds the deformed skin as drawn (evaluateFrame).
std::optional<SkinHit> pickSkin(const Model& model, const FrameState& frame, const Camera& camera,
                                float x, float y);

// The world length (metres) that `pixels` pixels of `camera`'s viewport span at `distance` from its
// eye: a brush radius given on the screen.
float pixelsToMeters(const Camera& camera, float pixels, float distance);

class GroomEditor {
 public:
  // Edits `start` (startingGroom) on `model`'s skin; the model must outlive the editor.
  GroomEditor(const Model& model, fur::VertexGroom start);

  const fur::VertexGroom& groom() const { return groom_; }
  const fur::VertexGroom& start() const { return start_; }
  // The strokes applied to the start, in order: undone ones are not, the one being drawn is.
  const std::vector<fur::GroomStroke>& strokes() const { return strokes_; }
  // Changes whenever groom() does.
  std::uint64_t revision() const { return revision_; }

  // A stroke with `brush`'s tool, radius, strength, colour, cut length and mirror (its points are
  // ignored; validateGroomStroke checks the rest, InputError naming `source`). Ends any stroke
  // being drawn and drops the redo history.
  void beginStroke(const fur::GroomStroke& brush, const std::string& source = "brush");
  // Adds a rest-pose point to the stroke being drawn unless it lies closer than `spacing` metres
  // to its last point, and applies the stroke so far; returns whether the groom changed.
  bool addPoint(const Eigen::Vector3f& rest, float spacing = 0.0f);
  // Ends the stroke (one that could not apply, e.g. a comb of one point, leaves no trace).
  void endStroke();
  // Applies a whole stroke (a strokes file's: validateGroomStroke, InputError naming `source`),
  // undoable as a drawn one.
  void applyStroke(const fur::GroomStroke& stroke, const std::string& source);
  bool drawing() const { return drawing_; }

  bool canUndo() const { return !drawing_ && !strokes_.empty(); }
  bool canRedo() const { return !drawing_ && !undone_.empty(); }
  void undo();  // the groom before the last stroke, bit for bit
  void redo();

  // Starts over from `start` (a loaded groom file) with no strokes and no history.
  void reset(fur::VertexGroom start);

 private:
  // groom_ = the start with strokes_[0, n) applied, from the nearest checkpoint.
  void rebuild();
  bool strokeApplies(const fur::GroomStroke& s) const;

  const Model* model_;
  fur::VertexGroom start_;
  fur::VertexGroom groom_;
  fur::VertexGroom beforeStroke_;  // the groom the stroke being drawn applies to
  fur::GroomStroke current_;       // the stroke being drawn
  std::vector<fur::GroomStroke> strokes_;
  std::vector<fur::GroomStroke> undone_;  // the redo stack (last undone at the back)
  // The groom after the first k strokes, every kCheckpointEvery strokes (bounded memory on big
  // meshes; undo replays at most kCheckpointEvery - 1 strokes).
  std::vector<std::pair<std::size_t, fur::VertexGroom>> checkpoints_;
  static constexpr std::size_t kCheckpointEvery = 16;
  bool drawing_ = false;
  bool strokeApplied_ = false;  // the stroke being drawn is in strokes_
  std::uint64_t revision_ = 0;
};

}  // namespace pelage::scene
