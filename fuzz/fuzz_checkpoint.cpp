// libFuzzer target: checkpoint_file (fuzz/fuzz_entries.hpp). Built with -DTIREFE_FUZZ=ON (clang).
#include "fuzz/fuzz_entries.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  tirefe::fuzz::checkpoint_file(data, size);
  return 0;
}
