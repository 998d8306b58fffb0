/*
 * groundnav_vectors.c - the nav board's dead reckoning on a recorded pulse stream, on both
 * worlds (issue 5): the host build and the MSP430 image must print bit-identical poses.
 *
 * The stream (generated at build time by tools/gen_gnav_stream.py from exact tricycle
 * kinematics) is delivered through the real interrupt path: on the MSP430 each odometer
 * pulse and gyro edge sets its port-1 flag with interrupts off and the ISR runs when they
 * are enabled again (HAL shim + portable handler, measured: @cycles isr_delta_l, the worst
 * case includes every kind of arc closing; it and isr_gyro_step are checked against the
 * floor of 1,000 cycles); the coordinate request sets the NMI flag; in the
 * host build the harness raises the same lines. Then: latches read back, a fix applied for
 * an earlier latch, and closings after straights long enough for every branch of the
 * deficit (up to 262,144 pulses, delivered as direct calls).
 */
#include <stdint.h>

#include "cy_test.h"
#include "gnav_stream.h"
#include "groundnav/gnav.h"
#include "hal/cpu.h"
#include "hal/edge.h"
#include "hal/irq.h"
#include "hal/pinmap.h"

#ifdef __MSP430__
#include "f2618.h"
#else
#include "hal_posix/harness.h"
#endif

static gnav_t nav;
#ifdef __MSP430__
static uint16_t sync_overhead; /* cycles of an empty cy_target_sync() */
#endif

static cy_bench_stat_t st_dl = {"isr_delta_l", 0, 0, 0};
static cy_bench_stat_t st_close = {"isr_delta_l_closing", 0, 0, 0};
static cy_bench_stat_t st_gyro = {"isr_gyro_step", 0, 0, 0};
static cy_bench_stat_t st_sighted = {"isr_beacon_sighted", 0, 0, 0};
static cy_bench_stat_t st_coord = {"isr_coord_request", 0, 0, 0};
static cy_bench_stat_t st_fix = {"gnav_fix", 0, 0, 0};
static cy_bench_stat_t st_pose = {"gnav_pose", 0, 0, 0};
static cy_bench_stat_t st_latch = {"gnav_latch_read", 0, 0, 0};
static cy_stack_stat_t sk_dl = {"isr_delta_l", 0}, sk_gyro = {"isr_gyro_step", 0},
                       sk_sighted = {"isr_beacon_sighted", 0}, sk_coord = {"isr_coord_request", 0},
                       sk_fix = {"gnav_fix", 0}, sk_latch = {"gnav_latch_read", 0};

/* Raise @p line and let its handler run; on the MSP430 returns the cycles of the whole
 * interrupt (entry, HAL shim, portable handler, return), 0 on the host. */
static uint16_t raise_line(hal_edge_line_t line)
{
#ifdef __MSP430__
    if (line == HAL_EDGE_COORD_REQUEST) {
        /* the RST/NMI pin: a falling edge from the simulator, taken inside the sync */
        cy_print("@sim wdt nmi 0\n");
        uint16_t t0 = cy_bench_now();
        cy_target_sync();
        uint16_t t1 = cy_bench_now();
        cy_print("@sim wdt nmi 1\n");
        cy_target_sync();
        return (uint16_t)(t1 - t0 - cy_bench_overhead - sync_overhead);
    }
    cy_dint();
    P1IFG |= (uint8_t)(1u << hal_edge_pin(line));
    uint16_t t0 = cy_bench_now();
    cy_eint();
    uint16_t t1 = cy_bench_now();
    return (uint16_t)(t1 - t0 - cy_bench_overhead);
#else
    posix_edge_raise(posix_board_current(), line);
    posix_dispatch();
    return 0;
#endif
}

static uint32_t closings(void)
{
    return gnav_closings(&nav, 0) + gnav_closings(&nav, 1) + gnav_closings(&nav, 2);
}

static void pulse(void)
{
    uint32_t before = closings();
    uint16_t c;
    CY_STACK(&sk_dl, c = raise_line(HAL_EDGE_DELTA_L));
    cy_bench_add(&st_dl, c);
    if (closings() != before)
        cy_bench_add(&st_close, c);
}

static void print_pose_raw(const char *tag)
{
    const gnav_pub_t *p = &nav.pub[nav.pub_seq & 1u];
    cy_print(tag);
    cy_print(" ");
    cy_print_hex64((uint64_t)p->x);
    cy_print(" ");
    cy_print_hex64((uint64_t)p->y);
    cy_print(" ");
    cy_print_hex32(p->heading);
    cy_print(" k ");
    cy_print_dec(p->k);
    cy_print(" rate ");
    cy_print_dec(p->rate);
    cy_print(" dir ");
    cy_print_dec(p->dir);
    cy_print(" ival ");
    cy_print_dec(p->ival);
    cy_print(" n ");
    cy_print_dec((int32_t)(((uint32_t)(uint16_t)nav.n_hi << 16) | nav.n_lo));
    for (unsigned k = 0; k < 4u; k++) {
        cy_print(" ");
        cy_print_dec((int32_t)gnav_closings(&nav, k));
    }
    cy_println();
}

static void print_pose(const char *tag, const gnav_pose_t *p)
{
    cy_print(tag);
    cy_print(" ");
    cy_print_dec(p->x);
    cy_print(" ");
    cy_print_dec(p->y);
    cy_print(" ");
    cy_print_hex32(p->heading);
    cy_println();
}

/* The last (up to) 8 latches as the main loop reads them now: their headings inside the cell
 * come from closed, open and forgotten intervals of every kind. */
static void print_latches(void)
{
    uint16_t next = gnav_latch_next(&nav);
    for (uint16_t k = 1; k <= 8u && k <= next; k++) {
        gnav_latch_t l;
        int r = 0;
        volatile uint16_t seq = (uint16_t)(next - k);
        CY_STACK(&sk_latch, CY_BENCH(&st_latch, r = gnav_latch_read(&nav, seq, &l)));
        cy_check(r == GNAV_OK, "latch read");
        cy_print("latch ");
        cy_print_dec(l.seq);
        print_pose("", &l.pose);
    }
}

static const gnav_config_t cfg = {
    .wheelbase = 49938,             /* 0.762 m (30 in) */
    .dl_q40 = 279275970u,           /* 0.01 in */
    .gyro_step_q48 = 195468720091u, /* 0.25 degrees */
    .stop_distance = 100l * 65536l,
};

static void replay(void)
{
    static const gnav_pose_t start = {.x = 12l * 65536l, .y = -3l * 65536l, .heading = 0x15555555u};
    cy_check(gnav_init(&nav, &cfg, &start) == GNAV_OK, "init");
    cy_check(gnav_attach(&nav) == 0, "attach");
    hal_irq_enable();
    print_pose_raw("start");
    for (uint16_t i = 0; i < GNAV_STREAM_N; i++) {
        uint16_t w = gnav_stream[i];
        uint16_t kind = (uint16_t)(w >> 13), count = (uint16_t)(w & 0x1FFFu);
        switch (kind) {
        case 0:
            for (uint16_t j = 0; j < count; j++)
                pulse();
            break;
        case 1: {
            uint16_t c;
            CY_STACK(&sk_gyro, c = raise_line(HAL_EDGE_GYRO_UP));
            cy_bench_add(&st_gyro, c);
            break;
        }
        case 2: {
            uint16_t c;
            CY_STACK(&sk_gyro, c = raise_line(HAL_EDGE_GYRO_DOWN));
            cy_bench_add(&st_gyro, c);
            break;
        }
        case 3: {
            uint16_t c;
            CY_STACK(&sk_sighted, c = raise_line(HAL_EDGE_BEACON_SIGHTED));
            cy_bench_add(&st_sighted, c);
            break;
        }
        case 4:
            gnav_set_reverse(&nav, true);
            break;
        case 5:
            gnav_set_reverse(&nav, false);
            break;
        default: {
            print_pose_raw("pose");
            uint16_t cc;
            CY_STACK(&sk_coord, cc = raise_line(HAL_EDGE_COORD_REQUEST));
            cy_bench_add(&st_coord, cc);
            gnav_pose_t c;
            gnav_coord(&nav, &c);
            print_pose("coord", &c);
            gnav_pose(&nav, &c);
            print_pose("pose_now", &c);
            print_latches();
            break;
        }
        }
    }
    print_pose_raw("end");
    gnav_pose_t p;
    CY_BENCH(&st_pose, gnav_pose(&nav, &p));
    print_pose("pose_m", &p);
    cy_check(!gnav_stop_requested(&nav), "no stop request within 100 m");
}

/* Latches of the replay, and a fix for the instant of one of them. */
static void latches_and_fix(void)
{
    uint16_t next = gnav_latch_next(&nav);
    gnav_latch_t l;
    cy_check(gnav_latch_read(&nav, next, &l) == GNAV_ERR_LATCH, "future latch refused");
    cy_check(gnav_latch_read(&nav, (uint16_t)(next - GNAV_LATCH_N - 1u), &l) == GNAV_ERR_LATCH,
             "overwritten latch refused");
    for (uint16_t k = 1; k <= 4u; k++) {
        cy_check(gnav_latch_read(&nav, (uint16_t)(next - k), &l) == GNAV_OK, "latch read");
        cy_print("latch ");
        cy_print_dec(l.seq);
        print_pose("", &l.pose);
    }
    /* the fix says the vehicle was 5 cm further east and 1 degree more to the left at the
     * instant of latch next-3 */
    cy_check(gnav_latch_read(&nav, (uint16_t)(next - 3u), &l) == GNAV_OK, "ref latch");
    gnav_pose_t f = l.pose;
    f.x += 3277;
    f.heading += 11930465u;
    int r = 0;
    CY_STACK(&sk_fix, CY_BENCH(&st_fix, r = gnav_fix(&nav, &f, &l)));
    cy_check(r == GNAV_OK, "fix applied");
    print_pose_raw("fixed");
    cy_check(gnav_latch_read(&nav, (uint16_t)(next - 3u), &l) == GNAV_OK, "ref latch at once");
    cy_check(l.pose.x == f.x && l.pose.y == f.y && l.pose.heading == f.heading,
             "the reference latch now reads as the fix");
    for (unsigned k = 0; k < 200u; k++)
        pulse();
    cy_bench_add(&st_gyro, raise_line(HAL_EDGE_GYRO_UP));
    pulse();
    print_pose_raw("after");
    cy_check(gnav_latch_read(&nav, (uint16_t)(next - 3u), &l) == GNAV_OK, "ref latch again");
    print_pose("ref_now", &l.pose);
    /* The gyro edge closed the latch's interval: its heading inside the cell is estimated
     * again with the exit it made (docs/groundnav.md, "The heading inside the cell"), at most
     * half a step from the estimate the fix used; its position stays. */
    uint32_t dh = l.pose.heading - f.heading;
    if (dh > 0x80000000u)
        dh = 0u - dh;
    cy_check(l.pose.x == f.x && l.pose.y == f.y && dh <= nav.step_whole / 2u,
             "the reference latch reads as the fix, its heading within half a step");
}

/*
 * Closings after m pulses, for every branch of the deficit (the pulses before the closing as
 * direct calls, the closing itself through the interrupt): the first edge after init (half a
 * step), a standard step forwards and backwards, two edges inside one pulse, and a reversal.
 */
static void long_intervals(void)
{
    static const uint32_t ms[] = {14, 20, 32, 33, 500, 1023, 1024, 3000, 16384, 70000, 262144};
    static const gnav_pose_t origin = {0, 0, 0};
    for (unsigned i = 0; i < sizeof ms / sizeof ms[0]; i++) {
        for (unsigned variant = 0; variant < 4u; variant++) {
            gnav_init(&nav, &cfg, &origin);
            cy_check(gnav_attach(&nav) == 0, "attach");
            gnav_set_reverse(&nav, variant == 1u);
            if (variant == 3u) { /* reversal: an arc's curvature goes on across a threshold */
                for (unsigned j = 0; j < 40u; j++)
                    gnav_on_delta_l(&nav);
                gnav_on_gyro_up(&nav);
                gnav_on_delta_l(&nav);
                for (unsigned j = 0; j < 40u; j++)
                    gnav_on_delta_l(&nav);
                gnav_on_gyro_up(&nav);
            } else if (variant != 0u) {
                gnav_on_gyro_up(&nav); /* leave the start cell: P on a threshold */
            }
            for (uint32_t j = 1; j < ms[i]; j++)
                gnav_on_delta_l(&nav);
            if (variant == 3u)
                gnav_on_gyro_down(&nav); /* back through the same threshold */
            else
                gnav_on_gyro_up(&nav);
            if (variant == 2u)
                gnav_on_gyro_up(&nav); /* two edges inside one pulse */
            pulse();
            cy_print("m ");
            cy_print_dec((int32_t)ms[i]);
            cy_print(" v");
            cy_print_dec((int32_t)variant);
            print_pose_raw("");
        }
    }
}

int main(void)
{
    hal_cpu_init();
    cy_bench_init();
#ifdef __MSP430__
    uint16_t t0 = cy_bench_now();
    cy_target_sync();
    uint16_t t1 = cy_bench_now();
    sync_overhead = (uint16_t)(t1 - t0 - cy_bench_overhead);
#endif
    replay();
    latches_and_fix();
    long_intervals();
    cy_bench_report(&st_dl);
    cy_bench_report(&st_close);
    cy_bench_report(&st_gyro);
    cy_bench_report(&st_sighted);
    cy_bench_report(&st_coord);
    cy_bench_report(&st_fix);
    cy_bench_report(&st_pose);
    cy_bench_report(&st_latch);
    const cy_stack_stat_t *sk[] = {&sk_dl, &sk_gyro, &sk_sighted, &sk_coord, &sk_fix, &sk_latch};
    for (unsigned i = 0; i < sizeof sk / sizeof sk[0]; i++)
        cy_stack_report(sk[i]);
    /* The floors of issue 13 on the worst case (a check image runs every kernel twice) */
    if (!cy_kernel_check_mode()) {
        cy_check(st_dl.max <= 1000u, "isr_delta_l at most 1,000 cycles");
        cy_check(st_gyro.max <= 1000u, "isr_gyro_step at most 1,000 cycles");
    }
    cy_test_end();
    return 0;
}
