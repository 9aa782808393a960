#include "gltf_reader.h"

#include <cmath>
#include <cstring>
#include <exception>
#include <filesystem>
#include <fstream>

#include "pelage/util/error.h"
#include "pelage/util/log.h"

namespace pelage::animation::gltf {
namespace {

constexpr std::uint64_t kMaxFileBytes = 1ull << 30;  // 1 GiB
constexpr std::size_t kMaxElements = std::size_t{1} << 26;
constexpr std::size_t kMaxZeroBytes = std::size_t{1} << 26;  // an accessor without data (all zeros)
constexpr std::uint32_t kGlbMagic = 0x46546C67;              // "glTF"
constexpr std::uint32_t kChunkJson = 0x4E4F534A;             // "JSON"
constexpr std::uint32_t kChunkBin = 0x004E4942;              // "BIN\0"

std::uint32_t le32(const std::vector<unsigned char>& b, std::size_t at) {
  return static_cast<std::uint32_t>(b[at]) | static_cast<std::uint32_t>(b[at + 1]) << 8 |
         static_cast<std::uint32_t>(b[at + 2]) << 16 | static_cast<std::uint32_t>(b[at + 3]) << 24;
}

std::string trim(std::string s) {
  while (!s.empty() && (s.back() == '\n' || s.back() == '\r' || s.back() == ' ')) s.pop_back();
  for (char& c : s)
    if (c == '\n') c = ';';
  return s;
}

// The GLB container (glTF 2.0 spec, "Binary glTF Layout"): 12-byte header (magic, version 2, total
// length), then chunks of (length, type, data) with 4-byte aligned lengths; the first is JSON, an
// optional second is BIN, unknown chunks after them are allowed.
void validateGlb(const std::string& path, const std::vector<unsigned char>& b) {
  const std::size_t size = b.size();
  if (size < 12)
    inputError(path, ": truncated GLB file (", size, " bytes; the header alone takes 12)");
  const std::uint32_t version = le32(b, 4), length = le32(b, 8);
  if (version != 2)
    inputError(path, ": GLB version ", version,
               " is not supported (glTF 2.0 files have version 2)");
  if (length > size)
    inputError(path, ": truncated GLB file (the header declares ", length, " bytes, the file has ",
               size, ")");
  if (length < size)
    inputError(path, ": GLB header declares ", length, " bytes but the file has ", size,
               " (trailing data)");
  std::size_t at = 12;
  int chunk = 0;
  while (at < size) {
    if (size - at < 8) inputError(path, ": truncated GLB chunk header at byte ", at);
    const std::uint32_t len = le32(b, at), type = le32(b, at + 4);
    if (len > size - at - 8)
      inputError(path, ": GLB chunk ", chunk, " (", len, " bytes at byte ", at,
                 ") runs past the end of the file (", size, " bytes): truncated or corrupt");
    if (len % 4 != 0)
      inputError(path, ": GLB chunk ", chunk, " length ", len, " is not a multiple of 4");
    if (chunk == 0 && type != kChunkJson) inputError(path, ": the first GLB chunk must be JSON");
    if (chunk == 0 && len == 0) inputError(path, ": the GLB JSON chunk is empty");
    if (chunk == 1 && type != kChunkBin) inputError(path, ": the second GLB chunk must be BIN");
    if (chunk > 0 && type == kChunkJson)
      inputError(path, ": the GLB file has more than one JSON chunk");
    at += 8 + len;
    ++chunk;
  }
  if (chunk == 0) inputError(path, ": the GLB file has no JSON chunk");
}

// tinygltf decodes no image: an image in a data URI keeps its encoded bytes in Image::image (its
// width stays -1), one in a bufferView is read later from the validated view (gltf_import.cpp
// decodes both with util/image.h), and an external one keeps its uri.
bool keepEncodedImage(tinygltf::Image* image, const int, std::string*, std::string*, int, int,
                      const unsigned char* bytes, int size, void*) {
  if (image->bufferView >= 0 || bytes == nullptr || size <= 0) return true;
  image->image.assign(bytes, bytes + size);
  image->width = image->height = -1;
  return true;
}

bool supportedRequiredExtension(const std::string& e) {
  // These change only appearance (materials, textures, lights), which pelage does not read.
  return e.rfind("KHR_materials_", 0) == 0 || e == "KHR_texture_transform" ||
         e == "KHR_texture_basisu" || e == "EXT_texture_webp" || e == "KHR_lights_punctual";
}

const char* typeName(int type) {
  switch (type) {
    case TINYGLTF_TYPE_SCALAR:
      return "SCALAR";
    case TINYGLTF_TYPE_VEC2:
      return "VEC2";
    case TINYGLTF_TYPE_VEC3:
      return "VEC3";
    case TINYGLTF_TYPE_VEC4:
      return "VEC4";
    case TINYGLTF_TYPE_MAT2:
      return "MAT2";
    case TINYGLTF_TYPE_MAT3:
      return "MAT3";
    case TINYGLTF_TYPE_MAT4:
      return "MAT4";
    default:
      return "an unknown type";
  }
}

const char* componentName(int c) {
  switch (c) {
    case TINYGLTF_COMPONENT_TYPE_BYTE:
      return "BYTE";
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE:
      return "UNSIGNED_BYTE";
    case TINYGLTF_COMPONENT_TYPE_SHORT:
      return "SHORT";
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT:
      return "UNSIGNED_SHORT";
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT:
      return "UNSIGNED_INT";
    case TINYGLTF_COMPONENT_TYPE_FLOAT:
      return "FLOAT";
    default:
      return "an unknown component type";
  }
}

std::size_t componentSize(int c) {
  switch (c) {
    case TINYGLTF_COMPONENT_TYPE_BYTE:
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE:
      return 1;
    case TINYGLTF_COMPONENT_TYPE_SHORT:
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT:
      return 2;
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT:
    case TINYGLTF_COMPONENT_TYPE_FLOAT:
      return 4;
    default:
      return 0;
  }
}

std::size_t componentsOf(int type) {
  switch (type) {
    case TINYGLTF_TYPE_SCALAR:
      return 1;
    case TINYGLTF_TYPE_VEC2:
      return 2;
    case TINYGLTF_TYPE_VEC3:
      return 3;
    case TINYGLTF_TYPE_VEC4:
      return 4;
    case TINYGLTF_TYPE_MAT2:
      return 4;
    case TINYGLTF_TYPE_MAT3:
      return 9;
    case TINYGLTF_TYPE_MAT4:
      return 16;
    default:
      return 0;
  }
}

}  // namespace

tinygltf::Model loadModelFile(const std::string& path) {
  namespace fs = std::filesystem;
  std::error_code ec;
  requireExistingFile(path);
  if (!fs::is_regular_file(path, ec)) inputError(path, ": not a regular file");
  const std::uintmax_t bytes = fs::file_size(path, ec);
  if (ec) inputError(path, ": cannot read the file size (", ec.message(), ")");
  if (bytes == 0) inputError(path, ": file is empty");
  if (bytes > kMaxFileBytes)
    inputError(path, ": file is ", bytes, " bytes; the limit is ", kMaxFileBytes);
  std::vector<unsigned char> data(static_cast<std::size_t>(bytes));
  {
    std::ifstream in(path, std::ios::binary);
    if (!in) inputError(path, ": cannot open file (unreadable)");
    in.read(reinterpret_cast<char*>(data.data()), static_cast<std::streamsize>(data.size()));
    if (static_cast<std::size_t>(in.gcount()) != data.size()) inputError(path, ": read error");
  }
  const bool glb = data.size() >= 4 && le32(data, 0) == kGlbMagic;
  const std::string ext = fs::path(path).extension().string();
  if (!glb && (ext == ".glb" || ext == ".GLB"))
    inputError(path, ": not a GLB file (wrong magic: a .glb file starts with the 4 bytes 'glTF')");
  if (glb) validateGlb(path, data);

  tinygltf::TinyGLTF loader;
  loader.SetImageLoader(&keepEncodedImage, nullptr);
  tinygltf::Model model;
  std::string err, warnings;
  const std::string baseDir = fs::path(path).parent_path().string();
  bool ok = false;
  try {
    ok = glb ? loader.LoadBinaryFromMemory(&model, &err, &warnings, data.data(),
                                           static_cast<unsigned int>(data.size()), baseDir)
             : loader.LoadASCIIFromString(&model, &err, &warnings,
                                          reinterpret_cast<const char*>(data.data()),
                                          static_cast<unsigned int>(data.size()), baseDir);
  } catch (const std::exception& e) {
    inputError(path, ": malformed glTF (", shortenLongWords(e.what()), ")");
  }
  if (!ok || !err.empty())
    inputError(
        path, ": malformed glTF: ",
        err.empty() ? std::string("tinygltf could not parse it") : shortenLongWords(trim(err)));
  if (!warnings.empty()) warn(path + ": " + shortenLongWords(trim(warnings)));

  for (const std::string& e : model.extensionsRequired)
    if (!supportedRequiredExtension(e))
      inputError(
          path, ": requires the glTF extension ", e,
          ", which pelage does not support (no extension that changes geometry or animation is)");
  for (std::size_t i = 0; i < model.bufferViews.size(); ++i) {
    const tinygltf::BufferView& bv = model.bufferViews[i];
    if (bv.buffer < 0 || static_cast<std::size_t>(bv.buffer) >= model.buffers.size())
      inputError(path, ": bufferView ", i, " refers to buffer ", bv.buffer,
                 ", which does not exist (", model.buffers.size(), " buffers)");
    const std::size_t bufSize = model.buffers[static_cast<std::size_t>(bv.buffer)].data.size();
    if (bv.byteOffset > bufSize || bv.byteLength > bufSize - bv.byteOffset)
      inputError(path, ": bufferView ", i, " (offset ", bv.byteOffset, ", length ", bv.byteLength,
                 ") is out of range of buffer ", bv.buffer, " (", bufSize, " bytes)");
    if (bv.byteStride != 0 && (bv.byteStride < 4 || bv.byteStride > 252 || bv.byteStride % 4 != 0))
      inputError(path, ": bufferView ", i, " byteStride ", bv.byteStride,
                 " is invalid (accepted: 0, or a multiple of 4 in [4, 252])");
  }
  return model;
}

void Accessors::fail(const std::string& what, int index, const std::string& message) const {
  inputError(path_, ": ", what, " (accessor ", index, "): ", message);
}

std::size_t Accessors::count(int index, const std::string& what) const {
  if (index < 0 || static_cast<std::size_t>(index) >= model_.accessors.size())
    fail(what, index, str("no such accessor (the file has ", model_.accessors.size(), ")"));
  return model_.accessors[static_cast<std::size_t>(index)].count;
}

Accessors::View Accessors::view(int index, int type, const std::string& what) const {
  count(index, what);
  const tinygltf::Accessor& a = model_.accessors[static_cast<std::size_t>(index)];
  if (a.sparse.isSparse) fail(what, index, "sparse accessors are not supported");
  if (a.type != type)
    fail(what, index, str("must be ", typeName(type), ", found ", typeName(a.type)));
  View v;
  v.componentType = a.componentType;
  v.componentSize = componentSize(a.componentType);
  if (v.componentSize == 0) fail(what, index, str("invalid componentType ", a.componentType));
  v.components = componentsOf(type);
  v.count = a.count;
  v.normalized = a.normalized;
  if (v.count == 0) fail(what, index, "count is 0 (glTF requires at least one element)");
  if (v.count > kMaxElements)
    fail(what, index, str("count ", v.count, " exceeds the limit ", kMaxElements));
  const std::size_t elem = v.components * v.componentSize;
  if (a.bufferView < 0) {  // glTF: no bufferView means all zeros
    if (v.count * elem > kMaxZeroBytes)
      fail(what, index,
           str("count ", v.count, " without a bufferView would take more than ", kMaxZeroBytes,
               " bytes"));
    v.stride = elem;
    return v;
  }
  if (static_cast<std::size_t>(a.bufferView) >= model_.bufferViews.size())
    fail(what, index,
         str("bufferView ", a.bufferView, " does not exist (", model_.bufferViews.size(),
             " bufferViews)"));
  const tinygltf::BufferView& bv = model_.bufferViews[static_cast<std::size_t>(a.bufferView)];
  v.stride = bv.byteStride != 0 ? bv.byteStride : elem;
  if (v.stride < elem)
    fail(what, index,
         str("byteStride ", v.stride, " is smaller than one element (", elem, " bytes)"));
  // The last byte read must lie inside the bufferView (all in 64 bits: no overflow).
  const std::uint64_t end =
      static_cast<std::uint64_t>(a.byteOffset) +
      static_cast<std::uint64_t>(v.stride) * (static_cast<std::uint64_t>(v.count) - 1) + elem;
  if (end > bv.byteLength)
    fail(what, index,
         str("out of range: ", v.count, " elements from byte ", a.byteOffset, " need ", end,
             " bytes, bufferView ", a.bufferView, " has ", bv.byteLength));
  v.data = model_.buffers[static_cast<std::size_t>(bv.buffer)].data.data() + bv.byteOffset +
           a.byteOffset;
  return v;
}

std::vector<float> Accessors::floats(int index, int type, bool allowNormalized,
                                     const std::string& what) const {
  const View v = view(index, type, what);
  const bool isFloat = v.componentType == TINYGLTF_COMPONENT_TYPE_FLOAT;
  const bool isNormInt =
      v.normalized && v.componentType != TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT && !isFloat;
  if (!isFloat && !(allowNormalized && isNormInt))
    fail(
        what, index,
        str("component type ", componentName(v.componentType), v.normalized ? " (normalized)" : "",
            " is not allowed here (accepted: FLOAT",
            allowNormalized ? ", or normalized BYTE/UNSIGNED_BYTE/SHORT/UNSIGNED_SHORT" : "", ")"));
  std::vector<float> out(v.count * v.components, 0.0f);
  if (!v.data) return out;
  for (std::size_t e = 0; e < v.count; ++e) {
    const unsigned char* p = v.data + e * v.stride;
    for (std::size_t c = 0; c < v.components; ++c, p += v.componentSize) {
      float f = 0.0f;
      switch (v.componentType) {
        case TINYGLTF_COMPONENT_TYPE_FLOAT:
          std::memcpy(&f, p, 4);
          break;
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE:
          f = static_cast<float>(*p) / 255.0f;
          break;
        case TINYGLTF_COMPONENT_TYPE_BYTE:
          f = std::max(static_cast<float>(static_cast<std::int8_t>(*p)) / 127.0f, -1.0f);
          break;
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: {
          std::uint16_t u;
          std::memcpy(&u, p, 2);
          f = static_cast<float>(u) / 65535.0f;
          break;
        }
        case TINYGLTF_COMPONENT_TYPE_SHORT: {
          std::int16_t s;
          std::memcpy(&s, p, 2);
          f = std::max(static_cast<float>(s) / 32767.0f, -1.0f);
          break;
        }
        default:
          break;
      }
      if (!std::isfinite(f)) fail(what, index, str("element ", e, " has a NaN or infinite value"));
      out[e * v.components + c] = f;
    }
  }
  return out;
}

std::vector<std::uint32_t> Accessors::uints(int index, int type,
                                            std::initializer_list<int> componentTypes,
                                            const std::string& what) const {
  const View v = view(index, type, what);
  bool ok = false;
  std::string accepted;
  for (int c : componentTypes) {
    ok = ok || c == v.componentType;
    accepted += std::string(accepted.empty() ? "" : ", ") + componentName(c);
  }
  if (!ok)
    fail(what, index,
         str("component type ", componentName(v.componentType),
             " is not allowed here (accepted: ", accepted, ")"));
  std::vector<std::uint32_t> out(v.count * v.components, 0u);
  if (!v.data) return out;
  for (std::size_t e = 0; e < v.count; ++e) {
    const unsigned char* p = v.data + e * v.stride;
    for (std::size_t c = 0; c < v.components; ++c, p += v.componentSize) {
      std::uint32_t u = 0;
      if (v.componentSize == 1) {
        u = *p;
      } else if (v.componentSize == 2) {
        std::uint16_t s;
        std::memcpy(&s, p, 2);
        u = s;
      } else {
        std::memcpy(&u, p, 4);
      }
      out[e * v.components + c] = u;
    }
  }
  return out;
}

}  // namespace pelage::animation::gltf
