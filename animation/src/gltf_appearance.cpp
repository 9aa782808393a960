// importGltf's appearance stage (gltf_stages.h): per-corner UVs, vertex colours, the materials'
// base colours and their textures.
#include <algorithm>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>

#include "gltf_stages.h"
#include "pelage/util/color.h"
#include "pelage/util/image.h"
#include "pelage/util/log.h"

namespace pelage::animation::detail {
namespace {

// Decoded image bytes allowed for one creature's textures, all images together.
constexpr std::size_t kMaxTextureBytes = std::size_t{1} << 30;

skin::Wrap wrapMode(int gl) {
  if (gl == TINYGLTF_TEXTURE_WRAP_CLAMP_TO_EDGE) return skin::Wrap::ClampToEdge;
  if (gl == TINYGLTF_TEXTURE_WRAP_MIRRORED_REPEAT) return skin::Wrap::MirroredRepeat;
  return skin::Wrap::Repeat;
}

// The encoded bytes of image `i`: its bufferView (validated by loadModelFile), its data URI's bytes
// (kept by the reader), or the file its uri names beside the .gltf. `bytes` may point into `file`.
// InputError naming the image when it has none or its file cannot be used.
void imageBytes(const ImportContext& ctx, int i, const std::string& what,
                std::vector<std::uint8_t>& file, const std::uint8_t*& bytes, std::size_t& size) {
  const tinygltf::Image& img = ctx.model.images[static_cast<std::size_t>(i)];
  if (img.bufferView >= 0) {
    if (static_cast<std::size_t>(img.bufferView) >= ctx.model.bufferViews.size())
      inputError(what, ": bufferView ", img.bufferView, " does not exist");
    const tinygltf::BufferView& bv =
        ctx.model.bufferViews[static_cast<std::size_t>(img.bufferView)];
    bytes = ctx.model.buffers[static_cast<std::size_t>(bv.buffer)].data.data() + bv.byteOffset;
    size = bv.byteLength;
    return;
  }
  if (!img.image.empty()) {
    bytes = img.image.data();
    size = img.image.size();
    return;
  }
  if (img.uri.empty()) inputError(what, ": has neither a bufferView nor a uri");
  // An external file, relative to the .gltf and inside its folder (no scheme, no absolute path,
  // no '..'): a downloaded model cannot make pelage read files elsewhere.
  const std::string uri = img.uri;
  const std::filesystem::path rel(uri);
  bool inside = uri.find("://") == std::string::npos && !rel.is_absolute();
  for (const auto& part : rel) inside = inside && part != "..";
  if (!inside)
    inputError(what, ": uri '", uri,
               "' is not a relative path inside the model's folder (only those are read)");
  std::string decoded;  // %XX escapes (glTF uris are URI-encoded)
  for (std::size_t k = 0; k < uri.size(); ++k) {
    if (uri[k] == '%' && k + 2 < uri.size() &&
        std::isxdigit(static_cast<unsigned char>(uri[k + 1])) &&
        std::isxdigit(static_cast<unsigned char>(uri[k + 2]))) {
      decoded += static_cast<char>(std::stoi(uri.substr(k + 1, 2), nullptr, 16));
      k += 2;
    } else {
      decoded += uri[k];
    }
  }
  const std::filesystem::path full = std::filesystem::path(ctx.path).parent_path() / decoded;
  std::error_code ec;
  if (!std::filesystem::is_regular_file(full, ec))
    inputError(what, ": its file ", full.string(), " does not exist");
  const std::uintmax_t n = std::filesystem::file_size(full, ec);
  if (ec || n > (std::size_t{512} << 20))
    inputError(what, ": its file ", full.string(), " is unreadable or over 512 MiB");
  file.resize(static_cast<std::size_t>(n));
  std::ifstream in(full, std::ios::binary);
  in.read(reinterpret_cast<char*>(file.data()), static_cast<std::streamsize>(file.size()));
  if (static_cast<std::size_t>(in.gcount()) != file.size())
    inputError(what, ": cannot read its file ", full.string());
  bytes = file.data();
  size = file.size();
}

}  // namespace

void readAppearance(const ImportContext& ctx, const Primitives& prims,
                    const std::vector<std::size_t>& kept,
                    const std::vector<std::int32_t>& faceVertices, const Weld& wd,
                    const std::vector<std::int32_t>& source, skin::SkinMesh& sk) {
  const tinygltf::Model& model = ctx.model;
  const std::size_t nF = kept.size();
  if (prims.hasUv) {
    std::vector<Eigen::Vector2f> inputUv(3 * nF);
    for (std::size_t f = 0; f < nF; ++f)
      for (std::size_t j = 0; j < 3; ++j)
        inputUv[3 * f + j] =
            prims.vertices[static_cast<std::size_t>(prims.triangles[kept[f]][j])].uv;
    skin::setCornerUvs(sk, faceVertices, inputUv);
  }
  if (prims.hasColor) {
    sk.vertexColor.resize(source.size());
    for (std::size_t v = 0; v < source.size(); ++v)
      sk.vertexColor[v] =
          prims.vertices[static_cast<std::size_t>(wd.welded[static_cast<std::size_t>(source[v])])]
              .color;
  }
  bool anyMaterial = false, anyDefault = false;
  for (std::size_t f = 0; f < nF; ++f) {
    const bool has = prims.triangleMaterial[kept[f]] >= 0;
    anyMaterial = anyMaterial || has;
    anyDefault = anyDefault || !has;
  }
  if (!anyMaterial) return;
  // Every glTF material in file order, then (if some triangle has none) a default of the skin's
  // colour.
  std::map<int, int> textureOf;  // glTF texture -> skin texture (-1: unusable)
  std::size_t textureBytes = 0;
  for (std::size_t m = 0; m < model.materials.size(); ++m) {
    const tinygltf::Material& gm = model.materials[m];
    skin::SkinMaterial sm;
    sm.name = gm.name.empty() ? str("material", m) : gm.name;
    const std::vector<double>& f = gm.pbrMetallicRoughness.baseColorFactor;
    if (f.size() == 4 && finite(f))
      for (int k = 0; k < 4; ++k)
        sm.baseColor[k] = static_cast<float>(std::clamp(f[static_cast<std::size_t>(k)], 0.0, 1.0));
    const tinygltf::TextureInfo& ti = gm.pbrMetallicRoughness.baseColorTexture;
    const std::string what =
        str(ctx.path, ": material ", m, " '", sm.name, "' base colour texture");
    if (ti.index >= 0) {
      if (ti.texCoord != 0) {
        warn(str(what, " uses TEXCOORD_", ti.texCoord, "; only TEXCOORD_0 is read: not textured"));
      } else if (!prims.hasUv) {
        warn(str(what, ": the mesh has no TEXCOORD_0, so it cannot be textured"));
      } else if (auto it = textureOf.find(ti.index); it != textureOf.end()) {
        sm.texture = it->second;
      } else {
        int made = -1;
        try {
          if (static_cast<std::size_t>(ti.index) >= model.textures.size())
            inputError(what, ": texture ", ti.index, " does not exist (", model.textures.size(),
                       " textures)");
          const tinygltf::Texture& gt = model.textures[static_cast<std::size_t>(ti.index)];
          if (gt.source < 0 || static_cast<std::size_t>(gt.source) >= model.images.size())
            inputError(what, ": texture ", ti.index, " has no image (source ", gt.source, ")");
          const tinygltf::Image& gi = model.images[static_cast<std::size_t>(gt.source)];
          const std::string imageName =
              str(ctx.path, ": image ", gt.source, gi.name.empty() ? "" : " '" + gi.name + "'");
          std::vector<std::uint8_t> file;
          const std::uint8_t* bytes = nullptr;
          std::size_t size = 0;
          imageBytes(ctx, gt.source, imageName, file, bytes, size);
          ImageLimits limits;
          limits.maxBytes = std::min(limits.maxBytes, kMaxTextureBytes - textureBytes);
          skin::Texture tex =
              skin::makeTexture(decodeImage(bytes, size, imageName, limits), imageName, true);
          if (gt.sampler >= 0 && static_cast<std::size_t>(gt.sampler) < model.samplers.size()) {
            const tinygltf::Sampler& s = model.samplers[static_cast<std::size_t>(gt.sampler)];
            tex.wrapS = wrapMode(s.wrapS);
            tex.wrapT = wrapMode(s.wrapT);
            tex.filter = s.magFilter == TINYGLTF_TEXTURE_FILTER_NEAREST ? skin::Filter::Nearest
                                                                        : skin::Filter::Linear;
          }
          if (!ti.extensions.empty())
            warn(
                str(what, ": texture extensions (", ti.extensions.begin()->first, ") are ignored"));
          textureBytes += tex.bytes();
          made = static_cast<int>(sk.textures.size());
          sk.textures.push_back(std::move(tex));
        } catch (const InputError& e) {
          warn(str(e.what(), "; the material is drawn with its base colour only"));
        }
        textureOf[ti.index] = made;
        sm.texture = made;
      }
    }
    sk.materials.push_back(std::move(sm));
  }
  const int fallback = static_cast<int>(sk.materials.size());
  if (anyDefault) {
    skin::SkinMaterial d;
    d.name = "(no material)";
    const Eigen::Vector3f linear = srgbToLinear(sk.color);
    d.baseColor = Eigen::Vector4f(linear.x(), linear.y(), linear.z(), 1.0f);
    sk.materials.push_back(d);
  }
  sk.triangleMaterial.resize(nF);
  for (std::size_t f = 0; f < nF; ++f) {
    const int m = prims.triangleMaterial[kept[f]];
    sk.triangleMaterial[f] = m >= 0 ? m : fallback;
  }
  skin::checkAppearance(sk);
}

}  // namespace pelage::animation::detail
