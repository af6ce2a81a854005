/* tirefe.h: the C API of libtirefe, a 2D finite-element tire behind its spindle.
 *
 * A host (a multibody vehicle code, a co-simulation master, a script) drives the tire
 * through its spindle, as docs/spindle.md describes for C++: in every corrector
 * iteration of a host step it puts the spindle somewhere at the end of the step
 * (tirefe_solve), gets the spindle force and its consistent 3x3 Jacobian back, and ends
 * the step with tirefe_commit (accepted) or tirefe_revert (rejected). docs/coupling.md
 * has a complete host and what each call costs.
 *
 * Axes, units and signs: ISO 8855 wheel axes at the wheel centre, as TYDEX and MF-Tyre
 * use them (docs/output.md, "Axes and signs"): x along the wheel's heading, z up, y the
 * spin axis (left of the heading); SI units (m, rad, s, N, N m). The motion is
 * (x, z, spin), the spin angle about y (positive rolling forward); force = (Fx, Fz, My)
 * is the force and moment THE TIRE EXERTS ON THE WHEEL: a loaded tire gives Fz = +load,
 * a driving torque Fx > 0. The heading is +x of the tire's plane unless
 * tirefe_options.heading says -x: a host rolling forward along its own x needs nothing.
 *
 * Errors: every call returns a status; TIREFE_OK is 0. On any other status
 * tirefe_message() says why in one line. No call throws, exits or aborts.
 * Handles: a tirefe_tire* or tirefe_saved_state* is a number in the guise of a pointer,
 * looked up in the library's table of open handles and never dereferenced: NULL, a
 * closed tire, a freed state (handles are never reused) or any other pointer is
 * TIREFE_INVALID_ARGUMENT, a double tirefe_close or tirefe_free_state too; closing NULL
 * does nothing, as free(NULL) does. A handle closed while another thread's call runs on
 * it is freed when that call returns.
 * Cancel: tirefe_cancel() stops the calls that run a deck's Lua code or take many steps.
 * Threads: calls on one handle are serialized by the handle (a lock); different
 * handles run in parallel, except tires opened from decks, which write result files:
 * their calls share one lock (the HDF5 library is not thread-safe).
 * C99; no C++ types cross this interface.
 */
#ifndef TIREFE_H
#define TIREFE_H

#include <stddef.h>

#ifdef __cplusplus
extern "C" {
#endif

typedef enum tirefe_status {
  TIREFE_OK = 0,
  TIREFE_INVALID_ARGUMENT = 1, /* a null pointer, a non-finite number, an unknown parameter */
  TIREFE_MODEL_ERROR = 2,      /* the tire could not be built: bad parameter values or files */
  TIREFE_STEP_FAILED = 3,      /* the step did not converge; the tire stays at its committed state */
  TIREFE_INVALID_CALL = 4,     /* a call out of order: commit without a solved trial step */
  TIREFE_OUT_OF_MEMORY = 5,
  TIREFE_INTERNAL_ERROR = 6,
  TIREFE_CANCELLED = 7 /* stopped by tirefe_cancel; a tire stays at its committed state */
} tirefe_status;

/* An opened tire. Not copyable; close it with tirefe_close. */
typedef struct tirefe_tire tirefe_tire;

/* One tire parameter overridden by name (a key of model:tire, docs/tire.md): e.g.
 * {"pressure", 180e3} or {"k_sw", 1200}. */
typedef struct tirefe_parameter {
  const char* name;
  double value;
} tirefe_parameter;

/* How the tire is set up. Fill with tirefe_default_options, then change fields. */
typedef struct tirefe_options {
  double friction;         /* Coulomb friction coefficient between tread and road (default 0.8) */
  double hht_alpha;        /* the tire's time integrator: 0 Newmark average acceleration (default),
                              in [-1/3, 0) HHT-alpha; the host should integrate with the same scheme */
  int free_spin;           /* 1 (default): the wheel turns freely on its bearing (the tire solves the
                              spin, My = 0); 0: the host gives the spin angle and gets the drive torque;
                              nothing else */
  int heading;             /* +1 (default): the wheel heads along +x of the tire's plane; -1: along -x */
  const char* road;        /* NULL (default): a flat road. Else a road file (docs/roads.md): a road data file
                              (.rdf, a flat or profile road), a CSV profile (.csv) or an ASCII OpenCRG road
                              (.crg), its x (an OpenCRG road's u) along the heading and its height 0 at the
                              level the tire touches with the spindle at z = 0 */
  const char* road_track;  /* "left" or "right": the track of a .rdf or .csv file with two (NULL: its only one) */
  double road_lateral;     /* an OpenCRG road's track: its lateral offset v from the reference line [m], left
                              positive, within the road's long sections (default 0: the reference line); must
                              be 0 for other roads */
  double road_start;       /* where the road file's x = 0 lies along the heading [m] (default 0) */
  double road_edge_radius; /* rounding of the road's convex corners [m] (default 0) */
  double start_z;          /* where the host takes the spindle over: the tire is pressed quasi-statically from
                              touching the road to this height [m] (default 0), its spin and x as built */
  const char* integrator;  /* NULL (default): hht_alpha decides. Else a scheme by name (docs/dynamics.md):
                              "newmark" (average acceleration), "hht" (with hht_alpha), "wbz" or
                              "generalized_alpha" (with rho_inf) */
  double rho_inf;          /* wbz and generalized_alpha: spectral radius at omega h -> infinity, in [0, 1]
                              (default 0.9) */
} tirefe_options;

/* The spindle at the end of the step to solve: the step h from the committed time and
 * the wheel centre's position and spin angle in wheel axes (absolute; the design
 * position of the spindle is x = z = 0, its spin 0). spin is ignored when free. */
typedef struct tirefe_spindle_motion {
  double time_step; /* h [s], at least 1e-7 s (below, round-off of the positions swamps the inertia) */
  double x;         /* along the heading [m] */
  double z;         /* up [m] */
  double spin;      /* about y, positive rolling forward [rad] */
} tirefe_spindle_motion;

/* The answer to a solved step. */
typedef struct tirefe_spindle_force {
  double force[3];       /* {Fx [N], Fz [N], My [N m]} the tire exerts on the wheel (see above). With
                            HHT the trial force is weighted like the tire's equations (docs/spindle.md) */
  double jacobian[3][3]; /* jacobian[i][j] = d force[i] / d (x, z, spin)[j]; for tirefe_solve_velocity
                            d force[i] / d (vx, vz, spin rate)[j]. Row and column 2 are zero when free */
  double time;           /* at the end of the solved step [s] */
  int newton_iterations; /* of the tire, this call */
} tirefe_spindle_force;

/* A stretch of steps for tirefe_advance: the spindle moves from its committed position,
 * with the rates 'start_velocity', to 'position' with 'velocity' at the end of 'duration',
 * along the cubic in time that meets both ends. Start a stretch with the rates the one
 * before ended with, so that the spindle's path has no kink where they meet (the tire's
 * own spindle velocity, tirefe_state's, carries its integrator's ringing, which a path
 * starting from it would feed back). */
typedef struct tirefe_spindle_path {
  double duration;          /* from the committed time [s] */
  double start_velocity[3]; /* rates of x, z, spin at the start [m/s, m/s, rad/s] */
  double position[3];       /* x [m], z [m], spin [rad] at the end (spin ignored when free) */
  double velocity[3];       /* their rates at the end */
} tirefe_spindle_path;

/* How a stretch went. */
typedef struct tirefe_advance_report {
  double time;           /* the committed time when tirefe_advance returned [s] */
  int steps;             /* steps taken and committed */
  int cuts;              /* tries that did not converge */
  int newton_iterations; /* of the steps taken */
} tirefe_advance_report;

/* The committed state of the spindle. */
typedef struct tirefe_spindle_state {
  double time;        /* [s] */
  double position[3]; /* x [m], z [m], spin [rad] in wheel axes */
  double velocity[3]; /* their rates [m/s, m/s, rad/s] */
  double force[3];    /* {Fx, Fz, My}: the physical force at the committed time [N, N, N m] */
} tirefe_spindle_state;

/* "0.1.0 (commit)": the library's version. */
const char* tirefe_version(void);

void tirefe_default_options(tirefe_options* options);

/* Opens a tire from its parameters: 'source' is a tire property file (a path ending in
 * .tir, docs/tire.md) or the name of a shipped parameter module ("tires.145SR12",
 * "tires.145SR12_tread_layer"); 'overrides' (may be NULL when count is 0) change
 * parameters by name; 'options' may be NULL for the defaults. The tire is built with its
 * spindle at (0, 0), inflated quasi-statically on its held hub (1 s of model time), and
 * put on a flat road touching its lowest tread node (tirefe_road_level); the spindle is
 * then the host's. On failure *tire is NULL and, when error is not NULL, the reason is
 * written there (at most error_size bytes, NUL-terminated). */
tirefe_status tirefe_open(const char* source, const tirefe_parameter* overrides, size_t count,
                          const tirefe_options* options, tirefe_tire** tire, char* error, size_t error_size);

/* Opens the tire a deck built (docs/decks.md): runs the deck with its parameters
 * overridden by 'overrides' ("key=value" strings as on tirefe's command line; may be NULL
 * when count is 0), its result files going to 'output_dir' (NULL: "results"; "" is refused). The deck
 * makes its model dynamic (Newmark or HHT) and names the tire for the host at its end:
 *     host_tire = { model = model, spindle = tire.spindle }       -- free_spin = false: driven
 * The deck's model then stays alive with the handle, and every committed step is written
 * to its result file like a deck's own step. tirefe_road_level is not available (the
 * deck's surfaces are its own). The wheel axes head as the deck's tire does
 * (model:tire{ heading }). Errors as for tirefe_open, the deck's messages naming its
 * file and line. */
tirefe_status tirefe_open_deck(const char* deck, const char* const* overrides, size_t count, const char* output_dir,
                               tirefe_tire** tire, char* error, size_t error_size);

/* Closes the tire and frees it. NULL: nothing, TIREFE_OK; a handle not open (closed
 * before, or never opened): TIREFE_INVALID_ARGUMENT. */
tirefe_status tirefe_close(tirefe_tire* tire);

/* Asks the calls of this library in progress in any thread (or, when none runs, the next
 * one) to stop: a deck's Lua code in tirefe_open_deck or in the load functions of a deck
 * tire's step, a deck's steps, the Lua of a parameter module in tirefe_open, the
 * deflections of tirefe_static_forces. Such a call returns TIREFE_CANCELLED within
 * milliseconds, a tire at its committed state; the cancel is then answered. Safe to call
 * from any thread and from a signal handler (it sets an atomic flag): a host's SIGINT
 * handler, a watchdog thread or alarm() gives a deadline. A call doing neither (a step of
 * a tire opened by tirefe_open) finishes; its cancel stops the next one. */
void tirefe_cancel(void);

/* Why the last call on this handle failed (one line); "" after a success. The text
 * stays valid until the next call on the handle. For a handle not open: a text saying so. */
const char* tirefe_message(const tirefe_tire* tire);

/* Height of the road below the spindle's design position [m] (negative). */
tirefe_status tirefe_road_level(tirefe_tire* tire, double* level);

/* Solves the trial step with the spindle held at 'motion' and answers with the spindle
 * force and its consistent Jacobian. Every solve starts from the committed state: call
 * it as often as the host's corrector needs within one step. */
tirefe_status tirefe_solve(tirefe_tire* tire, const tirefe_spindle_motion* motion, tirefe_spindle_force* out);

/* The same with the spindle's velocities at the end of the step given (vx, vz [m/s],
 * spin rate [rad/s]); the positions follow from the tire's Newmark formulas, and the
 * Jacobian is with respect to the velocities (H beta h / gamma). */
tirefe_status tirefe_solve_velocity(tirefe_tire* tire, double time_step, const double velocity[3],
                                    tirefe_spindle_force* out);

/* Advances the tire along 'path' in steps of its own, each committed as it converges:
 * equal, at most max_step long (> 0) and at least 1e-7 s, the last ending on the end; halved when one does not
 * converge and grown back after easy ones (the step control of docs/dynamics.md, at most
 * 10 cuts). A pending trial step is forgotten first. TIREFE_STEP_FAILED when a step fails
 * even at its smallest: the tire then stays at the last step it committed (report->time),
 * and the message says where along the stretch it stopped. 'report' may be NULL. */
tirefe_status tirefe_advance(tirefe_tire* tire, const tirefe_spindle_path* path, double max_step,
                             tirefe_advance_report* report);

/* Accepts the last solved trial step: the tire advances to it. */
tirefe_status tirefe_commit(tirefe_tire* tire);

/* Forgets the last trial step (the host rejected its step); the tire is unchanged. */
tirefe_status tirefe_revert(tirefe_tire* tire);

/* The committed time and spindle state. */
tirefe_status tirefe_state(tirefe_tire* tire, tirefe_spindle_state* state);

/* The tire's static vertical force-deflection curve on a flat frictionless road: the
 * tire of 'source' and 'overrides' (as for tirefe_open) inflated on its held hub, then
 * its spindle pressed quasi-statically to each of 'deflections' [m] (below first touch,
 * in this order) in turn. forces[i] is the vertical force Fz the tire exerts on the wheel
 * there [N] (positive: the tire carries the wheel). No handle: nothing is kept. */
tirefe_status tirefe_static_forces(const char* source, const tirefe_parameter* overrides, size_t count,
                                   const double* deflections, size_t n, double* forces, char* error, size_t error_size);

/* A step budget for real-time hosts (docs/performance.md). By default (all 0) every step
 * iterates to the tire's Newton tolerance or fails. With max_iterations N > 0, a step's
 * Newton ends after N iterations when its relative residual |R| / R_ref is within
 * max_residual, converged or not: the step is taken with the force of that state and the
 * residual is reported; above max_residual it goes on to convergence (an overrun: the
 * error of a state far from converged feeds the next steps' accelerations and grows).
 * max_time T > 0 [s] ends Newton in the same way once a solve has taken T of wall time
 * (after its first iteration), and counts every step whose solves and commit took longer
 * (a time miss). A budget also starts every step from the zero-acceleration predictor
 * (docs/dynamics.md), which spares a rolling tire iterations and failed steps; no budget
 * gives the tire its own back. Holds for tirefe_solve and for the steps of tirefe_advance. */
typedef struct tirefe_step_budget {
  int max_iterations;  /* Newton iterations per step; 0: to convergence */
  double max_time;     /* [s] of wall time per step; 0: none */
  double max_residual; /* the largest |R| / R_ref a step may end with; 0: 1e-4 (HUGE_VAL: any) */
} tirefe_step_budget;

/* The committed steps since the budget was last set (or the tire opened). */
typedef struct tirefe_budget_report {
  long steps;            /* committed */
  long unconverged;      /* ended by the budget before Newton's tolerance */
  double worst_residual; /* the largest |R| / R_ref a step ended with (0: every step converged) */
  long overruns;         /* took more than max_iterations (their residual above max_residual there) */
  long time_misses;      /* took longer than max_time (when set) */
  double worst_time;     /* the longest step: its solves and its commit [s] */
} tirefe_budget_report;

/* Sets the budget (NULL: none) and starts its report afresh. */
tirefe_status tirefe_set_step_budget(tirefe_tire* tire, const tirefe_step_budget* budget);
tirefe_status tirefe_step_budget_report(tirefe_tire* tire, tirefe_budget_report* report);

/* A copy of a tire's committed state (its checkpoint, docs/restart.md, kept in memory):
 * a host that steps back in time (a co-simulation master repeating a macro step)
 * saves the tire and restores it later, into it or a tire built with the same parameters
 * (another: TIREFE_INVALID_ARGUMENT). A pending trial step is discarded by a restore.
 * Free the copy with tirefe_free_state. */
typedef struct tirefe_saved_state tirefe_saved_state;
tirefe_status tirefe_save_state(tirefe_tire* tire, tirefe_saved_state** saved);
tirefe_status tirefe_restore_state(tirefe_tire* tire, const tirefe_saved_state* saved);
/* NULL: nothing, TIREFE_OK; a state not saved (freed before): TIREFE_INVALID_ARGUMENT. */
tirefe_status tirefe_free_state(tirefe_saved_state* saved);

#ifdef __cplusplus
}
#endif

#endif /* TIREFE_H */
