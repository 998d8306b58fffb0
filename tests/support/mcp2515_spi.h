/*
 * mcp2515_spi.h - hal/spi.h with the MCP2515 register model (mcp2515_model.h) behind it: the
 * SPI bus of the MCP2515 driver's host tests and of its target test image (the same source on
 * both worlds, linked instead of the HAL's USCI_B0 implementation). HAL_SPI_BUS_B0 with
 * HAL_SPI_CS_CAN reaches the attached model; the bus checks the HAL's contract (arguments,
 * initialisation, held frames) like the target's implementation does.
 */
#ifndef MCP2515_SPI_H
#define MCP2515_SPI_H

#include <stdint.h>

#include "hal/spi.h"
#include "mcp2515_model.h"

#ifdef __cplusplus
extern "C" {
#endif

/** Put @p m behind the bus (NULL: nothing answers, every byte reads 0xFF) and forget the
 * bus's set-up (hal_spi_init() is needed again). */
void mcp2515_spi_attach(mcp2515_model_t *m);

/** What the bus saw: the mode and rate of the last hal_spi_init(), the frames (chip select
 * assertions) and bytes so far, and (target) the cycles spent inside hal_spi_transfer(). */
typedef struct {
    hal_spi_mode_t mode;
    uint32_t rate_hz;
    uint32_t frames;
    uint32_t bytes;
    uint32_t cycles;
} mcp2515_spi_stats_t;

/** The bus's counters. */
const mcp2515_spi_stats_t *mcp2515_spi_stats(void);

#ifdef __cplusplus
}
#endif

#endif
