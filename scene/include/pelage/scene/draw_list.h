// The GL-free draw list between the scene and the renderer (as MuJoCo's mjv_updateScene builds an
// mjvScene that mjr_render draws): camera, light, the skin and one fur item per coat, background.
// The interactive viewer and headless export fill one and hand it to the same renderer, so what a
// frame contains is unit-testable without OpenGL.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "pelage/fur/fur_params.h"
#include "pelage/fur/roots.h"
#include "pelage/scene/model.h"
#include "pelage/skin/deform.h"

namespace pelage::scene {

struct FrameState;
struct Fur;

// A perspective camera. World frame: metres, Z up. The viewport is the image size in pixels.
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

// The camera presets of the viewer and of `pelage render` (issue 6).
enum class CameraPreset { Front, Side, ThreeQuarter, Face, Follow };
// "front", "side", "three-quarter", "face", "follow".
std::string_view cameraPresetName(CameraPreset preset);
// Parses a preset name; throws InputError listing the accepted names.
CameraPreset parseCameraPreset(std::string_view name);

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

// A camera for `preset`. Front, side and three-quarter: as close as it can be with the corners of
// framing.bounds (body plus hair) inside the view with a 10% margin, centred. Face: the sphere
// around the face inside the view. Follow looks at the root segment from behind and above, fitting
// the bounding sphere about the root.
Camera presetCamera(const Framing& framing, CameraPreset preset, int width, int height,
                    float fovYDegrees = 35.0f);

// An orbit camera: azimuth about +Z from +X, elevation above the XY plane (degrees), distance
// (metres) from the target. Used by the viewer's mouse and keyboard controls.
struct Orbit {
  Eigen::Vector3f target = Eigen::Vector3f::Zero();
  float azimuthDegrees = 0.0f;
  float elevationDegrees = 15.0f;
  float distanceMeters = 1.0f;
};
Camera orbitCamera(const Orbit& orbit, int width, int height, float fovYDegrees = 35.0f);
// The orbit that reproduces a camera's eye and target.
Orbit orbitOf(const Camera& camera);

// One directional key light plus ambient.
struct Light {
  Eigen::Vector3f direction{0.5f, 0.35f, 0.8f};  // towards the light (normalised by the renderer)
  Eigen::Vector3f color{1.0f, 1.0f, 1.0f};
  Eigen::Vector3f ambient{0.35f, 0.35f, 0.35f};  // ambient light intensity (the paper's GL model)
  bool shadows = false;                          // shadow map: fur and skin shadow each other
  int shadowMapSize = 2048;
};

// The light direction for azimuth/elevation in degrees (the viewer's light controls).
Eigen::Vector3f lightDirection(float azimuthDegrees, float elevationDegrees);

// Phong material (the paper's per-coat ambient/diffuse/specular/shininess, sec. 3.2 and Figure 2).
struct Material {
  Eigen::Vector3f ambient{0.2f, 0.2f, 0.2f};
  Eigen::Vector3f diffuse{0.6f, 0.6f, 0.6f};
  Eigen::Vector3f specular{0.1f, 0.1f, 0.1f};
  float shininess = 16.0f;
};

// How hairs are lit: the paper's Phong model with each style's shading normals, or Kajiya-Kay
// with the hair tangent.
enum class HairShading { Paper, KajiyaKay };
std::string_view hairShadingName(HairShading shading);
HairShading parseHairShading(std::string_view name);

// How 1-D hairs are drawn: 1-pixel lines, or ribbons tapering from `rootWidthPixels` to 0.
enum class HairWidth { Lines, Ribbons };

// The skin: the deformed arrays of the frame (non-owning; they live in the FrameState).
struct SkinDrawItem {
  Material material;
  const std::vector<Eigen::Vector3f>* positions = nullptr;  // nV
  const std::vector<Eigen::Vector3f>* normals = nullptr;    // nV
  const std::vector<std::int32_t>* triangles = nullptr;     // nT x 3
  int vertices = 0;
  int triangleCount = 0;
};

// Where a coat's hairs come from: buffers the CPU fur model wrote this frame, or the GPU, which
// regenerates them from the roots and the deformed skin (viewer/gpu_fur.h).
enum class HairSource { Cpu, Gpu };

// One coat (paper sec. 3.1). Non-owning pointers into the scene; valid for the frame.
struct FurDrawItem {
  int coat = 0;  // fur::kOvercoat or fur::kUndercoat
  fur::HairStyle style = fur::HairStyle::Polyline;
  Material material;
  int strandPoints = 2;         // points along one hair
  int strandStride = 1;         // points per ring for tubes (the nurbs-surface style), else 1
  bool triangles = false;       // tubes are drawn as triangles, other styles as line strips
  std::int64_t rootCount = 0;   // hairs grown on the skin
  std::int64_t drawnHairs = 0;  // after distance culling (sec. 3.3)
  float cullFactor = 1.0f;      // c of sec. 3.3 (1 = all hairs)
  HairSource source = HairSource::Cpu;
  // CPU source: drawnHairs * P * 3 floats each (P = strandPoints * strandStride).
  const float* positions = nullptr;
  const float* normals = nullptr;

  int pointsPerHair() const { return strandPoints * strandStride; }
};

// What the GPU hair source reads (shared by the coats; not owned).
struct GpuFurInputs {
  const fur::FurParams* params = nullptr;
  const fur::FurRoots* roots = nullptr;
  std::uint64_t rootsGeneration = 0;
  const skin::SkinMesh* skin = nullptr;
  const skin::DeformedSkin* deformed = nullptr;
};

// Everything one frame draws.
struct DrawList {
  Camera camera;
  Light light;
  Eigen::Vector3f background{0.80f, 0.82f, 0.86f};
  SkinDrawItem skin;
  std::vector<FurDrawItem> fur;  // 0, 1 or 2 coats
  HairShading hairShading = HairShading::Paper;
  HairWidth hairWidth = HairWidth::Lines;
  float ribbonRootWidthPixels = 2.5f;
  Eigen::AlignedBox3f bounds;  // everything drawn (fits the shadow map)
  GpuFurInputs gpuFur;         // for fur items with HairSource::Gpu

  std::int64_t drawnHairs() const;
};

// Options of buildDrawList.
struct DrawOptions {
  HairSource hairSource = HairSource::Cpu;
  HairShading hairShading = HairShading::Paper;
  HairWidth hairWidth = HairWidth::Lines;
  bool drawFur = true;
  bool drawSkin = true;
};

// Fills `list` for one evaluated frame: skin item from the frame's deformed skin and the model's
// skin colour, one fur item per coat with roots (when `fur` is given and options.drawFur), camera
// and light as given. With the CPU source the fur items point at the frame's hair buffers
// (evaluateFur must have run with cpuHairs); with the GPU source, at the roots and parameters in
// `fur`.
void buildDrawList(const Model& model, const FrameState& frame, const Fur* fur,
                   const Camera& camera, const Light& light, const DrawOptions& options,
                   DrawList& list);

// The scene material of a fur coat's material.
Material furMaterial(const fur::Material& material);

// The material of the skin for a diffuse colour (small ambient and specular terms).
Material skinMaterial(const Eigen::Vector3f& color);

}  // namespace pelage::scene
