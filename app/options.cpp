#include "options.h"

#include <array>
#include <utility>

namespace pelage::app {

std::string_view optionForField(std::string_view field) {
  static constexpr std::array<std::pair<std::string_view, std::string_view>, 22> kOptions{{
      {"benchmark frames", "--benchmark-frames"},
      {"benchmark hairs", "--benchmark-hairs"},
      {"camera", "--camera"},
      {"clip", "--clip"},
      {"dynamics", "--dynamics"},
      {"encoders", "--encoders"},
      {"fov", "--fov"},
      {"fps", "--fps"},
      {"frames", "--frames"},
      {"hair source", "--hair-source"},
      {"hold", "--hold"},
      {"out", "--out"},
      {"preroll", "--preroll"},
      {"samples", "--samples"},
      {"screenshot", "--screenshot"},
      {"shading", "--shading"},
      {"size", "--size"},
      {"skin color", "--skin-color"},
      {"sweep", "--sweep"},
      {"time", "--time"},
      {"triangles", "--triangles"},
      {"video", "--video"},
  }};
  for (const auto& [name, option] : kOptions)
    if (name == field) return option;
  return {};
}

std::string describe(const InputError& error) {
  const std::string_view option = optionForField(error.field());
  if (option.empty()) return error.what();
  return InputError::join(std::string(option), error.detail());
}

}  // namespace pelage::app
