/*
 * possrc.h - the simulated laser positioning system of seed 002 (SPSi's, its chapter 3):
 * three transmitters in the corners of the room, a receiver on the vehicle (or two). At
 * every update (rate_hz) each receiver's true position is measured, with noise relative to
 * its distance from the farthest transmitter (the seed: about 1 part in 100,000), provided
 * every transmitter is within range and not behind an occluder; after the system's lag the
 * position goes to the main board as seed 002's 14-byte packet (0x00, x, y, z as signed
 * 32-bit big-endian millimetres, 0xFF) on the receiver's serial line (hal/posix's UART,
 * instance 0 for receiver 1, 1 for receiver 2). Its troubles, each drawn per update and
 * receiver from the scenario's seed: outages (no updates at all), dropouts, zero packets,
 * wild positions, garbage before a packet, corrupted bytes. An update that finds its line
 * still busy with more than the packet before (9600 baud carries at most 68 packets a
 * second) is not sent. docs/posrx.md.
 */
#ifndef SIM_POSSRC_H
#define SIM_POSSRC_H

#include <stddef.h>
#include <stdint.h>

#include "sim/drive_board.h"
#include "sim/rng.h"
#include "sim/scenario.h"

/** Packets waiting for their lag to pass (100 Hz x 5 s x 2 receivers). */
#define SIM_POSSRC_QUEUE 1024
/** Longest packet with the garbage before it. */
#define SIM_POSSRC_BYTES 34

/** What the system did (the report's pursuit.source). */
typedef struct {
    uint32_t updates;       /* update instants */
    uint32_t sent;          /* packets put on the lines */
    uint32_t outage;        /* updates inside an outage */
    uint32_t dropouts;      /* receiver updates dropped */
    uint32_t no_sight;      /* receiver updates without all three transmitters */
    uint32_t line_busy;     /* packets not sent: the line still busy */
    uint32_t zeros, wilds;  /* packets with zeros, with a wild position */
    uint32_t garbage_bytes; /* random bytes before packets */
    uint32_t corrupt_bytes; /* bytes replaced on the line */
} sim_possrc_stats_t;

typedef struct {
    uint64_t t_ns; /* when it goes on the line */
    uint8_t receiver, len;
    uint8_t bytes[SIM_POSSRC_BYTES];
} sim_possrc_packet_t;

typedef struct {
    const sim_position_source_t *cfg;
    const sim_world_t *world;
    const sim_drive_t *drive; /* the truth */
    int board;                /* the main board */
    sim_xy_t tx[3];           /* the transmitters */
    sim_xy_t rcv[2];          /* the receivers' mountings */
    int n_rcv;
    double period; /* s */
    sim_rng_t rng;
    uint64_t k; /* updates so far */
    sim_possrc_packet_t q[SIM_POSSRC_QUEUE];
    size_t q_head, q_n;
    sim_possrc_stats_t st;
} sim_possrc_t;

/**
 * The positioning system of scenario @p sc measuring the vehicle of @p drive, sending to
 * harness board @p main_board (whose firmware opens the UARTs). Nothing is scheduled yet.
 */
void sim_possrc_init(sim_possrc_t *s, const sim_scenario_t *sc, const sim_drive_t *drive,
                     int main_board);

/** Schedule the first update (one period from now). */
void sim_possrc_start(sim_possrc_t *s);

/** Receiver @p r's true position (m) at @p t (s): the vehicle's pose and its mounting. */
sim_xy_t sim_possrc_truth(const sim_possrc_t *s, int r, double t);

#endif
