// tirefe: runs an input deck in this process (docs/decks.md).
//   tirefe deck.lua [key=value ...] [--output-dir DIR] [--restart FILE] [--quiet | --verbose]
//   tirefe --list-parameters DECK    the deck's parameters, without running it
//   tirefe --help | --macros | --version
// Exit status: 0 success, 1 deck or model error, 2 usage error, 3 a self-check failed,
// 128 + signal when SIGINT or SIGTERM stopped the run (after closing its files).
#include <iostream>
#ifdef __GLIBC__
#include <malloc.h>
#endif

#include "macros/deck_runner.hpp"

int main(int argc, char** argv) {
  // The result file's row buffers grow between flushes and are handed back and forth with
  // the writer: kept in the heap rather than mapped and unmapped each time, their pages are
  // reused instead of faulted in anew.
#ifdef __GLIBC__
  mallopt(M_MMAP_THRESHOLD, 64 << 20);
  mallopt(M_TRIM_THRESHOLD, 128 << 20);
#endif
  const tirefe::macros::DeckOutcome outcome = tirefe::macros::run_deck_command(argc, argv, {});
  std::cerr << outcome.error;
  return outcome.status;
}
