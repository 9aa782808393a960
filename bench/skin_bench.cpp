// Skin deformation + normals of the default monkey (130k triangles). Target: <= 1.5 ms per frame
// on 2 threads of a CI-class machine.
#include <benchmark/benchmark.h>

#include <cmath>

#include "pelage/anatomy/pose.h"
#include "pelage/scene/model.h"
#include "pelage/skin/deform.h"
#include "pelage/util/parallel.h"

namespace {

const pelage::scene::Model& monkey() {
  static const pelage::scene::Model m = pelage::scene::loadModel("monkey");
  return m;
}

void BM_DeformMonkey(benchmark::State& st) {
  pelage::setThreadCount(static_cast<int>(st.range(0)));
  const auto& m = monkey();
  pelage::anatomy::Pose pose = pelage::anatomy::restPose(m.body);
  pelage::anatomy::BodyState state;
  pelage::skin::DeformedSkin out;
  float t = 0.0f;
  for (auto _ : st) {
    t += 0.01f;
    for (std::size_t s = 1; s < pose.local.size(); ++s)
      pose.local[s].rotation = Eigen::Quaternionf(
          Eigen::AngleAxisf(0.3f * std::sin(t + static_cast<float>(s)), Eigen::Vector3f::UnitY()));
    pelage::anatomy::forwardKinematics(m.body, pose, state);
    pelage::skin::deformSkin(m.skin, state, out);
    benchmark::DoNotOptimize(out.normals.data());
    benchmark::ClobberMemory();
  }
  st.counters["triangles"] = m.skin.numTriangles();
  st.counters["vertices"] = m.skin.numVertices();
  st.counters["threads"] = static_cast<double>(st.range(0));
}
BENCHMARK(BM_DeformMonkey)->Arg(1)->Arg(2)->Unit(benchmark::kMillisecond)->UseRealTime();

}  // namespace

BENCHMARK_MAIN();
