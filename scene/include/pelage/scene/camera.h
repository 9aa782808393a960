// Cameras: the perspective camera every client draws with, the presets framed on the creature, the
// viewer's orbit, camera files (keys along the frames), the camera rig of a frame sequence, and the
// one rule for clip planes. World frame: metres, Z up. GL-free.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>

#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "pelage/fur/culling.h"
#include "pelage/scene/model.h"

namespace pelage::scene {

struct FrameState;

// A perspective camera. The viewport is the image size in pixels.
struct Camera {
  Eigen::Vector3f eye{1.0f, 0.0f, 0.0f};
  Eigen::Vector3f target = Eigen::Vector3f::Zero();
  Eigen::Vector3f up = Eigen::Vector3f::UnitZ();
  float fovYDegrees = 35.0f;  // vertical field of view
  float nearMeters = 0.01f;
  float farMeters = 100.0f;
  int width = 900;
  int height = 900;

  float aspect() const { return static_cast<float>(width) / static_cast<float>(height); }
  float distance() const { return (eye - target).norm(); }
  // World -> eye (right-handed, looking down -z), column-major as OpenGL takes it.
  Eigen::Matrix4f view() const;
  // Eye -> clip (OpenGL conventions: NDC z in [-1, 1]).
  Eigen::Matrix4f projection() const;
  Eigen::Matrix4f viewProjection() const { return projection() * view(); }
};

// What fur culling needs of a camera: its eye, vertical field of view and image height.
fur::ViewCamera viewCamera(const Camera& camera);

// The vertical field of view (degrees) of presets and orbits unless one is given.
inline constexpr float kDefaultFovYDegrees = 35.0f;
// The limits of an image and its camera, each checked by its validator (InputError naming
// `field`): sides in [kMinImageSide, kMaxImageSide], the vertical field of view in the open
// interval (kMinFovYDegrees, kMaxFovYDegrees).
inline constexpr int kMinImageSide = 16;
inline constexpr int kMaxImageSide = 16384;
void validateImageSize(int width, int height, std::string_view field = "size");
inline constexpr double kMinFovYDegrees = 1.0;
inline constexpr double kMaxFovYDegrees = 179.0;
void validateFov(double degrees, std::string_view field = "fov");
// MSAA samples of an image: -1 (4 on a GPU, none on a software rasteriser) or [0, kMaxSamples].
inline constexpr int kMaxSamples = 64;
void validateSamples(int samples, std::string_view field = "samples");

// The camera presets of the viewer and of `pelage render`.
enum class CameraPreset { Front, Side, ThreeQuarter, Face, Follow };
// "front", "side", "three-quarter", "face", "follow".
std::string_view cameraPresetName(CameraPreset preset);
// "front, side, three-quarter, face, follow".
std::string cameraPresetNames();
// Parses a preset name; throws InputError naming `field` and listing the accepted names.
CameraPreset parseCameraPreset(std::string_view name, std::string_view field = "camera");

// Where a creature is and which way it faces in one frame; what camera framing needs.
struct Framing {
  Eigen::AlignedBox3f bounds;                          // deformed skin plus the longest hair
  Eigen::Vector3f center = Eigen::Vector3f::Zero();    // centre of the bounding sphere
  float radius = 0.0f;                                 // bounding-sphere radius (metres)
  Eigen::Vector3f forward = Eigen::Vector3f::UnitX();  // horizontal unit vector the creature faces
  Eigen::Vector3f faceCenter = Eigen::Vector3f::Zero();  // centre of the face (see framingOf)
  float faceRadius = 0.0f;  // radius of a sphere around the face (metres)
  Eigen::Vector3f rootPosition = Eigen::Vector3f::Zero();  // world position of segment 0
};

// Framing of the current frame. `forward`: the horizontal direction from the body's centre to its
// head (a segment whose name contains "head", case-insensitive; +X, the monkey's facing, if none).
// The face: skin vertices of the region named "face" if the skin has one, else those bound to the
// head segment, else the whole body.
Framing framingOf(const Model& model, const FrameState& frame, float maxHairLengthMeters);

// The clip planes of every camera that looks at a creature (the one rule): near and far around the
// bounding sphere of `framing` seen from the camera's eye at distance d, near = max((d - r) / 2,
// r / 500) and far = d + 2 r, so zooming far out or close in keeps the creature visible.
void fitClipPlanes(Camera& camera, const Framing& framing);

// A camera for `preset`, with fitClipPlanes. Front, side and three-quarter: as close as it can be
// with the corners of framing.bounds (body plus hair) inside the view with a 10% margin, centred.
// Face: the sphere around the face inside the view. Follow looks at the root segment from behind
// and above, fitting the bounding sphere about the root.
Camera presetCamera(const Framing& framing, CameraPreset preset, int width, int height,
                    float fovYDegrees = kDefaultFovYDegrees);

// An orbit camera: azimuth about +Z from +X, elevation above the XY plane (degrees), distance
// (metres) from the target. Used by the viewer's mouse and keyboard controls.
struct Orbit {
  Eigen::Vector3f target = Eigen::Vector3f::Zero();
  float azimuthDegrees = 0.0f;
  float elevationDegrees = 15.0f;
  float distanceMeters = 1.0f;
};
// The orbit's camera (clip planes left at their defaults: apply fitClipPlanes for a creature).
Camera orbitCamera(const Orbit& orbit, int width, int height,
                   float fovYDegrees = kDefaultFovYDegrees);
// The orbit that reproduces a camera's eye and target.
Orbit orbitOf(const Camera& camera);

// A camera file (JSON): one camera, or keys along the frames, linearly interpolated and held
// beyond the first and last key:
//   {"eye": [x, y, z], "target": [x, y, z], "up": [0, 0, 1], "fovYDegrees": 35}
//   {"keys": [{"frame": 0, "eye": ..., "target": ...}, {"frame": 48, ...}], "track": true}
// Metres, world frame (Z up). "track": move with the creature (see CameraRig::track).
struct CameraKey {
  int frame = 0;
  Eigen::Vector3f eye{1.0f, 0.0f, 0.0f};
  Eigen::Vector3f target = Eigen::Vector3f::Zero();
  Eigen::Vector3f up = Eigen::Vector3f::UnitZ();
  float fovYDegrees = kDefaultFovYDegrees;
};
struct CameraPath {
  std::vector<CameraKey> keys;  // frames strictly increasing
  bool track = false;
};
// Loads a camera file; InputError naming the file and field on anything malformed.
CameraPath loadCameraFile(const std::string& path);
// Parses a camera file's text (`source` names it in messages).
CameraPath parseCameraFile(const std::string& text, const std::string& source);
// The path's camera at `frame` (clip planes left at their defaults).
Camera cameraOnPath(const CameraPath& path, int frame, int width, int height);

// How each frame of a sequence is seen: a preset framed on the creature at the sequence's first
// pose (clip time 0), or a camera file; optionally moving with the creature.
struct CameraRig {
  CameraPreset preset = CameraPreset::ThreeQuarter;
  std::optional<CameraPath> path;  // a camera file instead of the preset
  // Move the camera with the creature: by the horizontal displacement of its root segment since
  // the first pose (always on for the follow preset and for paths that ask for it).
  bool track = false;
  float fovYDegrees = kDefaultFovYDegrees;  // of the preset, (1, 179)
};

// The camera of sequence frame `frame` for a width x height image: the rig's camera, moved with the
// creature when tracking, with clip planes around `current` (fitClipPlanes). `first` is the framing
// of the first pose, `current` this frame's.
Camera rigCamera(const CameraRig& rig, const Framing& first, const Framing& current, int frame,
                 int width, int height);

}  // namespace pelage::scene
