// The glTF tests' independent minimal reader of a glTF file's JSON and buffers (GLB chunks, base64
// data URIs), to check the importer against. (The shared models' paths: support/files.h.)
#pragma once

#include <gtest/gtest.h>

#include <Eigen/Core>
#include <nlohmann/json.hpp>

#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "support/files.h"

namespace pelage::test {

inline std::vector<unsigned char> readBytes(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return std::vector<unsigned char>((std::istreambuf_iterator<char>(in)),
                                    std::istreambuf_iterator<char>());
}

inline void writeBytes(const std::string& path, const std::vector<unsigned char>& b) {
  std::ofstream out(path, std::ios::binary);
  out.write(reinterpret_cast<const char*>(b.data()), static_cast<std::streamsize>(b.size()));
}

inline std::uint32_t le32(const std::vector<unsigned char>& b, std::size_t at) {
  std::uint32_t v;
  std::memcpy(&v, b.data() + at, 4);
  return v;
}

inline std::vector<unsigned char> base64Decode(const std::string& s) {
  std::vector<unsigned char> out;
  int val = 0, bits = -8;
  for (unsigned char c : s) {
    int d;
    if (c >= 'A' && c <= 'Z')
      d = c - 'A';
    else if (c >= 'a' && c <= 'z')
      d = c - 'a' + 26;
    else if (c >= '0' && c <= '9')
      d = c - '0' + 52;
    else if (c == '+')
      d = 62;
    else if (c == '/')
      d = 63;
    else
      break;
    val = (val << 6) + d;
    bits += 6;
    if (bits >= 0) {
      out.push_back(static_cast<unsigned char>((val >> bits) & 0xFF));
      bits -= 8;
    }
  }
  return out;
}

inline std::string base64Encode(const std::vector<unsigned char>& in) {
  static const char* t = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  int val = 0, bits = -6;
  for (unsigned char c : in) {
    val = (val << 8) + c;
    bits += 8;
    while (bits >= 0) {
      out.push_back(t[(val >> bits) & 0x3F]);
      bits -= 6;
    }
  }
  if (bits > -6) out.push_back(t[((val << 8) >> (bits + 8)) & 0x3F]);
  while (out.size() % 4) out.push_back('=');
  return out;
}

// A glTF file split into its JSON and its buffers, and put back together.
struct GltfParts {
  bool glb = false;
  nlohmann::json json;
  std::vector<std::vector<unsigned char>> buffers;  // decoded; for a GLB, buffer 0 = the BIN chunk

  static GltfParts read(const std::string& path) {
    GltfParts p;
    const std::vector<unsigned char> b = readBytes(path);
    p.glb = b.size() >= 4 && std::memcmp(b.data(), "glTF", 4) == 0;
    std::vector<unsigned char> bin;
    if (p.glb) {
      const std::uint32_t jsonLen = le32(b, 12);
      p.json = nlohmann::json::parse(b.begin() + 20, b.begin() + 20 + jsonLen);
      const std::size_t binAt = 20 + jsonLen;
      if (binAt + 8 <= b.size())
        bin.assign(b.begin() + static_cast<long>(binAt + 8),
                   b.begin() + static_cast<long>(binAt + 8 + le32(b, binAt)));
    } else {
      p.json = nlohmann::json::parse(b.begin(), b.end());
    }
    for (const auto& buf : p.json["buffers"]) {
      if (!buf.contains("uri")) {
        p.buffers.push_back(bin);
        continue;
      }
      const std::string uri = buf["uri"];
      const auto comma = uri.find(',');
      p.buffers.push_back(base64Decode(uri.substr(comma + 1)));
    }
    return p;
  }

  // Writes the file back (re-encoding data-URI buffers from `buffers`).
  void write(const std::string& path) const {
    nlohmann::json j = json;
    for (std::size_t i = 0; i < buffers.size(); ++i)
      if (j["buffers"][i].contains("uri") &&
          j["buffers"][i]["uri"].get<std::string>().rfind("data:", 0) == 0)
        j["buffers"][i]["uri"] = "data:application/octet-stream;base64," + base64Encode(buffers[i]);
    std::string text = j.dump();
    if (!glb) {
      std::ofstream(path, std::ios::binary) << text;
      return;
    }
    while (text.size() % 4) text.push_back(' ');
    std::vector<unsigned char> bin = buffers.empty() ? std::vector<unsigned char>{} : buffers[0];
    while (bin.size() % 4) bin.push_back(0);
    std::vector<unsigned char> out;
    auto put = [&](std::uint32_t v) {
      for (int i = 0; i < 4; ++i) out.push_back(static_cast<unsigned char>(v >> (8 * i)));
    };
    put(0x46546C67);
    put(2);
    put(static_cast<std::uint32_t>(12 + 8 + text.size() + (bin.empty() ? 0 : 8 + bin.size())));
    put(static_cast<std::uint32_t>(text.size()));
    put(0x4E4F534A);
    out.insert(out.end(), text.begin(), text.end());
    if (!bin.empty()) {
      put(static_cast<std::uint32_t>(bin.size()));
      put(0x004E4942);
      out.insert(out.end(), bin.begin(), bin.end());
    }
    writeBytes(path, out);
  }

  // Byte offset of accessor `a`'s first element in its buffer, and that buffer's index.
  std::pair<std::size_t, std::size_t> accessorBytes(int a) const {
    const auto& acc = json["accessors"][static_cast<std::size_t>(a)];
    const auto& bv = json["bufferViews"][acc["bufferView"].get<std::size_t>()];
    return {bv.value("byteOffset", std::size_t{0}) + acc.value("byteOffset", std::size_t{0}),
            bv["buffer"].get<std::size_t>()};
  }

  // FLOAT VEC3 accessor values.
  std::vector<Eigen::Vector3f> vec3(int a) const {
    const auto& acc = json["accessors"][static_cast<std::size_t>(a)];
    const auto& bv = json["bufferViews"][acc["bufferView"].get<std::size_t>()];
    const std::size_t stride = bv.value("byteStride", std::size_t{12});
    const auto [off, buf] = accessorBytes(a);
    std::vector<Eigen::Vector3f> out(acc["count"].get<std::size_t>());
    for (std::size_t i = 0; i < out.size(); ++i)
      std::memcpy(out[i].data(), buffers[buf].data() + off + i * stride, 12);
    return out;
  }
};

}  // namespace pelage::test
