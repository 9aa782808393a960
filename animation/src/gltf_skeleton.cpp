// importGltf's skeleton stages (gltf_stages.h): the node tree, the scene's meshes, the segments
// and their bind transforms, the body.
#include <algorithm>
#include <cmath>
#include <set>

#include "gltf_stages.h"
#include "pelage/util/log.h"

namespace pelage::animation::detail {
namespace {

// A node's local transform as TRS. A matrix must be affine and decomposable: M = T R S with
// S = the column norms (one negated when det < 0) and R orthonormal (glTF forbids shear).
anatomy::Transform nodeTransform(const ImportContext& ctx, int index) {
  const tinygltf::Node& n = ctx.model.nodes[static_cast<std::size_t>(index)];
  anatomy::Transform t;
  if (!n.matrix.empty()) {
    if (n.matrix.size() != 16)
      ctx.fail("node ", index, " matrix has ", n.matrix.size(), " numbers (16 expected)");
    if (!finite(n.matrix)) ctx.fail("node ", index, " matrix has a NaN or infinite value");
    Eigen::Matrix4d m;
    for (int c = 0; c < 4; ++c)
      for (int r = 0; r < 4; ++r) m(r, c) = n.matrix[static_cast<std::size_t>(c * 4 + r)];
    if ((m.row(3) - Eigen::RowVector4d(0, 0, 0, 1)).cwiseAbs().maxCoeff() > 1e-6)
      ctx.fail("node ", index, " matrix is not affine (last row must be 0 0 0 1)");
    Eigen::Matrix3d a = m.topLeftCorner<3, 3>();
    Vec3d s(a.col(0).norm(), a.col(1).norm(), a.col(2).norm());
    if (s.minCoeff() < 1e-12) ctx.fail("node ", index, " matrix is degenerate (a zero scale)");
    if (a.determinant() < 0.0) s.x() = -s.x();
    const Eigen::Matrix3d r = a * s.cwiseInverse().asDiagonal();
    if ((r.transpose() * r - Eigen::Matrix3d::Identity()).cwiseAbs().maxCoeff() > 1e-3)
      ctx.fail("node ", index,
               " matrix has shear, which glTF does not allow (it must be translation * rotation * "
               "scale)");
    t.rotation = Eigen::Quaternionf(Eigen::Quaterniond(r).normalized().cast<float>());
    t.translation = m.topRightCorner<3, 1>().cast<float>();
    t.scale = s.cast<float>();
    return t;
  }
  if (!n.translation.empty()) {
    if (n.translation.size() != 3 || !finite(n.translation))
      ctx.fail("node ", index, " translation must be 3 finite numbers");
    t.translation =
        Eigen::Vector3f(static_cast<float>(n.translation[0]), static_cast<float>(n.translation[1]),
                        static_cast<float>(n.translation[2]));
  }
  if (!n.rotation.empty()) {
    if (n.rotation.size() != 4 || !finite(n.rotation))
      ctx.fail("node ", index, " rotation must be 4 finite numbers");
    Eigen::Quaterniond q(n.rotation[3], n.rotation[0], n.rotation[1], n.rotation[2]);
    if (q.norm() < 1e-6) ctx.fail("node ", index, " rotation is a zero quaternion");
    t.rotation = Eigen::Quaternionf(q.normalized().cast<float>());
  }
  if (!n.scale.empty()) {
    if (n.scale.size() != 3 || !finite(n.scale))
      ctx.fail("node ", index, " scale must be 3 finite numbers");
    t.scale = Eigen::Vector3f(static_cast<float>(n.scale[0]), static_cast<float>(n.scale[1]),
                              static_cast<float>(n.scale[2]));
  }
  return t;
}

Affine3d toAffine(const anatomy::Transform& t) {
  return t.matrix().cast<double>();
}

}  // namespace

Tree buildTree(const ImportContext& ctx) {
  const tinygltf::Model& m = ctx.model;
  const int N = static_cast<int>(m.nodes.size());
  Tree t;
  t.parent.assign(static_cast<std::size_t>(N), -1);
  for (int i = 0; i < N; ++i)
    for (int c : m.nodes[static_cast<std::size_t>(i)].children) {
      if (c < 0 || c >= N)
        ctx.fail("node ", i, " has child ", c, ", which does not exist (", N, " nodes)");
      if (c == i) ctx.fail("node ", i, " is its own child");
      if (t.parent[static_cast<std::size_t>(c)] >= 0)
        ctx.fail("node ", c, " has two parents (nodes ", t.parent[static_cast<std::size_t>(c)],
                 " and ", i, "); glTF nodes form a tree");
      t.parent[static_cast<std::size_t>(c)] = i;
    }
  for (int i = 0; i < N; ++i) {  // every walk up must reach a root within N steps
    int steps = 0;
    for (int p = i; p >= 0; p = t.parent[static_cast<std::size_t>(p)])
      if (++steps > N) ctx.fail("the node hierarchy has a cycle through node ", i);
  }
  std::vector<int> roots;
  if (!m.scenes.empty()) {
    const int s = m.defaultScene >= 0 ? m.defaultScene : 0;
    if (s >= static_cast<int>(m.scenes.size())) ctx.fail("default scene ", s, " does not exist");
    for (int r : m.scenes[static_cast<std::size_t>(s)].nodes) {
      if (r < 0 || r >= N) ctx.fail("scene ", s, " lists node ", r, ", which does not exist");
      if (t.parent[static_cast<std::size_t>(r)] >= 0)
        ctx.fail("scene ", s, " root node ", r, " has a parent");
      roots.push_back(r);
    }
  } else {
    for (int i = 0; i < N; ++i)
      if (t.parent[static_cast<std::size_t>(i)] < 0) roots.push_back(i);
  }
  std::vector<bool> seen(static_cast<std::size_t>(N), false);
  for (int r : roots) {
    std::vector<int> stack{r};
    while (!stack.empty()) {
      const int n = stack.back();
      stack.pop_back();
      if (seen[static_cast<std::size_t>(n)]) continue;
      seen[static_cast<std::size_t>(n)] = true;
      t.sceneNodes.push_back(n);
      const auto& ch = m.nodes[static_cast<std::size_t>(n)].children;
      for (auto it = ch.rbegin(); it != ch.rend(); ++it) stack.push_back(*it);
    }
  }
  return t;
}

SceneMeshes sceneMeshes(const ImportContext& ctx, const Tree& tree) {
  const tinygltf::Model& model = ctx.model;
  SceneMeshes out;
  std::vector<Instance>& instances = out.instances;
  for (int n : tree.sceneNodes) {
    const tinygltf::Node& node = model.nodes[static_cast<std::size_t>(n)];
    if (node.mesh < 0) continue;
    if (node.mesh >= static_cast<int>(model.meshes.size()))
      ctx.fail("node ", n, " uses mesh ", node.mesh, ", which does not exist (",
               model.meshes.size(), " meshes)");
    if (node.skin >= static_cast<int>(model.skins.size()))
      ctx.fail("node ", n, " uses skin ", node.skin, ", which does not exist (", model.skins.size(),
               " skins)");
    instances.push_back({n, node.mesh, node.skin});
  }
  if (instances.empty()) ctx.fail("the scene has no mesh");

  for (const Instance& in : instances)
    if (in.skin >= 0) out.usedSkins.insert(in.skin);
  return out;
}

Skeleton buildSkeleton(const ImportContext& ctx, const Tree& tree, const SceneMeshes& meshes) {
  const tinygltf::Model& model = ctx.model;
  const int N = static_cast<int>(model.nodes.size());
  const std::vector<Instance>& instances = meshes.instances;
  Skeleton skel;
  // Segments: joints of the used skins, rigid mesh nodes, and all their ancestors.
  std::vector<bool> isSegment(static_cast<std::size_t>(N), false);
  auto markUp = [&](int n) {
    for (; n >= 0 && !isSegment[static_cast<std::size_t>(n)];
         n = tree.parent[static_cast<std::size_t>(n)])
      isSegment[static_cast<std::size_t>(n)] = true;
  };
  for (const Instance& in : instances) {
    if (in.skin < 0) {
      markUp(in.node);
      continue;
    }
    const tinygltf::Skin& s = model.skins[static_cast<std::size_t>(in.skin)];
    if (s.joints.empty()) ctx.fail("skin ", in.skin, " has no joints");
    for (int j : s.joints) {
      if (j < 0 || j >= N)
        ctx.fail("skin ", in.skin, " lists joint node ", j, ", which does not exist (", N,
                 " nodes)");
      markUp(j);
    }
  }
  // Parents-first order: a depth-first walk from the roots of the whole node forest.
  std::vector<int>& order = skel.order;
  std::vector<int>& segmentOf = skel.segmentOf;
  segmentOf.assign(static_cast<std::size_t>(N), -1);
  {
    std::vector<int> stack;
    for (int i = N - 1; i >= 0; --i)
      if (tree.parent[static_cast<std::size_t>(i)] < 0 && isSegment[static_cast<std::size_t>(i)])
        stack.push_back(i);
    while (!stack.empty()) {
      const int n = stack.back();
      stack.pop_back();
      segmentOf[static_cast<std::size_t>(n)] = static_cast<int>(order.size());
      order.push_back(n);
      const auto& ch = model.nodes[static_cast<std::size_t>(n)].children;
      for (auto it = ch.rbegin(); it != ch.rend(); ++it)
        if (isSegment[static_cast<std::size_t>(*it)]) stack.push_back(*it);
    }
  }
  const int nS = static_cast<int>(order.size());

  // Rest transforms (file units) and bind transforms.
  std::vector<anatomy::Transform>& rest = skel.rest;
  rest.resize(static_cast<std::size_t>(nS));
  for (int s = 0; s < nS; ++s)
    rest[static_cast<std::size_t>(s)] = nodeTransform(ctx, order[static_cast<std::size_t>(s)]);
  std::vector<bool> isJoint(static_cast<std::size_t>(nS), false);
  std::vector<Affine3d>& bind = skel.bind;
  bind.assign(static_cast<std::size_t>(nS), Affine3d::Identity());
  // Global rest transforms of all nodes (parents first).
  std::vector<Affine3d>& global = skel.global;
  global.assign(static_cast<std::size_t>(N), Affine3d::Identity());
  {
    std::vector<int> stack;
    for (int i = N - 1; i >= 0; --i)
      if (tree.parent[static_cast<std::size_t>(i)] < 0) stack.push_back(i);
    while (!stack.empty()) {
      const int n = stack.back();
      stack.pop_back();
      const int p = tree.parent[static_cast<std::size_t>(n)];
      const Affine3d local = toAffine(nodeTransform(ctx, n));
      global[static_cast<std::size_t>(n)] =
          p < 0 ? local : global[static_cast<std::size_t>(p)] * local;
      for (int c : model.nodes[static_cast<std::size_t>(n)].children) stack.push_back(c);
    }
  }
  // Joints: bind transform = (mesh node's global rest transform) * IBM^-1, so that bind space is
  // where the rest pose puts the mesh (skinning W IBM M^-1 (M p) = W IBM p, the glTF result).
  std::map<int, SkinJoints>& skinJoints = skel.skinJoints;
  std::map<int, std::vector<Eigen::Matrix4d>> ibms;
  for (int si : meshes.usedSkins) {
    const tinygltf::Skin& sk = model.skins[static_cast<std::size_t>(si)];
    std::vector<Eigen::Matrix4d>& list = ibms[si];
    std::vector<float> ibm;
    if (sk.inverseBindMatrices >= 0) {
      ibm = ctx.acc.floats(sk.inverseBindMatrices, TINYGLTF_TYPE_MAT4, false,
                           str("skin ", si, " inverseBindMatrices"));
      if (ibm.size() / 16 < sk.joints.size())
        ctx.fail("skin ", si, " has ", sk.joints.size(), " joints but ", ibm.size() / 16,
                 " inverse bind matrices");
    }
    SkinJoints& sj = skinJoints[si];
    for (std::size_t j = 0; j < sk.joints.size(); ++j) {
      Eigen::Matrix4d mm = Eigen::Matrix4d::Identity();
      if (!ibm.empty()) {
        for (int c = 0; c < 4; ++c)
          for (int r = 0; r < 4; ++r)
            mm(r, c) = static_cast<double>(ibm[j * 16 + static_cast<std::size_t>(c * 4 + r)]);
        if ((mm.row(3) - Eigen::RowVector4d(0, 0, 0, 1)).cwiseAbs().maxCoeff() > 1e-4)
          ctx.fail("skin ", si, " inverse bind matrix ", j, " is not affine");
        if (!(std::abs(mm.topLeftCorner<3, 3>().determinant()) > 1e-12))
          ctx.fail("skin ", si, " inverse bind matrix ", j, " is singular");
        mm.row(3) << 0, 0, 0, 1;
      }
      list.push_back(mm);
      sj.segment.push_back(segmentOf[static_cast<std::size_t>(sk.joints[j])]);
    }
  }
  for (const Instance& in : instances) {
    if (in.skin < 0) continue;
    const Affine3d& M = global[static_cast<std::size_t>(in.node)];
    const std::vector<Eigen::Matrix4d>& list = ibms.at(in.skin);
    const std::vector<int>& segs = skinJoints.at(in.skin).segment;
    for (std::size_t j = 0; j < segs.size(); ++j) {
      Affine3d ib;
      ib.matrix() = list[j];
      const Affine3d b = M * ib.inverse();
      const std::size_t seg = static_cast<std::size_t>(segs[j]);
      if (isJoint[seg] && !bind[seg].matrix().isApprox(b.matrix(), 1e-4))
        ctx.fail("joint node ", model.skins[static_cast<std::size_t>(in.skin)].joints[j],
                 " has two different bind transforms (shared by skins or mesh nodes that disagree; "
                 "not supported)");
      isJoint[seg] = true;
      bind[seg] = b;
    }
  }
  for (int s = 0; s < nS; ++s) {
    if (isJoint[static_cast<std::size_t>(s)]) continue;
    const int p = tree.parent[static_cast<std::size_t>(order[static_cast<std::size_t>(s)])];
    const Affine3d local = toAffine(rest[static_cast<std::size_t>(s)]);
    bind[static_cast<std::size_t>(s)] =
        p < 0 ? local
              : bind[static_cast<std::size_t>(segmentOf[static_cast<std::size_t>(p)])] * local;
  }

  return skel;
}

// 5. The body: roots take the change of basis and scale; every bind transform is K * bind.
void buildBody(const ImportContext& ctx, const Tree& tree, const Skeleton& sk, const Units& units,
               anatomy::Body& body) {
  const tinygltf::Model& model = ctx.model;
  const int nS = sk.size();
  const double s = static_cast<double>(units.scale);
  const Eigen::Matrix3d& C = units.C;
  std::set<std::string> names;
  for (int si = 0; si < nS; ++si) {
    const int n = sk.order[static_cast<std::size_t>(si)];
    anatomy::Segment seg;
    seg.name = model.nodes[static_cast<std::size_t>(n)].name.empty()
                   ? str("node", n)
                   : model.nodes[static_cast<std::size_t>(n)].name;
    if (!names.insert(seg.name).second) {
      seg.name = str(seg.name, "#", n);
      names.insert(seg.name);
    }
    const int p = tree.parent[static_cast<std::size_t>(n)];
    seg.parent = p < 0 ? -1 : sk.segmentOf[static_cast<std::size_t>(p)];
    seg.rest = sk.rest[static_cast<std::size_t>(si)];
    if (seg.parent < 0) {
      seg.rest.rotation = (units.qC.cast<float>() * seg.rest.rotation).normalized();
      seg.rest.translation = (s * C * seg.rest.translation.cast<double>()).cast<float>();
      seg.rest.scale *= units.scale;
    }
    body.segments.push_back(seg);
    const Affine3d b = units.K * sk.bind[static_cast<std::size_t>(si)];
    body.inverseBind.push_back(Eigen::Affine3f(b.inverse().cast<float>()));
  }
  anatomy::checkBody(body);
}

}  // namespace pelage::animation::detail
