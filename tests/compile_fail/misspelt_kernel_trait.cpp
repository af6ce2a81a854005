// Must not compile: a kernel whose traits() misspells a member (reads_accleration). Its
// promises are members of KernelTraits (element.hpp), so the compiler names the misspelt
// one instead of the block falling back to the default; tests/CMakeLists.txt builds this
// file and expects that message.
#include "core/element.hpp"

namespace tirefe {

struct MisspeltTraitKernel : KernelShape<1> {
  static constexpr KernelTraits traits() {
    KernelTraits traits;
    traits.reads_accleration = false;
    return traits;
  }
};

}  // namespace tirefe
