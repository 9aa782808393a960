// Shared helpers for the fur tests: tiny hand-made skins, the default monkey (built once per test
// binary, without the scene module), and running one frame of fur.
#pragma once

#include <gtest/gtest.h>
#include <Eigen/Core>

#include <array>
#include <cmath>
#include <cstring>
#include <string>
#include <vector>

#include "pelage/anatomy/creature.h"
#include "pelage/anatomy/pose.h"
#include "pelage/fur/generate.h"
#include "pelage/fur/preset.h"
#include "pelage/fur/roots.h"
#include "pelage/models/builtin.h"
#include "pelage/skin/build_from_shapes.h"
#include "pelage/skin/deform.h"
#include "pelage/skin/skin_mesh.h"
#include "pelage/util/parallel.h"

namespace pelage::test {

// A skin from explicit vertices and triangles, every vertex with fur length `length` (m) and
// segment direction `direction` (bind pose).
inline skin::SkinMesh makeSkin(const std::vector<Eigen::Vector3f>& vertices,
                               const std::vector<std::array<int, 3>>& triangles, float length,
                               const Eigen::Vector3f& direction = Eigen::Vector3f::Zero()) {
  skin::SkinMesh s;
  std::vector<skin::TriMesh::VertexHandle> vh;
  for (const Eigen::Vector3f& v : vertices)
    vh.push_back(s.mesh.add_vertex(skin::TriMesh::Point(v.x(), v.y(), v.z())));
  for (const auto& t : triangles)
    s.mesh.add_face(vh[static_cast<std::size_t>(t[0])], vh[static_cast<std::size_t>(t[1])],
                    vh[static_cast<std::size_t>(t[2])]);
  skin::addSkinProperties(s);
  for (auto v : s.mesh.vertices()) {
    s.mesh.property(s.furLength, v) = length;
    s.mesh.property(s.segmentDirection, v) =
        OpenMesh::Vec3f(direction.x(), direction.y(), direction.z());
  }
  skin::finalizeSkin(s);
  return s;
}

// An n x n grid of squares (2 triangles each) of side `cell` in the plane z = 0, normal +Z.
inline skin::SkinMesh makeGrid(int n, float cell, float length,
                               const Eigen::Vector3f& direction = Eigen::Vector3f::Zero()) {
  std::vector<Eigen::Vector3f> v;
  std::vector<std::array<int, 3>> t;
  for (int j = 0; j <= n; ++j)
    for (int i = 0; i <= n; ++i)
      v.emplace_back(static_cast<float>(i) * cell, static_cast<float>(j) * cell, 0.0f);
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      const int a = j * (n + 1) + i, b = a + 1, c = a + n + 1, d = c + 1;
      t.push_back({a, b, d});
      t.push_back({a, d, c});
    }
  return makeSkin(v, t, length, direction);
}

// The default monkey's body and skin (~130k triangles), built once.
struct MonkeySkin {
  anatomy::Body body;
  skin::SkinMesh skin;
  skin::DeformedSkin rest;
};
inline const MonkeySkin& monkeySkin() {
  static const MonkeySkin m = [] {
    const anatomy::Creature c =
        anatomy::parseCreature(std::string(*models::builtinFile("monkey.json")), "built-in monkey");
    MonkeySkin out{c.body, skin::buildSkin(c, {c.defaultTriangles}), {}};
    anatomy::BodyState state;
    anatomy::forwardKinematics(out.body, anatomy::restPose(out.body), state);
    skin::deformSkin(out.skin, state, out.rest);
    return out;
  }();
  return m;
}

// FurParams with one coat (no undercoat) of `style`, `hairs` hairs, no randomness, culling off.
inline fur::FurParams simpleParams(fur::HairStyle style, double hairs) {
  fur::FurParams p;
  p.setHairCount(hairs);
  p.undercoatShare = 0.0f;
  p.culling.enabled = false;
  for (auto& c : p.coats) {
    c.style = style;
    c.stiffness = 0.2f;
  }
  return p;
}

// One frame of fur.
inline fur::FurFrame furFrame(const skin::SkinMesh& s, const fur::FurRoots& roots,
                              const fur::FurParams& p, const skin::DeformedSkin& d,
                              const fur::FurView& view = {}) {
  fur::FurWorkspace ws;
  fur::FurFrame frame;
  fur::generateFur(s, roots, p, d, view, ws, frame);
  return frame;
}

// A skin in its rest pose with grown roots: the common setup of the small-skin tests.
struct RestFur {
  skin::DeformedSkin rest;
  fur::FurRoots roots;
};
inline RestFur restFur(const skin::SkinMesh& s, const fur::FurParams& p) {
  RestFur f;
  skin::restSkin(s, f.rest);
  f.roots = fur::growRoots(s, p);
  return f;
}

// Whether two frames hold bit-identical hairs.
inline bool sameHairs(const fur::FurFrame& a, const fur::FurFrame& b) {
  for (int c = 0; c < fur::kCoatCount; ++c) {
    const auto& x = a.coats[static_cast<std::size_t>(c)];
    const auto& y = b.coats[static_cast<std::size_t>(c)];
    if (x.drawn != y.drawn || x.layout.pointsPerHair() != y.layout.pointsPerHair()) return false;
    const std::size_t floats = static_cast<std::size_t>(x.drawn * x.layout.pointsPerHair() * 3);
    if (floats == 0) continue;  // empty buffers may have no storage at all
    if (std::memcmp(x.positions.data(), y.positions.data(), floats * sizeof(float)) != 0)
      return false;
    if (std::memcmp(x.normals.data(), y.normals.data(), floats * sizeof(float)) != 0) return false;
    if (std::memcmp(x.hairIds.data(), y.hairIds.data(),
                    static_cast<std::size_t>(x.drawn) * sizeof(std::int32_t)) != 0)
      return false;
  }
  return true;
}

inline Eigen::Vector3f point(const fur::HairBuffers& b, std::int64_t hair, int k) {
  return Eigen::Map<const Eigen::Vector3f>(b.positions.data() +
                                           (hair * b.layout.pointsPerHair() + k) * 3);
}
// A hair's strand point k (a tube's ring centre, the mean of its M points in order).
inline Eigen::Vector3f strandPoint(const fur::HairBuffers& b, std::int64_t h, int k) {
  const int M = b.layout.ringSides;
  Eigen::Vector3f sum = Eigen::Vector3f::Zero();
  for (int m = 0; m < M; ++m) sum += point(b, h, k * M + m);
  return M == 1 ? sum : Eigen::Vector3f(sum / static_cast<float>(M));
}
inline Eigen::Vector3f normal(const fur::HairBuffers& b, std::int64_t hair, int k) {
  return Eigen::Map<const Eigen::Vector3f>(b.normals.data() +
                                           (hair * b.layout.pointsPerHair() + k) * 3);
}

// A UV sphere of radius r (rings x segments), fur lengths from 2 mm at the bottom to 12 mm at the
// top, segment direction +X except on the southern cap (none there).
inline skin::SkinMesh makeSphere(float r, int rings, int segments) {
  std::vector<Eigen::Vector3f> v{{0, 0, -r}};
  std::vector<std::array<int, 3>> t;
  for (int i = 1; i < rings; ++i)
    for (int j = 0; j < segments; ++j) {
      const double th = M_PI * i / rings, ph = 2 * M_PI * j / segments;
      v.emplace_back(static_cast<float>(r * std::sin(th) * std::cos(ph)),
                     static_cast<float>(r * std::sin(th) * std::sin(ph)),
                     static_cast<float>(-r * std::cos(th)));
    }
  v.emplace_back(0, 0, r);
  const int top = static_cast<int>(v.size()) - 1;
  const auto ring = [&](int i, int j) { return 1 + (i - 1) * segments + (j % segments); };
  for (int j = 0; j < segments; ++j) {
    t.push_back({0, ring(1, j + 1), ring(1, j)});
    for (int i = 1; i + 1 < rings; ++i) {
      t.push_back({ring(i, j), ring(i, j + 1), ring(i + 1, j + 1)});
      t.push_back({ring(i, j), ring(i + 1, j + 1), ring(i + 1, j)});
    }
    t.push_back({top, ring(rings - 1, j), ring(rings - 1, j + 1)});
  }
  skin::SkinMesh s = makeSkin(v, t, 0.01f, Eigen::Vector3f(1, 0, 0));
  for (auto vh : s.mesh.vertices()) {
    const float z = s.mesh.point(vh)[2] / r;
    s.mesh.property(s.furLength, vh) = 0.002f + 0.005f * (z + 1.0f);
    if (z < -0.7f) s.mesh.property(s.segmentDirection, vh) = OpenMesh::Vec3f(0, 0, 0);
  }
  return s;
}

// For every style (fig9 parameters, the undercoat curly, a length region around `regionCenter`):
// the kernel output equals the scalar reference bit for bit; it is the same for 1, 2 and 4
// threads, with and without culling, and on every SIMD path the CPU has; every float is finite and
// every normal unit.
inline void checkStylesAgainstReference(const skin::SkinMesh& s, const skin::DeformedSkin& d,
                                        double hairs, const Eigen::Vector3f& regionCenter,
                                        const fur::Groom& groom = {}) {
  using namespace fur;

  for (HairStyle style :
       {HairStyle::Line, HairStyle::Polyline, HairStyle::Curve, HairStyle::Tube}) {
    SCOPED_TRACE(styleName(style));
    FurParams p = loadFurPreset("fig9");
    p.setHairCount(hairs);
    for (auto& c : p.coats) c.style = style;
    p.coats[kUndercoat].curlRadius = 0.2f;  // the helix too (curve and tube)
    p.coats[kUndercoat].curlTurns = 2.5f;
    p.lengthRegion.shape = RegionShape::Sphere;  // and a length region around the head
    p.lengthRegion.center = regionCenter;
    p.lengthRegion.radius = 0.08f;
    p.lengthRegion.scale = 2.0f;
    const FurRoots r = growRoots(s, p, groom);
    const FurFrame f = furFrame(s, r, p, d);
    std::vector<float> pos, nrm;
    for (int c = 0; c < kCoatCount; ++c) {
      const HairBuffers& hb = f.coats[static_cast<std::size_t>(c)];
      ASSERT_EQ(hb.drawn, r.coats[static_cast<std::size_t>(c)].size());
      ASSERT_EQ(hb.layout.pointsPerHair(), pointsPerHair(p.coats[static_cast<std::size_t>(c)]));
      const std::size_t n = static_cast<std::size_t>(hb.layout.pointsPerHair()) * 3;
      for (std::size_t k = 0; k < static_cast<std::size_t>(hb.drawn) * n; ++k) {
        ASSERT_TRUE(std::isfinite(hb.positions.data()[k]));
        ASSERT_TRUE(std::isfinite(hb.normals.data()[k]));
      }
      for (std::int64_t h = 0; h < hb.drawn; ++h) {
        for (int k = 0; k < hb.layout.pointsPerHair(); ++k)
          ASSERT_NEAR(normal(hb, h, k).norm(), 1.0f, 2e-5f);
        if (h % 5 != 0) continue;
        ASSERT_EQ(hb.hairIds[static_cast<std::size_t>(h)], h);
        referenceHair(s, r, p, d, c, h, pos, nrm);
        ASSERT_EQ(0, std::memcmp(pos.data(), hb.positions.data() + static_cast<std::size_t>(h) * n,
                                 n * sizeof(float)))
            << "coat " << c << " hair " << h;
        ASSERT_EQ(0, std::memcmp(nrm.data(), hb.normals.data() + static_cast<std::size_t>(h) * n,
                                 n * sizeof(float)))
            << "coat " << c << " hair " << h;
      }
    }
    FurView culled;
    culled.culling = true;
    culled.referenceDistance = 0.1f;
    culled.viewDistance = 0.25f;
    for (const FurView& view : {FurView{}, culled}) {
      setThreadCount(1);
      const FurFrame one = furFrame(s, r, p, d, view);
      for (int threads : {2, 4}) {
        setThreadCount(threads);
        EXPECT_TRUE(sameHairs(one, furFrame(s, r, p, d, view))) << threads << " threads";
      }
      for (const std::string& target : kernelTargets()) {  // each SIMD target, forced
        ASSERT_TRUE(setKernelTarget(target));
        EXPECT_TRUE(sameHairs(one, furFrame(s, r, p, d, view))) << target << " kernel";
      }
      setKernelTarget("auto");
      setThreadCount(0);
    }
  }
}

}  // namespace pelage::test
