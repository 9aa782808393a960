// Two kinds of error (STYLE.md practice 8):
//  - InputError: bad user input (files, parameters, command line). The message names the file or
//    field and the accepted range; the app prints it and exits non-zero.
//  - PELAGE_CHECK: a broken internal invariant (a bug); throws InternalError with file:line.
#pragma once

#include <sstream>
#include <stdexcept>
#include <string>
#include <string_view>

namespace pelage {

// Bad user input: a clear message naming the file/field and the accepted range. Libraries name
// fields and values ("fps 0 is out of range [1, 1000]"); an error about one named field carries
// it, so an application can say it in its own words (app/ names the command-line option instead:
// "--fps 0 is out of range [1, 1000]").
class InputError : public std::runtime_error {
 public:
  explicit InputError(const std::string& message) : std::runtime_error(message) {}
  // An error about `field`: the message is "<field> <detail>" ("<field>: ..." when the detail
  // starts with a colon).
  InputError(const std::string& field, const std::string& detail)
      : std::runtime_error(join(field, detail)), field_(field), detail_(detail) {}
  // `name` (a field's, or an option's) followed by a detail as above.
  static std::string join(const std::string& name, const std::string& detail) {
    return detail.empty() || detail[0] == ':' ? name + detail : name + " " + detail;
  }
  // The field the error is about ("" when it names none), and the message after it.
  const std::string& field() const { return field_; }
  const std::string& detail() const { return detail_; }

 private:
  std::string field_, detail_;
};

// Bad user input that names a file which does not exist (Python raises FileNotFoundError for it).
class MissingFileError : public InputError {
 public:
  using InputError::InputError;
};

// Input text as an error message quotes it (excerpt): at most `maxChars` characters (then "..." and
// the whole length), control characters as \xNN. Every message that quotes what a user or a file
// gave goes through it, so a 2 MB buffer never becomes a 2 MB message.
inline constexpr std::size_t kMaxQuotedChars = 48;
std::string excerpt(std::string_view text, std::size_t maxChars = kMaxQuotedChars);
// Another library's message with each run of non-blank characters longer than kMaxQuotedChars
// (an echoed data URI, a whole buffer) cut as excerpt() cuts it.
std::string shortenLongWords(std::string_view message);

// Throws MissingFileError "<path>: <what> does not exist" unless `path` exists.
void requireExistingFile(const std::string& path, const std::string& what = "file");

// A broken invariant inside pelage (a bug, never the user's fault).
class InternalError : public std::logic_error {
 public:
  using std::logic_error::logic_error;
};

namespace detail {
[[noreturn]] void checkFailed(const char* file, int line, const char* cond, const std::string& msg);

inline void appendAll(std::ostringstream&) {}
template <typename T, typename... Rest>
void appendAll(std::ostringstream& os, const T& v, const Rest&... rest) {
  os << v;
  appendAll(os, rest...);
}
template <typename... Args>
std::string concat(const Args&... args) {
  std::ostringstream os;
  appendAll(os, args...);
  return os.str();
}
}  // namespace detail

// Builds a message from any streamable pieces: str("field ", name, " = ", v).
template <typename... Args>
std::string str(const Args&... args) {
  return detail::concat(args...);
}

// Throws InputError with the concatenated message.
template <typename... Args>
[[noreturn]] void inputError(const Args&... args) {
  throw InputError(detail::concat(args...));
}

// Throws InputError about `field` ("fps", "frames", "size"...), the rest of the message
// concatenated: fieldError("fps", 0, " is out of range [1, 1000]").
template <typename... Args>
[[noreturn]] void fieldError(const std::string& field, const Args&... args) {
  throw InputError(field, detail::concat(args...));
}

}  // namespace pelage

#define PELAGE_CHECK(cond, ...)                                                               \
  do {                                                                                        \
    if (!(cond))                                                                              \
      ::pelage::detail::checkFailed(__FILE__, __LINE__, #cond,                                \
                                    ::pelage::detail::concat("" __VA_OPT__(, ) __VA_ARGS__)); \
  } while (0)
