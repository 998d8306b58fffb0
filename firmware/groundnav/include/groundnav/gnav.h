/*
 * gnav.h - ground navigation of the nav board (SPEC G1-G6, issue 5): dead reckoning at every
 * odometer pulse from a tricycle's front-wheel travel and an incremental gyro, pose latches at
 * beacon sightings, optical fixes applied for an earlier instant, a never-torn coordinate
 * request, and a stop request after too much travel without a fix. docs/groundnav.md has the
 * kinematics, the formats and the protocol.
 *
 * Geometry: the steered, driven front wheel sits L ahead of the rear-axle centre (the
 * reference point). An odometer pulse is dl of FRONT-wheel travel; a gyro edge is one step of
 * heading (up = counter-clockwise). The heading is only known to a gyro cell (one step wide);
 * the arc between two gyro edges is closed at the first pulse after the second edge with the
 * rear-axle chord n - E(n) pulses along the cell's mean heading, E(n) = n - sqrt(n^2 - M^2),
 * M = L * step / dl (the seed's situation 3); fewer than M pulses for a step leave the
 * position where it was (situation 1); between edges the pose is continued from the last
 * curvature for at most the last interval's length, then straight (situation 2, bounded).
 * The headings handed out (pose, coordinate request, latches) are placed inside the gyro's
 * cell: on the threshold at an edge, then on at the rate the intervals showed, between the
 * edges once the next one is known (latches read later); the handlers store pulse counts
 * only, the readers divide (docs/groundnav.md, "The heading inside the cell").
 *
 * Contexts: the five handlers below have the hal_edge_cb_t signature (arg = the gnav_t) and
 * run in interrupt context. gnav_on_coord_request() is meant for the non-maskable line: it may
 * preempt every other handler and every critical section and still sees a consistent pose
 * (the pose is published double-buffered). The other functions run in the main loop.
 * All state lives in the caller's gnav_t (no heap); the fields are private.
 */
#ifndef GROUNDNAV_GNAV_H
#define GROUNDNAV_GNAV_H

#include <stdbool.h>
#include <stdint.h>

#include "fx/fx.h"

#ifdef __cplusplus
extern "C" {
#endif

/** Entries of the per-configuration deficit table: M = L * step / dl must stay below this. */
#define GNAV_TABLE_N 32u
/** Pose latches kept (a power of two, at least the 15 sightings of a revolution). */
#define GNAV_LATCH_N 16u
/** Closed gyro intervals remembered to interpolate latch headings (a power of two). */
#define GNAV_RING_N  8u
/** gnav_pub_t.k while a gyro edge has not been followed by a pulse yet. */
#define GNAV_K_EDGE  INT16_MIN
/** Fix corrections kept to bring latches of older frames forward. */
#define GNAV_CORR_N  4u

/** Result codes (0 = success); gnav_strerror() names them. */
typedef enum {
    GNAV_OK = 0,
    GNAV_ERR_WHEELBASE = -1, /**< wheelbase outside (0, 32] m */
    GNAV_ERR_DL = -2,        /**< odometer pulse outside [2^25, 2^31) * 2^-40 m */
    GNAV_ERR_GYRO_STEP = -3, /**< gyro step outside (0, 10] degrees */
    GNAV_ERR_STEERING = -4,  /**< M = L * step / dl not below GNAV_TABLE_N */
    GNAV_ERR_STOP = -5,      /**< negative stop distance */
    GNAV_ERR_POSE = -6,      /**< a position outside the +-30,000 m working range */
    GNAV_ERR_LATCH = -7,     /**< latch no longer (or not yet) in the buffer */
    GNAV_ERR_STALE = -8,     /**< latch older than the last GNAV_CORR_N fixes */
    GNAV_ERR_BUSY = -9,      /**< fix not installed: the state kept changing under it */
    GNAV_ERR_NULL = -10,     /**< a required pointer was NULL */
} gnav_err_t;

/** Configuration (fixed point; fx_host.h converts on the host). */
typedef struct {
    fx_q16_t wheelbase;     /**< L, rear axle to front wheel, metres Q15.16, (0, 32] m */
    uint32_t dl_q40;        /**< front-wheel travel per odometer pulse, metres * 2^40:
                                 [2^25, 2^31), i.e. 30.5 um .. 1.95 mm (0.01 in = 279275970) */
    uint64_t gyro_step_q48; /**< heading per gyro step, turns * 2^48, (0, 2^48 / 36]
                                 (0.25 degrees = 2^48 / 1440 rounded) */
    fx_q16_t stop_distance; /**< travel without an optical fix before the stop request,
                                 metres Q15.16, >= 0; 0 = never */
} gnav_config_t;

/** A pose: rear-axle centre in metres (Q15.16) and heading (binary angle, CCW from +x). */
typedef struct {
    fx_q16_t x, y;
    fx_angle_t heading;
} gnav_pose_t;

/** A pose latched at a beacon sighting, in the frame of fix generation @c gen. */
typedef struct {
    uint16_t seq; /**< latch number: the k-th Beacon Sighted edge since init has seq k */
    uint8_t gen;  /**< frame generation (number of fixes applied when it was valid, mod 256) */
    gnav_pose_t pose;
} gnav_latch_t;

/**
 * Called from the coordinate-request (NMI) handler once it has taken the pose of that instant;
 * read it with gnav_coord() from the main loop (the conversion to metres multiplies, which
 * nothing in the NMI may do). Keep it short and multiply-free: it runs in the NMI.
 */
typedef void (*gnav_coord_fn)(void *ctx);
/** Called once from the dl handler when the travel without a fix reaches the limit. */
typedef void (*gnav_stop_fn)(void *ctx);

/* Private state (about 0.9 KB of RAM); see gnav_internal.h for the formats. */
typedef struct {
    int64_t x, y;       /* pulses, Q25 */
    fx_angle_t heading; /* centre of the gyro cell */
    int16_t k;          /* pulses since the interval's first pulse (GNAV_K_EDGE: none yet) */
    uint16_t rate;      /* the rate it entered at, pulses per step (0: unknown) */
    uint16_t ival;      /* its number: gyro edges so far */
    int8_t dir;         /* its entry edge: +1 up, -1 down, 0 the start at the cell centre */
} gnav_pub_t;

typedef struct {
    int32_t x4, y4;     /* pulses, Q4 */
    fx_angle_t heading; /* centre of the gyro cell */
    int16_t k;          /* the published k, rate, interval number and dir */
    uint16_t rate;
    uint16_t ival;
    int8_t dir;
    uint8_t gen;
} gnav_latch_raw_t;

typedef struct {
    fx_angle_t turn;  /* heading correction */
    fx_q30_t c, s;    /* its cosine and sine */
    int32_t lx4, ly4; /* reference point before (pulses Q4) */
    int32_t fx4, fy4; /* ... and after the correction */
} gnav_corr_t;

typedef struct gnav {
    /* dead reckoning, the dl handler's part (x, y adjacent: one call adds a step to both) */
    int64_t x, y;      /* provisional position, pulses Q25 */
    int64_t xp, yp;    /* closing point P of the interval */
    int32_t inc[2][2]; /* step per pulse, Q25: [0] curved (dir - rho_p dir), [1] dir */
    uint16_t n_lo;     /* signed pulses since P: n_hi:n_lo (negative: backwards) */
    int16_t n_hi;
    int16_t nq;                /* the same, saturated at +-32767 */
    uint16_t n_p;              /* curved pulses of this interval: the last one's length */
    uint16_t rho_p;            /* deficit per pulse of the last interval, Q15 */
    uint16_t x_p, g_p;         /* x = M / n_p (Q16) and g(x) (Q17) while rho_p is due */
    int32_t resid;             /* rounding carried between closings, pulses Q16 */
    int16_t d15_c, d15_s;      /* unit vector of the interval's cell, Q15 */
    uint16_t stop_lo, stop_hi; /* pulses left before the stop request */
    uint8_t pending, reverse, dc_due, rho_due, stop_armed, stop;
    uint8_t p_due; /* the closing point P is the position now: taken at the next pulse */
    /* gyro: the current cell */
    int32_t nxt_c, nxt_s;    /* its unit vector, Q25 */
    int16_t n15_c, n15_s;    /* and in Q15 */
    fx_angle_t heading;      /* its centre, rounded */
    uint32_t hd;             /* its centre, turns * 2^32 (floor) ... */
    uint16_t hd_frac;        /* ... and the next 16 bits: the step is not a whole binary angle */
    uint16_t cell, cell_int; /* gyro count now and of the interval (both wrap) */
    uint16_t h_p, h_first, h_last; /* half-step indices of P and of the edges since */
    uint16_t version;              /* bumped by every closing and gyro edge (fix installation) */
    /* the heading inside the cell: the interval since the last edge (published with the pose) */
    uint16_t ival;  /* gyro edges so far: the interval's number */
    uint16_t hrate; /* the rate it entered at, pulses per step (0: unknown) */
    int8_t hdir;    /* direction of the last edge (0: none since init) */
    uint8_t gen;    /* fixes applied (mod 256): the frame generation */
    /* the published pose: the writer fills pub[(seq + 1) & 1], then bumps seq */
    volatile uint16_t pub_seq;
    gnav_pub_t pub[2];
    gnav_stop_fn stop_fn;
    void *stop_ctx;
    /* configuration and derived constants (init) */
    uint32_t dl_q40;
    int32_t per_m_q16;   /* pulses per metre, Q16 */
    uint32_t step_whole; /* the gyro step: turns * 2^32 (floor) and the next 16 bits */
    uint16_t step_frac;
    uint32_t m_q24; /* M = L * step / dl, pulses, Q24 */
    uint32_t m_q16;
    uint16_t m_q11;
    uint16_t n0;      /* smallest pulse count with n >= M */
    uint16_t tab_end; /* the table holds n0 .. tab_end - 1 */
    uint32_t stop_pulses;
    int32_t tab_e[GNAV_TABLE_N];    /* E(n), pulses Q16 */
    uint16_t tab_rho[GNAV_TABLE_N]; /* E(n) / n, Q15 */
    uint32_t closings[4];           /* situation 1, arcs, reversals, extra edges */
    /* latches and frames; the intervals closed last (by number mod GNAV_RING_N): pulses from
     * the entry edge to the exit edge, bit 15 set when the exit edge went up */
    uint16_t ring[GNAV_RING_N];
    uint16_t latch_seq;
    gnav_latch_raw_t latch[GNAV_LATCH_N];
    gnav_corr_t corr[GNAV_CORR_N];
    /* outputs: the coordinate request's snapshots (the NMI fills coord[(seq + 1) & 1], then
     * bumps coord_seq) */
    volatile uint16_t coord_seq;
    gnav_pub_t coord[2];
    gnav_coord_fn coord_fn;
    void *coord_ctx;
} gnav_t;

/**
 * Initialise @p g for @p cfg at the pose @p start (which also "sets the gyroscope": the
 * gyro reading at this instant is the centre of the start heading's cell). Fills the deficit
 * table (up to 32 square roots; a few ms on the MSP430). Returns GNAV_OK or the first
 * configuration error (g then unusable). Does not register the handlers (gnav_attach()).
 */
int gnav_init(gnav_t *g, const gnav_config_t *cfg, const gnav_pose_t *start);

/**
 * Register the five handlers with hal_edge_init(): dl, gyro up/down and beacon sighted on
 * their rising edges, the coordinate request on the NMI line. Returns 0 or -1 (HAL refused).
 */
int gnav_attach(gnav_t *g);

/** dl handler: one odometer pulse (dl of front-wheel travel, direction set by gnav_set_reverse). */
void gnav_on_delta_l(void *arg);
/** Gyro handler: the heading went up (counter-clockwise) by one step. */
void gnav_on_gyro_up(void *arg);
/** Gyro handler: the heading went down (clockwise) by one step. */
void gnav_on_gyro_down(void *arg);
/** Beacon Sighted handler: latch the current pose as the next latch (seq = count so far),
 * with what its heading inside the cell needs (no division: gnav_latch_read places it). */
void gnav_on_beacon_sighted(void *arg);
/**
 * Coordinate Request handler (NMI): copy the published pose (never torn, even when it
 * preempts the dl handler mid-update) as the snapshot gnav_coord() reads, and call the
 * callback set with gnav_set_coord_callback(). A copy of 28 bytes and nothing else: it
 * reaches no multiply (an NMI may land inside any; tools/stack_bound.py --no-mpy-in-nmi proves
 * it for the nav board image).
 */
void gnav_on_coord_request(void *arg);

/** Direction of travel for the following pulses (from the drive): true = backwards. */
void gnav_set_reverse(gnav_t *g, bool reverse);

/** Callback of the coordinate request (NULL: none). Set it before attaching. */
void gnav_set_coord_callback(gnav_t *g, gnav_coord_fn fn, void *ctx);
/** Callback of the stop request (NULL: none); runs in the dl handler. */
void gnav_set_stop_callback(gnav_t *g, gnav_stop_fn fn, void *ctx);

/**
 * The current pose, consistent (never torn), from any context but the NMI (it multiplies):
 * retries while dl or gyro handlers publish under it. Position error: at most 8 um of rounding
 * on top of the dead reckoning itself. Heading: inside the current gyro cell (within +-half a
 * step of its centre), extrapolated from the last edge at the rate the intervals showed
 * (cycles: gnav_pose in build/msp430/cycles.json).
 */
void gnav_pose(gnav_t *g, gnav_pose_t *out);

/**
 * The pose the last coordinate request took (all zero before the first), in metres and with
 * its heading placed inside the cell: the snapshot converted now (the same numbers whenever it
 * is read). Main loop only, any time after the request; retries while a new request lands
 * under it.
 */
void gnav_coord(const gnav_t *g, gnav_pose_t *out);

/** Number of the next latch (the count of Beacon Sighted edges so far, wraps at 2^16). */
uint16_t gnav_latch_next(const gnav_t *g);

/**
 * Latch number @p seq brought into the current frame (all fixes since applied), into *out.
 * Its heading is placed inside its gyro cell with what is known now: between the edges of its
 * interval when that has closed since (one of the last GNAV_RING_N), else from the edge
 * before it; reading later can only refine it. GNAV_ERR_LATCH when it is not in the buffer
 * (more than GNAV_LATCH_N newer ones, or not yet taken), GNAV_ERR_STALE when more than
 * GNAV_CORR_N fixes came after it.
 */
int gnav_latch_read(gnav_t *g, uint16_t seq, gnav_latch_t *out);

/**
 * Apply an optical fix: @p fix is the true pose at the instant of @p ref (a latch as read with
 * gnav_latch_read(), any generation not older than GNAV_CORR_N fixes), or now when @p ref is
 * NULL. The motion since that instant is carried forward: the whole dead-reckoning state
 * (position, closing point, heading and the gyro's cell, i.e. "set the gyroscope") is moved
 * by the rigid transform that takes the reference pose onto the fix, never overwritten; the
 * reference's heading is its estimate inside the cell, whose offset from the centre is kept. Resets
 * the travel counted for the stop request and clears the request. Interrupts are held off for
 * the final install only. Returns GNAV_OK, GNAV_ERR_LATCH/STALE (ref), GNAV_ERR_POSE, or
 * GNAV_ERR_BUSY when 8 attempts in a row were overtaken by gyro edges or arc closings.
 */
int gnav_fix(gnav_t *g, const gnav_pose_t *fix, const gnav_latch_t *ref);

/** True once the travel without a fix has reached the configured stop distance. */
bool gnav_stop_requested(const gnav_t *g);

/** Arc closings so far by kind: 0 too few pulses (situation 1), 1 arcs, 2 reversals of the
 * heading (zero net step), 3 extra gyro edges inside one pulse. */
uint32_t gnav_closings(const gnav_t *g, unsigned kind);

/** M = L * step / dl in pulses, Q8.24 (for tests and reports). */
uint32_t gnav_m_q24(const gnav_t *g);

/** Readable name of a gnav_err_t. */
const char *gnav_strerror(int err);

#ifdef __cplusplus
}
#endif

#endif
