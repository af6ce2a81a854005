// TIREFE_SIMD_CLONES marks a loop kernel vectorised across elements to be compiled twice:
// for AVX2 and for the baseline x86-64 that every build targets; the program picks the
// one the processor runs when it loads (target_clones). AVX2 without FMA does the same
// IEEE arithmetic in the same order, so both give the same numbers, bit for bit, the
// AVX2 one on four lanes instead of two. GCC only: Clang (the fuzz build) does not clone
// templates yet, and builds the baseline.
#pragma once

#if defined(__x86_64__) && defined(__GNUC__) && !defined(__clang__)
#define TIREFE_SIMD_CLONES __attribute__((target_clones("avx2", "default")))
#else
#define TIREFE_SIMD_CLONES
#endif
