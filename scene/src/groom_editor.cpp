#include "pelage/scene/groom_editor.h"

#include <cmath>
#include <limits>

#include "pelage/fur/culling.h"
#include "pelage/util/error.h"

namespace pelage::scene {

fur::VertexGroom startingGroom(const Model& model, const fur::FurParams& params,
                               const std::string& source) {
  fur::VertexGroom groom =
      fur::resolveVertexGroom(model.skin, model.body, model.name, params, source);
  if (groom.length.empty())
    groom.length.assign(model.skin.furLengths(),
                        model.skin.furLengths() + model.skin.numVertices());
  return groom;
}

std::optional<SkinHit> pickSkin(const Model& model, const FrameState& frame, const Camera& camera,
                                float x, float y) {
  const std::vector<Eigen::Vector3f>& pos = frame.skin.positions;
  PELAGE_CHECK(pos.size() == static_cast<std::size_t>(model.skin.numVertices()),
               "pickSkin before evaluateFrame");
  // The ray through the pixel in eye space (looking down -z), turned into the world by the view's
  // rotation (its rows are the eye's axes).
  const float tanHalf = std::tan(camera.fovYDegrees * 3.14159265358979f / 360.0f);
  const float ndcX = 2.0f * x / static_cast<float>(camera.width) - 1.0f;
  const float ndcY = 1.0f - 2.0f * y / static_cast<float>(camera.height);
  const Eigen::Vector3f eyeDir(ndcX * tanHalf * camera.aspect(), ndcY * tanHalf, -1.0f);
  const Eigen::Matrix3f toEye = camera.view().block<3, 3>(0, 0);
  const Eigen::Vector3f dir = (toEye.transpose() * eyeDir).normalized();
  const Eigen::Vector3f& o = camera.eye;
  // Moeller & Trumbore 1997, both faces; the nearest hit in front of the eye.
  std::optional<SkinHit> best;
  float bestT = std::numeric_limits<float>::infinity();
  const std::int32_t* tri = model.skin.triangles.data();
  for (int t = 0; t < model.skin.numTriangles(); ++t) {
    const Eigen::Vector3f& a = pos[static_cast<std::size_t>(tri[3 * t])];
    const Eigen::Vector3f e1 = pos[static_cast<std::size_t>(tri[3 * t + 1])] - a;
    const Eigen::Vector3f e2 = pos[static_cast<std::size_t>(tri[3 * t + 2])] - a;
    const Eigen::Vector3f p = dir.cross(e2);
    const float det = e1.dot(p);
    if (std::abs(det) < 1e-20f) continue;
    const float inv = 1.0f / det;
    const Eigen::Vector3f s = o - a;
    const float u = s.dot(p) * inv;
    if (u < 0.0f || u > 1.0f) continue;
    const Eigen::Vector3f q = s.cross(e1);
    const float v = dir.dot(q) * inv;
    if (v < 0.0f || u + v > 1.0f) continue;
    const float dist = e2.dot(q) * inv;
    if (!(dist > 0.0f && dist < bestT)) continue;
    bestT = dist;
    SkinHit h;
    h.triangle = t;
    h.barycentric = Eigen::Vector3f(1.0f - u - v, u, v);
    h.distance = dist;
    best = h;
  }
  if (!best) return best;
  const float* rest = model.skin.restPositions();
  for (int k = 0; k < 3; ++k) {
    const auto v = static_cast<std::size_t>(tri[3 * best->triangle + k]);
    best->position += best->barycentric[k] * pos[v];
    best->rest += best->barycentric[k] * Eigen::Map<const Eigen::Vector3f>(rest + 3 * v);
  }
  return best;
}

float pixelsToMeters(const Camera& camera, float pixels, float distance) {
  return pixels / fur::pixelsPerMeter(distance, camera.fovYDegrees, camera.height);
}

GroomEditor::GroomEditor(const Model& model, fur::VertexGroom start)
    : model_(&model), start_(std::move(start)), groom_(start_) {}

bool GroomEditor::strokeApplies(const fur::GroomStroke& s) const {
  if (s.points.empty()) return false;
  if (s.tool != fur::BrushTool::Comb) return true;
  for (const Eigen::Vector3f& p : s.points)
    if (p != s.points[0]) return true;
  return false;  // a comb needs a direction
}

void GroomEditor::beginStroke(const fur::GroomStroke& brush, const std::string& source) {
  fur::validateGroomStroke(brush, source, /*needPoints=*/false);
  if (drawing_) endStroke();
  undone_.clear();
  current_ = brush;
  current_.points.clear();
  beforeStroke_ = groom_;
  drawing_ = true;
  strokeApplied_ = false;
}

bool GroomEditor::addPoint(const Eigen::Vector3f& rest, float spacing) {
  PELAGE_CHECK(drawing_, "addPoint outside a stroke");
  if (!rest.allFinite() || current_.points.size() >= fur::kMaxStrokePoints) return false;
  if (!current_.points.empty() && (rest - current_.points.back()).norm() < spacing) return false;
  current_.points.push_back(rest);
  if (!strokeApplies(current_)) return false;
  groom_ = beforeStroke_;
  fur::applyGroomStrokes(model_->skin, {current_}, groom_);
  if (strokeApplied_) {
    strokes_.back() = current_;
  } else {
    strokes_.push_back(current_);
    strokeApplied_ = true;
  }
  ++revision_;
  return true;
}

void GroomEditor::endStroke() {
  if (!drawing_) return;
  drawing_ = false;
  if (strokeApplied_ && strokes_.size() % kCheckpointEvery == 0)
    checkpoints_.emplace_back(strokes_.size(), groom_);
  strokeApplied_ = false;
  beforeStroke_ = {};
}

void GroomEditor::applyStroke(const fur::GroomStroke& stroke, const std::string& source) {
  fur::validateGroomStroke(stroke, source);
  endStroke();
  undone_.clear();
  fur::applyGroomStrokes(model_->skin, {stroke}, groom_);
  strokes_.push_back(stroke);
  if (strokes_.size() % kCheckpointEvery == 0) checkpoints_.emplace_back(strokes_.size(), groom_);
  ++revision_;
}

void GroomEditor::rebuild() {
  while (!checkpoints_.empty() && checkpoints_.back().first > strokes_.size())
    checkpoints_.pop_back();
  const std::size_t from = checkpoints_.empty() ? 0 : checkpoints_.back().first;
  groom_ = checkpoints_.empty() ? start_ : checkpoints_.back().second;
  const std::vector<fur::GroomStroke> rest(strokes_.begin() + static_cast<std::ptrdiff_t>(from),
                                           strokes_.end());
  fur::applyGroomStrokes(model_->skin, rest, groom_);
  ++revision_;
}

void GroomEditor::undo() {
  if (!canUndo()) return;
  undone_.push_back(std::move(strokes_.back()));
  strokes_.pop_back();
  rebuild();
}

void GroomEditor::redo() {
  if (!canRedo()) return;
  strokes_.push_back(std::move(undone_.back()));
  undone_.pop_back();
  fur::applyGroomStrokes(model_->skin, {strokes_.back()}, groom_);
  if (strokes_.size() % kCheckpointEvery == 0 &&
      (checkpoints_.empty() || checkpoints_.back().first != strokes_.size()))
    checkpoints_.emplace_back(strokes_.size(), groom_);
  ++revision_;
}

void GroomEditor::reset(fur::VertexGroom start) {
  drawing_ = strokeApplied_ = false;
  start_ = std::move(start);
  groom_ = start_;
  beforeStroke_ = {};
  strokes_.clear();
  undone_.clear();
  checkpoints_.clear();
  ++revision_;
}

}  // namespace pelage::scene
