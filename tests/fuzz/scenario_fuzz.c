/*
 * scenario_fuzz.c - agv-sim's scenario loader (sim/scenario.c, sim/schema.c): any text as a
 * scenario file's contents.
 *
 * Properties beyond memory safety: the loader answers 0, or -1 with a non-empty reason; an
 * accepted scenario holds what docs/schema/scenario.schema.json allows (counts of beacons,
 * reflectors, walls and path points, every number finite and within its key's range, the
 * mode one of the schema's); and the same text gives the same answer twice.
 */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "fuzz_check.h"
#include "sim/scenario.h"

#define DEG (M_PI / 180.0)

/* @p v within [lo, hi] (the schema's range, in the struct's units), with a rounding's room. */
#define IN(v, lo, hi)                                                                              \
    FUZZ_CHECK(isfinite((double)(v)) && (v) >= (lo)-1e-12 && (v) <= (hi) + 1e-12,                  \
               "accepted %s = %.17g outside [%g, %g]", #v, (double)(v), (double)(lo),              \
               (double)(hi))

static void check_accepted(const sim_scenario_t *sc)
{
    FUZZ_CHECK(memchr(sc->name, '\0', sizeof sc->name) != NULL, "name not terminated");
    FUZZ_CHECK(sc->mode >= 0 && sc->mode < SIM_SCENARIO_MODE_COUNT, "mode %d", sc->mode);
    const sim_world_t *w = &sc->world;
    IN(w->n_beacons, 3, SIM_MAX_BEACONS);
    IN(w->n_spurious, 0, SIM_MAX_SPURIOUS);
    IN(w->n_occluders, 0, SIM_MAX_OCCLUDERS);
    for (size_t i = 0; i < w->n_beacons; i++) {
        IN(w->beacon[i].x, -1e4, 1e4);
        IN(w->beacon[i].y, -1e4, 1e4);
        IN(w->beacon[i].diameter, 0.005, 2.0);
    }
    for (size_t i = 0; i < w->n_spurious; i++) {
        IN(w->spurious[i].x, -1e4, 1e4);
        IN(w->spurious[i].y, -1e4, 1e4);
        IN(w->spurious[i].width, 0.001 * DEG, 1.0 * DEG);
    }
    for (size_t i = 0; i < w->n_occluders; i++) {
        IN(w->occluder[i].x1, -1e4, 1e4);
        IN(w->occluder[i].y2, -1e4, 1e4);
    }
    IN(sc->wheelbase, 0.1, 5.0);
    IN(sc->min_radius, 0.05, 100.0);
    IN(sc->speed, 0.01, 5.0);
    IN(sc->start_x, -1e4, 1e4);
    IN(sc->start_heading, -720 * DEG, 720 * DEG);
    IN(sc->start_err_x, -1.0, 1.0);
    IN(sc->start_err_heading, -10 * DEG, 10 * DEG);
    IN(sc->n_path, 1, SIM_SCENARIO_PATH_MAX_ITEMS);
    for (size_t i = 0; i < sc->n_path; i++) {
        IN(sc->path[i].x, -1e4, 1e4);
        IN(sc->path[i].heading, -720 * DEG, 720 * DEG);
        IN(sc->path[i].speed, 0.01, 5.0); /* absent: the vehicle's */
    }
    IN(sc->rev_per_s, 0.1, 50.0);
    IN(sc->counts, 360, 65535);
    IN(sc->gonio_noise, 0.0, 5.0 * DEG);
    IN(sc->gonio_range, 1.0, 1000.0);
    IN(sc->dl, 1e-5, 0.1);
    IN(sc->odo_scale, 0.9, 1.1);
    IN(sc->gyro_step, 0.001 * DEG, 10.0 * DEG);
    IN(sc->gyro_drift, -1.0 * DEG, 1.0 * DEG);
    IN(sc->duration, 0.1, 36000.0);
    IN(sc->success.min_fix_ratio, 0.0, 1.0);
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    char *text = malloc(size + 1);
    FUZZ_CHECK(text != NULL, "out of memory");
    memcpy(text, data, size);
    text[size] = '\0';
    static sim_scenario_t a, b; /* 40 KB each: kept off the stack */
    char ea[512] = "", eb[512] = "";
    int ra = sim_scenario_parse(text, &a, ea, sizeof ea);
    FUZZ_CHECK(ra == 0 || ra == -1, "loader returned %d", ra);
    if (ra == 0)
        check_accepted(&a);
    else
        FUZZ_CHECK(ea[0] != '\0', "refused without a reason");
    int rb = sim_scenario_parse(text, &b, eb, sizeof eb);
    FUZZ_CHECK(rb == ra && strcmp(ea, eb) == 0,
               "a second parse answered differently: %d \"%s\" "
               "then %d \"%s\"",
               ra, ea, rb, eb);
    if (ra == 0)
        FUZZ_CHECK(memcmp(&a, &b, sizeof a) == 0, "a second parse filled another scenario");
    free(text);
    return 0;
}
