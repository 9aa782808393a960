// What the command line calls things: the libraries name fields ("fps 0 is out of range"), the
// command line its options ("--fps 0 is out of range").
#pragma once

#include <string>
#include <string_view>

#include "pelage/util/error.h"

namespace pelage::app {

// The option that sets library field `field` ("fps" -> "--fps"), or "" when none does.
std::string_view optionForField(std::string_view field);

// An error's message in the command line's words: a field error names the option instead.
std::string describe(const InputError& error);

}  // namespace pelage::app
