/*
 * hal/spi.h - SPI master buses and the chip selects of the devices on them.
 *
 * A bus is an instance (hal_spi_bus_t): hal_spi_init() sets its clock rate and SPI mode, then
 * hal_spi_transfer() exchanges bytes full duplex with one device, framed by that device's chip
 * select (active low). A transfer may leave the chip select asserted (HAL_SPI_HOLD) so that a
 * device instruction can be sent from one buffer and its data read into another within one
 * frame; the next transfer on the bus must then name the same chip select.
 *
 * Transfers are blocking and byte-polled; the HAL does not lock: a caller that uses a bus from
 * both the main loop and an interrupt handler holds interrupts off around each frame (the
 * MCP2515 driver, firmware/can, does).
 *
 *  - MSP430F2618 (hal/msp430/spi_usci_b0.c): HAL_SPI_BUS_B0 is USCI_B0 in 3-pin SPI master
 *    mode, MSB first, clocked from SMCLK divided by an integer (the fastest rate not above the
 *    request): P3.1 UCB0SIMO, P3.2 UCB0SOMI, P3.3 UCB0CLK; HAL_SPI_CS_CAN (the MCP2515's /CS)
 *    is P3.0 as a plain output (docs/hardware.md).
 *  - Host: the harness's boards have no SPI bus (their CAN is hal/can.h's bus model); host
 *    tests and target test images link tests/support/mcp2515_spi.c, which puts the MCP2515
 *    register model (tests/support/mcp2515_model.h) behind this API.
 */
#ifndef HAL_SPI_H
#define HAL_SPI_H

#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

/** SPI buses (instances). */
typedef enum {
    HAL_SPI_BUS_B0 = 0, /**< MSP430: USCI_B0 (P3.1 SIMO, P3.2 SOMI, P3.3 CLK) */
    HAL_SPI_BUS_COUNT
} hal_spi_bus_t;

/** Chip selects (one per device, active low). */
typedef enum {
    HAL_SPI_CS_CAN = 0, /**< the MCP2515 CAN controller's /CS: P3.0 */
    HAL_SPI_CS_COUNT
} hal_spi_cs_t;

/** SPI modes: clock polarity (CPOL, idle level of the clock) and phase (CPHA). */
typedef enum {
    HAL_SPI_MODE_0 = 0, /**< CPOL 0, CPHA 0: data sampled on the rising edge (MCP2515: 0,0) */
    HAL_SPI_MODE_1,     /**< CPOL 0, CPHA 1: sampled on the falling edge */
    HAL_SPI_MODE_2,     /**< CPOL 1, CPHA 0: sampled on the falling edge */
    HAL_SPI_MODE_3,     /**< CPOL 1, CPHA 1: sampled on the rising edge (MCP2515: 1,1) */
    HAL_SPI_MODE_COUNT
} hal_spi_mode_t;

/** Return codes. */
enum {
    HAL_SPI_OK = 0,
    HAL_SPI_ERR_ARG = -1,     /**< bus, chip select, mode or flags out of range, or rate 0 */
    HAL_SPI_ERR_RATE = -2,    /**< hal_spi_init(): the rate is below the slowest the bus does
                                   (MSP430: SMCLK / 16383, 977 Hz at 16 MHz) */
    HAL_SPI_ERR_STATE = -3,   /**< the bus is not initialised, or a held frame belongs to
                                   another chip select */
    HAL_SPI_ERR_TIMEOUT = -4, /**< a byte did not complete in twice its shift time (the bus
                                   hardware does not run); the chip select is released */
};

/** hal_spi_transfer() flags. */
#define HAL_SPI_HOLD 0x01u /**< leave the chip select asserted: the frame goes on */

/**
 * Set up @p bus as a master at the fastest clock rate not above @p rate_hz (Hz, > 0) in
 * @p mode, every chip select deasserted (driven high). May be called again to change the rate
 * or mode (between frames). Returns HAL_SPI_OK, HAL_SPI_ERR_ARG or HAL_SPI_ERR_RATE (nothing
 * changed then).
 */
int hal_spi_init(hal_spi_bus_t bus, uint32_t rate_hz, hal_spi_mode_t mode);

/** The clock rate @p bus runs at (Hz), 0 when it is not initialised or out of range. */
uint32_t hal_spi_rate(hal_spi_bus_t bus);

/**
 * Exchange @p n bytes (0..65535) with the device behind @p cs: asserts its chip select (unless
 * a held frame of the same device goes on), sends tx[0..n-1] (0x00 each when @p tx is NULL)
 * and stores the bytes received at the same time in rx[0..n-1] (discarded when @p rx is
 * NULL; @p rx may equal @p tx), then deasserts the chip select unless @p flags has
 * HAL_SPI_HOLD. Returns HAL_SPI_OK, HAL_SPI_ERR_ARG (unknown bus, chip select or flag bits)
 * or HAL_SPI_ERR_STATE (bus not initialised, or held by another chip select), and nothing is
 * sent then; or HAL_SPI_ERR_TIMEOUT when the bus stopped part way (chip select released).
 */
int hal_spi_transfer(hal_spi_bus_t bus, hal_spi_cs_t cs, const uint8_t *tx, uint8_t *rx, uint16_t n,
                     uint8_t flags);

#ifdef __cplusplus
}
#endif

#endif
