// Binding a skin built from shapes to the creature's segments (skin/build_from_shapes.h,
// bindToSegments): each vertex's closest segments by the shapes' distance fields, blended across
// joints so that linear blend skinning bends without folding.
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <queue>
#include <utility>
#include <vector>

#include "pelage/skin/build_from_shapes.h"
#include "pelage/util/parallel.h"
#include "shape_sdf.h"

namespace pelage::skin {

using Vec3 = Eigen::Vector3f;
using anatomy::Creature;
using detail::smoothstep01;

namespace {

// Length of segment s's bone: the distance from its joint to its farthest child joint, or else to
// the farthest end of its own shapes.
float boneLength(const Creature& c, const std::vector<Eigen::Affine3f>& world, int s) {
  const Vec3 joint = world[static_cast<std::size_t>(s)].translation();
  float len = 0.0f;
  bool hasChild = false;
  for (int k = 0; k < c.body.size(); ++k)
    if (c.body.segments[static_cast<std::size_t>(k)].parent == s) {
      len = std::max(len, (world[static_cast<std::size_t>(k)].translation() - joint).norm());
      hasChild = true;
    }
  if (!hasChild)
    for (const auto& sh : c.shapes)
      if (sh.segment == s)
        len = std::max(
            len, ((sh.kind == anatomy::Shape::Kind::Capsule ? sh.to : sh.center) - joint).norm());
  return len;
}

// Half-width of the weight blend at each segment's joint with its parent (metres): twice the local
// flesh radius (how deep the joint lies inside its two segments' shapes), at least the creature's
// blend radius. A bend of up to ~90 degrees then keeps the inner side of a joint from folding over:
// linear blend skinning inverts the inner surface at radius r when the weight changes faster than
// 1 / (2 r) per metre at 90 degrees, and the smoothstep below changes at most 1.5 / (2 width).
std::vector<float> jointWidths(const Creature& c) {
  const std::vector<Eigen::Affine3f> world = anatomy::restWorldTransforms(c.body);
  std::vector<float> width(static_cast<std::size_t>(c.body.size()), c.blendRadiusMeters);
  for (int s = 0; s < c.body.size(); ++s) {
    const int parent = c.body.segments[static_cast<std::size_t>(s)].parent;
    const Vec3 joint = world[static_cast<std::size_t>(s)].translation();
    float depth = 0.0f;
    for (const auto& sh : c.shapes)
      if (sh.segment == s || sh.segment == parent)
        depth = std::max(depth, -detail::shapeDistance(sh, joint));
    // ... but at most half the length of the shorter of the two bones, so that a short segment
    // (the monkey's spine) is not blended away entirely.
    const float limit =
        std::min(boneLength(c, world, s), parent >= 0 ? boneLength(c, world, parent) : 1e9f);
    width[static_cast<std::size_t>(s)] =
        std::max(c.blendRadiusMeters, std::min(2.0f * depth, 0.5f * limit));
  }
  return width;
}

// Blend width between two segments: their joint's if one is the other's parent, else the smaller.
float pairWidth(const Creature& c, const std::vector<float>& width, int a, int b) {
  if (c.body.segments[static_cast<std::size_t>(a)].parent == b)
    return width[static_cast<std::size_t>(a)];
  if (c.body.segments[static_cast<std::size_t>(b)].parent == a)
    return width[static_cast<std::size_t>(b)];
  return std::min(width[static_cast<std::size_t>(a)], width[static_cast<std::size_t>(b)]);
}

}  // namespace

void bindToSegments(const Creature& c, SkinMesh& skin) {
  const int nSeg = c.body.size();
  TriMesh& mesh = skin.mesh;
  const int nV = static_cast<int>(mesh.n_vertices());
  Binding* bind = mesh.property(skin.binding).data_vector().data();
  OpenMesh::Vec3f* dirs = mesh.property(skin.segmentDirection).data_vector().data();
  const TriMesh::Point* pts = mesh.points();

  // 1. Sec. 3.4: each vertex belongs to its closest segment (by distance to the segments' shapes).
  std::vector<std::int32_t> label(static_cast<std::size_t>(nV));
  parallelForChunks(nV, 1024, [&](std::int64_t b, std::int64_t e) {
    std::vector<float> dist(static_cast<std::size_t>(nSeg));
    for (std::int64_t v = b; v < e; ++v) {
      const Vec3 p(pts[v][0], pts[v][1], pts[v][2]);
      std::fill(dist.begin(), dist.end(), std::numeric_limits<float>::infinity());
      for (const auto& sh : c.shapes)
        dist[static_cast<std::size_t>(sh.segment)] =
            std::min(dist[static_cast<std::size_t>(sh.segment)], detail::shapeDistance(sh, p));
      int closest = 0;
      for (int s = 1; s < nSeg; ++s)
        if (dist[static_cast<std::size_t>(s)] < dist[static_cast<std::size_t>(closest)])
          closest = s;
      label[static_cast<std::size_t>(v)] = closest;
    }
  });

  // 2. Distance along the surface from each vertex to the boundaries of its segment's region with
  // the neighbouring regions (multi-source Dijkstra over mesh edges, staying inside the region),
  // keeping the nearest boundary per neighbouring segment.
  const std::vector<float> width = jointWidths(c);
  const float maxWidth = *std::max_element(width.begin(), width.end());
  constexpr int kSlots = 3;
  struct Near {
    std::int32_t segment[kSlots] = {-1, -1, -1};
    float dist[kSlots] = {0, 0, 0};
  };
  std::vector<Near> near(static_cast<std::size_t>(nV));
  struct Item {
    float dist;
    std::int32_t vertex, segment;
    bool operator>(const Item& o) const {
      return dist > o.dist ||
             (dist == o.dist && (vertex > o.vertex || (vertex == o.vertex && segment > o.segment)));
    }
  };
  std::priority_queue<Item, std::vector<Item>, std::greater<Item>> queue;
  auto edgeLength = [&](int a, int b) { return (pts[a] - pts[b]).norm(); };
  for (auto eh : mesh.edges()) {
    const auto h = mesh.halfedge_handle(eh, 0);
    const int a = mesh.from_vertex_handle(h).idx(), b = mesh.to_vertex_handle(h).idx();
    if (label[static_cast<std::size_t>(a)] == label[static_cast<std::size_t>(b)]) continue;
    const float half = 0.5f * edgeLength(a, b);
    queue.push({half, a, label[static_cast<std::size_t>(b)]});
    queue.push({half, b, label[static_cast<std::size_t>(a)]});
  }
  while (!queue.empty()) {
    const Item it = queue.top();
    queue.pop();
    Near& n = near[static_cast<std::size_t>(it.vertex)];
    int slot = -1;
    bool known = false;
    for (int k = 0; k < kSlots; ++k) {
      if (n.segment[k] == it.segment) known = true;
      if (n.segment[k] < 0 && slot < 0) slot = k;
    }
    if (known || slot < 0) continue;  // already settled for this segment, or slots full
    n.segment[slot] = it.segment;
    n.dist[slot] = it.dist;
    for (auto w : mesh.vv_range(TriMesh::VertexHandle(it.vertex))) {
      if (label[static_cast<std::size_t>(w.idx())] != label[static_cast<std::size_t>(it.vertex)])
        continue;
      const float d = it.dist + edgeLength(it.vertex, w.idx());
      if (d < maxWidth) queue.push({d, w.idx(), it.segment});
    }
  }

  // 3. Weights: a neighbouring segment at boundary distance d gets (1 - smoothstep(d / width)) / 2,
  // which is 1/2 on the boundary from both sides, so weights are continuous across it.
  parallelFor(nV, 1024, [&](std::int64_t v) {
    const int own = label[static_cast<std::size_t>(v)];
    const Near& n = near[static_cast<std::size_t>(v)];
    std::array<std::pair<float, int>, kSlots + 1> cand;
    int nc = 1;
    float others = 0.0f;
    for (int k = 0; k < kSlots; ++k) {
      if (n.segment[k] < 0) continue;
      const float w =
          0.5f * (1.0f - smoothstep01(n.dist[k] / pairWidth(c, width, own, n.segment[k])));
      if (w <= 1e-4f) continue;
      cand[static_cast<std::size_t>(nc++)] = {w, n.segment[k]};
      others += w;
    }
    cand[0] = {std::max(1.0f - others, 0.0f), own};
    Binding bd;
    float sum = 0.0f;
    for (int k = 0; k < nc; ++k) sum += cand[static_cast<std::size_t>(k)].first;
    Vec3 dir = Vec3::Zero();
    for (int k = 0; k < 4; ++k) {
      const bool used = k < nc;
      bd.segment[static_cast<std::size_t>(k)] =
          used ? cand[static_cast<std::size_t>(k)].second : own;
      bd.weight[static_cast<std::size_t>(k)] =
          used ? cand[static_cast<std::size_t>(k)].first / sum : 0.0f;
      if (used)
        dir += bd.weight[static_cast<std::size_t>(k)] *
               c.body.segments[static_cast<std::size_t>(bd.segment[static_cast<std::size_t>(k)])]
                   .direction;
    }
    bind[v] = bd;
    // The segment direction of the vertex's segment, blended like the weights near joints so
    // that fur direction has no seam at a joint.
    const float len = dir.norm();
    const Vec3 d = len > 1e-6f ? Vec3(dir / len) : Vec3::Zero();
    dirs[v] = OpenMesh::Vec3f(d.x(), d.y(), d.z());
  });
}

}  // namespace pelage::skin
