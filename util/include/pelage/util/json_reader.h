// Reading user JSON files (creatures, fur presets, clips) with errors that name the file, the
// field path (e.g. `segments[3].joint`), the expected type and the accepted range.
#pragma once

#include <Eigen/Core>
#include <nlohmann/json.hpp>

#include <initializer_list>
#include <optional>
#include <string>
#include <vector>

namespace pelage {

// A read-only view of one JSON value inside a file, remembering where it is.
class JsonReader {
 public:
  JsonReader(const nlohmann::json& value, std::string file, std::string path = "");

  // Parses a file; throws InputError naming the file (missing, unreadable, syntax error + line).
  static nlohmann::json parseFile(const std::string& file);
  // Parses text that came from `name` (a file name or "built-in ..."), same errors.
  static nlohmann::json parseText(const std::string& text, const std::string& name);

  const nlohmann::json& json() const { return *value_; }
  const std::string& file() const { return file_; }
  const std::string& path() const { return path_; }
  // "file: path" for messages.
  std::string where() const;
  [[noreturn]] void fail(const std::string& message) const;

  bool isObject() const { return value_->is_object(); }
  bool isArray() const { return value_->is_array(); }
  bool has(const std::string& key) const;
  // Required member (fails if absent or if this is not an object).
  JsonReader at(const std::string& key) const;
  std::optional<JsonReader> find(const std::string& key) const;
  // Array access (fails if this is not an array).
  std::size_t size() const;
  JsonReader at(std::size_t index) const;
  // Object keys in file order (fails if this is not an object).
  std::vector<std::string> keys() const;
  // Fails naming the first member not in `allowed` (catches typos such as "stifness").
  void rejectUnknown(std::initializer_list<const char*> allowed) const;

  // Typed values of this node.
  double asNumber(double lo, double hi) const;
  std::int64_t asInteger(std::int64_t lo, std::int64_t hi) const;
  std::string asString() const;
  bool asBool() const;
  Eigen::Vector3f asVec3() const;
  Eigen::Vector4f asVec4() const;

  // Typed members; the variants with `fallback` return it when the member is absent.
  double number(const std::string& key, double lo, double hi) const;
  double number(const std::string& key, double fallback, double lo, double hi) const;
  std::int64_t integer(const std::string& key, std::int64_t lo, std::int64_t hi) const;
  std::int64_t integer(const std::string& key, std::int64_t fallback, std::int64_t lo,
                       std::int64_t hi) const;
  std::string string(const std::string& key) const;
  std::string string(const std::string& key, const std::string& fallback) const;
  bool boolean(const std::string& key, bool fallback) const;
  Eigen::Vector3f vec3(const std::string& key) const;
  Eigen::Vector3f vec3(const std::string& key, const Eigen::Vector3f& fallback) const;

 private:
  const nlohmann::json* value_;
  std::string file_;
  std::string path_;
};

// The number to write for `f` in a JSON file: the double of f's shortest decimal (0.06f -> 0.06,
// not 0.05999999865889549), so that a written file reads as it was typed and is about half as long;
// read back and converted to float it is f again. Not-finite values pass through.
double shortestDecimal(float f);

}  // namespace pelage
