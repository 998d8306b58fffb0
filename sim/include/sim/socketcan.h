/*
 * socketcan.h - agv-sim --can IFACE: every frame of the bus model travels through a real
 * SocketCAN raw socket on IFACE and back (docs/interfaces.md, docs/socketcan.md).
 *
 * The bus model keeps deciding everything that makes the run what it is: timing, arbitration,
 * errors, faults. At the instant a frame goes through the model (its end), the carrier writes
 * it to the socket and reads back what the kernel delivers: with CAN_RAW_RECV_OWN_MSGS, the
 * socket receives its own frame again, marked MSG_CONFIRM, once the interface sent it (vcan
 * at once; a real can0 after the frame went out on its bus). That echo - the bytes the kernel
 * carried - is compared with the frame sent and handed to the receiving boards. Frames of
 * others on the interface (a cansend, another program) are skipped and counted. The run is the
 * same with and without --can: same report, same logs; only wall time differs. A failed
 * write, a missing echo (2 s) or an echo that differs ends the run with an error (exit 2).
 */
#ifndef SIM_SOCKETCAN_H
#define SIM_SOCKETCAN_H

#include <stddef.h>
#include <stdint.h>

#include "hal/can.h"

typedef struct {
    int fd;
    char iface[32];
    uint64_t frames;  /* carried there and back */
    uint64_t foreign; /* others' frames skipped */
    int failed;       /* the carrier failed: err says why */
    char err[256];
} sim_socketcan_t;

/**
 * Open a CAN_RAW socket on @p iface, receiving its own frames. Returns 0, or -1 with the
 * reason (naming the interface) in @p err.
 */
int sim_socketcan_open(sim_socketcan_t *s, const char *iface, char *err, size_t errlen);

/** The bus model's carrier (posix_can_carrier_fn; ctx = the sim_socketcan_t). */
int sim_socketcan_carry(void *ctx, hal_can_t bus, const hal_can_frame_t *sent,
                        hal_can_frame_t *got);

/** Close the socket. */
void sim_socketcan_close(sim_socketcan_t *s);

#endif
