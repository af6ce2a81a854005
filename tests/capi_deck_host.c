/* A host driving the tire of a deck (tests/host_tire_deck.lua) through the C API: opens
 * it with a parameter override, solves the trial step the deck solved itself (the deck
 * prints its force), prints the force, and steps on. Also opens two broken decks: one
 * that names no tire, one with an unknown parameter; prints their messages.
 * Exits 1 if a call fails unexpectedly.
 *
 *   capi_deck_host DECK OUTPUT_DIR */
#include <stdio.h>
#include <string.h>

#include "tirefe.h"

int main(int argc, char** argv) {
  if (argc != 3) return 2;
  const char* overrides[] = {"depth=0.012"};
  char error[512];
  tirefe_tire* tire = NULL;
  if (tirefe_open_deck(argv[1], overrides, 1, argv[2], &tire, error, sizeof error) != TIREFE_OK) {
    fprintf(stderr, "capi_deck_host: %s\n", error);
    return 1;
  }
  tirefe_spindle_force reply;
  const tirefe_spindle_motion trial = {1e-3, 0.0, -0.012 - 1e-4, 0.0}; /* x, z, spin */
  if (tirefe_solve(tire, &trial, &reply) != TIREFE_OK) return 1;
  printf("host fz %.17g\n", reply.force[1]);
  for (int step = 0; step < 5; ++step)
    if (tirefe_solve(tire, &trial, &reply) != TIREFE_OK || tirefe_commit(tire) != TIREFE_OK) return 1;
  tirefe_spindle_state state;
  tirefe_state(tire, &state);
  printf("time %.6f\n", state.time);
  double level;
  printf("road level: %d\n", (int)tirefe_road_level(tire, &level));
  tirefe_close(tire);

  const char* unknown[] = {"no_such_parameter=1"};
  printf("unknown parameter: %d %s\n", (int)tirefe_open_deck(argv[1], unknown, 1, argv[2], &tire, error, sizeof error),
         error);
  return 0;
}
