// One animation frame: sample a clip (keyframe search + interpolation into a Pose), forward
// kinematics, then linear blend skinning with vertex normals (skin::deformSkin). Models: the
// default monkey (130k triangles, its baked procedural `walk`) and each shared glTF model with its
// walk or first clip; the largest are CesiumMan (4672 triangles) and the Stag (7438 stored
// vertices, 1875 after welding). Time advances 1/60 s per frame. Arguments: threads. Models that
// are missing are skipped with a message.
#include <benchmark/benchmark.h>

#include <filesystem>
#include <map>
#include <string>

#include "pelage/anatomy/pose.h"
#include "pelage/animation/clip.h"
#include "pelage/scene/model.h"
#include "pelage/skin/deform.h"
#include "pelage/util/parallel.h"

namespace {

using namespace pelage;

const scene::Model* model(const std::string& spec) {
  static std::map<std::string, scene::Model> cache;
  auto it = cache.find(spec);
  if (it == cache.end()) {
    if (spec != "monkey" && !std::filesystem::exists(spec)) return nullptr;
    it = cache.emplace(spec, scene::loadModel(spec)).first;
  }
  return &it->second;
}

// The model's walk (or first) clip, or null after skipping the benchmark when the model is absent.
const animation::Clip* clipOf(benchmark::State& st, const scene::Model* m,
                              const std::string& spec) {
  if (!m || m->clips.empty()) {
    st.SkipWithError(("model not found or without clips: " + spec).c_str());
    return nullptr;
  }
  for (const char* name : {"walk", "Walk"})
    if (const int c = m->findClip(name); c >= 0) return &m->clips[static_cast<std::size_t>(c)];
  return &m->clips.front();
}

// Sample + FK + skinning per frame.
void BM_AnimateFrame(benchmark::State& st, const std::string& spec) {
  setThreadCount(static_cast<int>(st.range(0)));
  const scene::Model* m = model(spec);
  const animation::Clip* found = clipOf(st, m, spec);
  if (!found) return;
  const animation::Clip& clip = *found;
  anatomy::Pose pose;
  anatomy::BodyState state;
  skin::DeformedSkin out;
  animation::sampleClip(clip, m->body, 0.0, pose);  // size the buffers once
  anatomy::forwardKinematics(m->body, pose, state);
  skin::deformSkin(m->skin, state, out);
  double t = 0.0;
  for (auto _ : st) {
    t += 1.0 / 60.0;
    animation::sampleClip(clip, m->body, t, pose);
    anatomy::forwardKinematics(m->body, pose, state);
    skin::deformSkin(m->skin, state, out);
    benchmark::DoNotOptimize(out.normals.data());
    benchmark::ClobberMemory();
  }
  st.counters["triangles"] = m->skin.numTriangles();
  st.counters["vertices"] = m->skin.numVertices();
  st.counters["segments"] = m->body.size();
  st.counters["channels"] = static_cast<double>(clip.channels.size());
  st.counters["threads"] = static_cast<double>(st.range(0));
}

// Clip sampling alone (no skinning), the part this module adds to a frame.
void BM_SampleClip(benchmark::State& st, const std::string& spec) {
  const scene::Model* m = model(spec);
  const animation::Clip* found = clipOf(st, m, spec);
  if (!found) return;
  const animation::Clip& clip = *found;
  anatomy::Pose pose;
  animation::sampleClip(clip, m->body, 0.0, pose);
  double t = 0.0;
  for (auto _ : st) {
    t += 1.0 / 60.0;
    animation::sampleClip(clip, m->body, t, pose);
    benchmark::DoNotOptimize(pose.local.data());
    benchmark::ClobberMemory();
  }
  st.counters["channels"] = static_cast<double>(clip.channels.size());
}

}  // namespace

int main(int argc, char** argv) {
  const std::string dir = PELAGE_SHARED_MODELS_DIR;
  const std::pair<const char*, std::string> models[] = {
      {"monkey", "monkey"},
      {"CesiumMan", dir + "/CesiumMan/CesiumMan.glb"},
      {"Stag", dir + "/Stag/Stag.gltf"},
      {"Fox", dir + "/Fox/Fox.glb"},
      {"Horse", dir + "/Horse/Horse.gltf"},
      {"Wolf", dir + "/Wolf/Wolf.gltf"}};
  for (const auto& [name, spec] : models) {
    benchmark::RegisterBenchmark((std::string("BM_AnimateFrame/") + name).c_str(), BM_AnimateFrame,
                                 spec)
        ->Arg(1)
        ->Arg(2)
        ->Unit(benchmark::kMillisecond)
        ->UseRealTime();
    benchmark::RegisterBenchmark((std::string("BM_SampleClip/") + name).c_str(), BM_SampleClip,
                                 spec)
        ->Unit(benchmark::kMicrosecond);
  }
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
