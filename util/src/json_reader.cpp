#include "pelage/util/json_reader.h"

#include <charconv>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "pelage/util/error.h"

namespace pelage {
namespace {
std::string typeName(const nlohmann::json& j) {
  return j.type_name();
}
}  // namespace

double shortestDecimal(float f) {
  if (!std::isfinite(f)) return static_cast<double>(f);
  char text[32];
  const auto r = std::to_chars(text, text + sizeof text - 1, f);
  *r.ptr = '\0';
  return std::strtod(text, nullptr);
}

JsonReader::JsonReader(const nlohmann::json& value, std::string file, std::string path)
    : value_(&value), file_(std::move(file)), path_(std::move(path)) {}

nlohmann::json JsonReader::parseFile(const std::string& file) {
  std::error_code ec;
  if (!std::filesystem::exists(file, ec))
    throw MissingFileError(file + ": cannot open file (missing or unreadable)");
  std::ifstream in(file, std::ios::binary);
  if (!in) inputError(file, ": cannot open file (missing or unreadable)");
  std::ostringstream ss;
  ss << in.rdbuf();
  if (in.bad()) inputError(file, ": read error");
  return parseText(ss.str(), file);
}

nlohmann::json JsonReader::parseText(const std::string& text, const std::string& name) {
  try {
    return nlohmann::json::parse(text);
  } catch (const nlohmann::json::parse_error& e) {
    // Convert the byte offset into a line number for the user.
    std::size_t line = 1;
    for (std::size_t i = 0; i < text.size() && i < e.byte; ++i) line += text[i] == '\n';
    inputError(name, ": malformed JSON near line ", line, " (", e.what(), ")");
  } catch (const nlohmann::json::exception& e) {
    // E.g. a number too large for a double ("number overflow parsing '1e400'").
    inputError(name, ": malformed JSON (", e.what(), ")");
  }
}

std::string JsonReader::where() const {
  return path_.empty() ? file_ + ": top level" : file_ + ": field '" + path_ + "'";
}

void JsonReader::fail(const std::string& message) const {
  inputError(where(), ": ", message);
}

bool JsonReader::has(const std::string& key) const {
  return value_->is_object() && value_->contains(key);
}

JsonReader JsonReader::at(const std::string& key) const {
  if (!value_->is_object()) fail("expected an object, found " + typeName(*value_));
  auto it = value_->find(key);
  const std::string sub = path_.empty() ? key : path_ + "." + key;
  if (it == value_->end()) inputError(file_, ": missing required field '", sub, "'");
  return JsonReader(*it, file_, sub);
}

std::optional<JsonReader> JsonReader::find(const std::string& key) const {
  if (!has(key)) return std::nullopt;
  return at(key);
}

std::size_t JsonReader::size() const {
  if (!value_->is_array()) fail("expected an array, found " + typeName(*value_));
  return value_->size();
}

JsonReader JsonReader::at(std::size_t index) const {
  if (!value_->is_array()) fail("expected an array, found " + typeName(*value_));
  PELAGE_CHECK(index < value_->size(), "index ", index, " size ", value_->size());
  return JsonReader((*value_)[index], file_, path_ + "[" + std::to_string(index) + "]");
}

std::vector<std::string> JsonReader::keys() const {
  if (!value_->is_object()) fail("expected an object, found " + typeName(*value_));
  std::vector<std::string> out;
  for (auto it = value_->begin(); it != value_->end(); ++it) out.push_back(it.key());
  return out;
}

void JsonReader::rejectUnknown(std::initializer_list<const char*> allowed) const {
  for (const std::string& k : keys()) {
    bool ok = false;
    for (const char* a : allowed) ok = ok || k == a;
    if (!ok) {
      std::string list;
      for (const char* a : allowed) list += std::string(list.empty() ? "" : ", ") + a;
      const std::string sub = path_.empty() ? k : path_ + "." + k;
      inputError(file_, ": unknown field '", excerpt(sub), "' (accepted here: ", list, ")");
    }
  }
}

double JsonReader::asNumber(double lo, double hi) const {
  if (!value_->is_number()) fail("expected a number, found " + typeName(*value_));
  const double v = value_->get<double>();
  if (!std::isfinite(v)) fail("expected a finite number");
  if (v < lo || v > hi) fail(str("value ", v, " is out of range [", lo, ", ", hi, "]"));
  return v;
}

std::int64_t JsonReader::asInteger(std::int64_t lo, std::int64_t hi) const {
  if (!value_->is_number_integer() && !value_->is_number_unsigned()) {
    if (value_->is_number_float()) {
      const double d = value_->get<double>();
      if (std::isfinite(d) && d == std::floor(d) && std::abs(d) < 9e15) {
        const auto v = static_cast<std::int64_t>(d);
        if (v < lo || v > hi) fail(str("value ", v, " is out of range [", lo, ", ", hi, "]"));
        return v;
      }
    }
    fail("expected an integer, found " + typeName(*value_));
  }
  if (value_->is_number_unsigned() && value_->get<std::uint64_t>() > static_cast<std::uint64_t>(hi))
    fail(str("value ", value_->get<std::uint64_t>(), " is out of range [", lo, ", ", hi, "]"));
  const std::int64_t v = value_->get<std::int64_t>();
  if (v < lo || v > hi) fail(str("value ", v, " is out of range [", lo, ", ", hi, "]"));
  return v;
}

std::string JsonReader::asString() const {
  if (!value_->is_string()) fail("expected a string, found " + typeName(*value_));
  return value_->get<std::string>();
}

bool JsonReader::asBool() const {
  if (!value_->is_boolean()) fail("expected true or false, found " + typeName(*value_));
  return value_->get<bool>();
}

Eigen::Vector3f JsonReader::asVec3() const {
  if (!value_->is_array() || value_->size() != 3) fail("expected an array of 3 numbers");
  Eigen::Vector3f v;
  for (int i = 0; i < 3; ++i)
    v[i] = static_cast<float>(at(static_cast<std::size_t>(i)).asNumber(-1e30, 1e30));
  return v;
}

Eigen::Vector4f JsonReader::asVec4() const {
  if (!value_->is_array() || value_->size() != 4) fail("expected an array of 4 numbers");
  Eigen::Vector4f v;
  for (int i = 0; i < 4; ++i)
    v[i] = static_cast<float>(at(static_cast<std::size_t>(i)).asNumber(-1e30, 1e30));
  return v;
}

double JsonReader::number(const std::string& key, double lo, double hi) const {
  return at(key).asNumber(lo, hi);
}
double JsonReader::number(const std::string& key, double fallback, double lo, double hi) const {
  return has(key) ? at(key).asNumber(lo, hi) : fallback;
}
std::int64_t JsonReader::integer(const std::string& key, std::int64_t lo, std::int64_t hi) const {
  return at(key).asInteger(lo, hi);
}
std::int64_t JsonReader::integer(const std::string& key, std::int64_t fallback, std::int64_t lo,
                                 std::int64_t hi) const {
  return has(key) ? at(key).asInteger(lo, hi) : fallback;
}
std::string JsonReader::string(const std::string& key) const {
  return at(key).asString();
}
std::string JsonReader::string(const std::string& key, const std::string& fallback) const {
  return has(key) ? at(key).asString() : fallback;
}
bool JsonReader::boolean(const std::string& key, bool fallback) const {
  return has(key) ? at(key).asBool() : fallback;
}
Eigen::Vector3f JsonReader::vec3(const std::string& key) const {
  return at(key).asVec3();
}
Eigen::Vector3f JsonReader::vec3(const std::string& key, const Eigen::Vector3f& fallback) const {
  return has(key) ? at(key).asVec3() : fallback;
}

}  // namespace pelage
