// The names of an enum read from and written to text (preset fields, groom strokes, options): one
// table per enum gives a value's name, the value of a name and the accepted names for messages, so
// a message's list cannot drift from what the parser accepts.
#pragma once

#include <array>
#include <cstddef>
#include <optional>
#include <string>
#include <string_view>
#include <utility>

namespace pelage {

template <class E, std::size_t N>
struct EnumNames {
  std::array<std::pair<E, std::string_view>, N> entries;

  // The name of `value`; "?" for a value the table lacks.
  constexpr std::string_view name(E value) const {
    for (const auto& [v, n] : entries)
      if (v == value) return n;
    return "?";
  }

  // The value named exactly `text`; nullopt for any other text.
  constexpr std::optional<E> find(std::string_view text) const {
    for (const auto& [v, n] : entries)
      if (n == text) return v;
    return std::nullopt;
  }

  // The accepted names in table order, "a, b, c".
  std::string list() const {
    std::string s;
    for (const auto& [v, n] : entries) {
      if (!s.empty()) s += ", ";
      s += n;
    }
    return s;
  }
};

// EnumNames from a braced list: makeEnumNames<HairStyle>({{HairStyle::Line, "line"}, ...}).
template <class E, std::size_t N>
constexpr EnumNames<E, N> makeEnumNames(const std::pair<E, std::string_view> (&entries)[N]) {
  EnumNames<E, N> names{};
  for (std::size_t k = 0; k < N; ++k) names.entries[k] = entries[k];
  return names;
}

}  // namespace pelage
