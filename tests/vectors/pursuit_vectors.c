/*
 * pursuit_vectors.c - seed 002's goal-point pursuit on both worlds: a closed loop in fixed
 * point (a tricycle that takes the pursuit's steering and speed commands, its drive slower
 * per count than nominal, a receiver 10 times a second with millimetres of noise, a gap in
 * the updates, a second receiver behind the first with one pair out of place) drives a
 * five-point path to its end. Every command and every update's record are printed, then the
 * counters: the MSP430's output must equal the host's (the same C, firmware/pursuit). The
 * update's cycles go to the cycle report as pursuit_position (main-loop work, no floor).
 */
#include <stdint.h>

#include "cy_test.h"
#include "drive/drive_path.h"
#include "fx/fx.h"
#include "pursuit/pursuit.h"

#define Q16(num, den) ((fx_q16_t)((int32_t)(num)*65536 / (den))) /* num/den m, Q16 */
#define STEP_MS       100u                                       /* receiver updates, 10 Hz */
#define TICK_MS       10u         /* the main loop's pursuit_tick() */
#define WHEELBASE_Q16 49938       /* 0.762 m */
#define TRUE_PER_NOM  55705       /* the drive's true speed per count: 0.85 of nominal, Q16 */
#define RAD_TO_ANGLE  683565276ll /* 2^32 / (2 pi), binary angle per radian */
#define MM_Q16        66          /* one millimetre, metres Q16 (65.5) */

static uint32_t rng = 0x6A09E667u;
static cy_bench_stat_t st_pos = {"pursuit_position", 0, 0, 0};

static const int32_t pts[][2] = {{3, 0}, {5, 2}, {5, 6}, {2, 8}};
static drive_path_point_t path[4];

/* The vehicle: rear-axle point (m Q16), heading, steering and the drive's speed counts. */
static fx_q16_t vx, vy;
static fx_angle_t vh, steer;
static int8_t counts;

static void print_out(uint32_t t, const pursuit_out_t *o)
{
    if (!o->actions)
        return;
    cy_print("t ");
    cy_print_dec((int32_t)t);
    cy_print(" act ");
    cy_print_dec(o->actions);
    cy_print(" steer ");
    cy_print_hex32(o->steer);
    cy_print(" speed ");
    cy_print_dec(o->speed);
    cy_println();
}

static void apply(const pursuit_out_t *o)
{
    if (o->actions & PURSUIT_ACT_STEER)
        steer = o->steer;
    if (o->actions & PURSUIT_ACT_SPEED)
        counts = o->speed;
    if (o->actions & PURSUIT_ACT_DONE)
        counts = 0;
}

/* One step of STEP_MS: the arc the vehicle drives, in fixed point. */
static void move(fx_q16_t max_speed)
{
    int64_t v = (int64_t)counts * max_speed / PURSUIT_SPEED_COUNTS; /* nominal, m/s Q16 */
    v = v * TRUE_PER_NOM >> 16;
    int32_t d = (int32_t)(v * STEP_MS / 1000); /* m Q16 */
    int32_t turn = 0;                          /* rad Q16 */
    fx_div_shift(fx_mul_q16(d, fx_tan(steer)), WHEELBASE_Q16, 16, &turn);
    fx_angle_t dh = (fx_angle_t)(int32_t)((int64_t)turn * RAD_TO_ANGLE >> 16);
    fx_q30_t s, c;
    fx_sincos(vh + (fx_angle_t)((int32_t)dh / 2), &s, &c); /* the chord's direction */
    vx += fx_mul_q30(d, c);
    vy += fx_mul_q30(d, s);
    vh += dh;
}

static int32_t noise(void)
{
    return ((int32_t)(cy_rand32(&rng) % 7u) - 3) * MM_Q16;
}

int main(void)
{
    cy_bench_init();
    for (uint8_t i = 0; i < 4u; i++) {
        path[i].pose.x = Q16(pts[i][0], 1);
        path[i].pose.y = Q16(pts[i][1], 1);
        path[i].speed = Q16(1, 2);
    }
    pursuit_config_t cfg = {0};
    cfg.speed = Q16(1, 2);
    cfg.max_speed = Q16(1, 1);
    cfg.k = Q16(1, 1);
    cfg.activation_ms = 400u;
    cfg.threshold = Q16(1, 2);
    cfg.max_steer = fx_angle_from_counts(40u, 360u);
    cfg.slow_after_ms = 600u;
    cfg.stop_after_ms = 1500u;
    cfg.regulate = true;
    cfg.pair_sep = Q16(1, 2);
    cfg.pair_tol = Q16(1, 20);
    cy_check(pursuit_config_ok(&cfg), "configuration in range");
    pursuit_t p;
    cy_check(pursuit_init(&p, &cfg, 0, 0, path, 4u), "pursuit set up");
    pursuit_out_t out;
    uint32_t t = 0;
    pursuit_start(&p, 0, t, &out);
    print_out(t, &out);
    apply(&out);
    for (uint16_t k = 1; k < 1200u && !pursuit_done(&p); k++) {
        for (uint32_t dt = TICK_MS; dt <= STEP_MS; dt += TICK_MS) {
            pursuit_tick(&p, t + dt, &out);
            print_out(t + dt, &out);
            apply(&out);
        }
        t += STEP_MS;
        move(cfg.max_speed);
        if (k >= 150u && k < 172u)
            continue; /* the receiver's line is dark for 2.2 s */
        fx_q16_t x = vx + noise(), y = vy + noise();
        fx_angle_t h, *heading = 0;
        if (k % 5u == 0) { /* a second receiver 0.5 m behind, one pair out of place */
            fx_q30_t s, c;
            fx_sincos(vh, &s, &c);
            fx_q16_t back = k == 100u ? Q16(3, 5) : Q16(1, 2);
            if (pursuit_pair(&p, x, y, x - fx_mul_q30(back, c), y - fx_mul_q30(back, s), &h))
                heading = &h;
        }
        pursuit_record_t rec;
        pursuit_alive(&p, t);
        CY_BENCH(&st_pos, pursuit_position(&p, x, y, heading, t, &rec, &out));
        cy_print("rec ");
        cy_print_dec((int32_t)t);
        cy_print(" ");
        cy_print_hex32((uint32_t)rec.x);
        cy_print(" ");
        cy_print_hex32((uint32_t)rec.y);
        cy_print(" h ");
        cy_print_hex32(rec.heading);
        cy_print(" err ");
        cy_print_hex32((uint32_t)rec.err);
        cy_print(" xd ");
        cy_print_hex32((uint32_t)rec.xdist);
        cy_print(" seg ");
        cy_print_dec(rec.segment);
        cy_print(" goal ");
        cy_print_dec(rec.goal);
        cy_print(" dphi ");
        cy_print_hex32(rec.dphi);
        cy_println();
        print_out(t, &out);
        apply(&out);
    }
    const pursuit_stats_t *s = &p.st;
    const uint32_t n[] = {s->updates, (uint32_t)s->err_max, s->corrections,
                          s->goals,   s->slowdowns,         s->stops,
                          s->resumes, s->regulations,       s->pair_rejects};
    cy_print("stats");
    for (uint8_t i = 0; i < sizeof n / sizeof n[0]; i++) {
        cy_print(" ");
        cy_print_dec((int32_t)n[i]);
    }
    cy_print(" sum ");
    cy_print_hex64(s->err_sum);
    cy_println();
    cy_check(pursuit_done(&p), "the path driven to its end");
    cy_check(s->goals == 3u && s->slowdowns >= 1u && s->stops >= 1u && s->resumes >= 1u &&
                 s->regulations >= 1u && s->pair_rejects == 1u && s->corrections >= 5u,
             "every feature at work");
    cy_bench_report(&st_pos);
    cy_test_end();
    return 0;
}
