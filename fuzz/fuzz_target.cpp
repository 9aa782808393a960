// One libFuzzer target per input reader: built once per name in fuzz/CMakeLists.txt with
// PELAGE_FUZZ_TARGET set to the reader's name (see fuzz_entry.h).
#include <cstddef>
#include <cstdint>

#include "fuzz_entry.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  pelage::fuzz::runTarget(PELAGE_FUZZ_TARGET, data, size);
  return 0;
}
