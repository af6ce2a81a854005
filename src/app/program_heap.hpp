// The heap settings of the tirefe programs (not of the library, which leaves its host's
// allocator alone).
#pragma once

#ifdef __GLIBC__
#include <malloc.h>
#endif

namespace tirefe::macros {

/// The result file's row buffers grow between flushes and are handed back and forth with
/// the writer: kept in the heap rather than mapped and unmapped each time, their pages are
/// reused instead of faulted in anew.
inline void keep_row_buffers_in_heap() {
#ifdef __GLIBC__
  mallopt(M_MMAP_THRESHOLD, 64 << 20);
  mallopt(M_TRIM_THRESHOLD, 128 << 20);
#endif
}

}  // namespace tirefe::macros
