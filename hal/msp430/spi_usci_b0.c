/*
 * spi_usci_b0.c - hal/spi.h on USCI_B0 in 3-pin SPI master mode (docs/hardware.md, docs/can.md):
 * P3.1 UCB0SIMO, P3.2 UCB0SOMI, P3.3 UCB0CLK, MSB first, BRCLK = SMCLK divided by UCB0BR
 * (SLAU144: f_bitclock = f_BRCLK / UCBRx); the MCP2515's /CS is P3.0 as a plain output.
 *
 * Bytes are polled one at a time: write UCB0TXBUF, wait for UCB0RXIFG, read UCB0RXBUF (which
 * clears the flag). At 8 MHz (SMCLK 16 MHz / 2) a byte shifts in 16 MCLK cycles. The divider
 * follows the clock hal_cpu_init() chose (cy_clock.h): 10 MHz asked gives 8 MHz from 16 MHz,
 * 6 MHz from 12 MHz. The wait is
 * bounded by twice a byte's shift time (a poll takes at least 6 cycles: BIT.B &IFG2 and a
 * jump): a USCI that never completes a byte (a fault, or mspdebug's simulator, where the USCI
 * is plain memory) gives HAL_SPI_ERR_TIMEOUT instead of a hang.
 */
#include <stddef.h>

#include "cy_clock.h"
#include "f2618.h"
#include "hal/spi.h"

#define CS_CAN_BIT 0x01u /* P3.0 */
#define SPI_PINS   0x0Eu /* P3.1 SIMO, P3.2 SOMI, P3.3 CLK */

/* UCB0CTL0 clock bits of each SPI mode. TI's UCCKPH is the inverse of CPHA: with UCCKPH set
 * the data is captured on the first edge (SLAU144, "Serial Clock Control"). */
static const uint8_t mode_bits[HAL_SPI_MODE_COUNT] = {UCCKPH, 0u, UCCKPH | UCCKPL, UCCKPL};

/* The slowest divider: keeps a byte's poll bound (2 x 8 x div / 6 + 16) within 16 bits. */
#define DIV_MAX 16383u

static uint32_t rate;       /* Hz, 0 while not initialised */
static uint16_t poll_limit; /* UCB0RXIFG polls per byte before HAL_SPI_ERR_TIMEOUT */
static int8_t held = -1;    /* chip select of a held frame, -1 none */

int hal_spi_init(hal_spi_bus_t bus, uint32_t rate_hz, hal_spi_mode_t mode)
{
    if ((unsigned)bus >= HAL_SPI_BUS_COUNT || (unsigned)mode >= HAL_SPI_MODE_COUNT || rate_hz == 0u)
        return HAL_SPI_ERR_ARG;
    uint32_t clk = cy_clock->hz;                   /* SMCLK: the clock hal_cpu_init() chose */
    uint32_t div = (clk + rate_hz - 1u) / rate_hz; /* the fastest rate not above the request */
    if (div == 0u)
        div = 1u;
    if (div > DIV_MAX)
        return HAL_SPI_ERR_RATE;
    /* /CS: latch high before the pin becomes an output (never a stray select). */
    P3OUT |= CS_CAN_BIT;
    P3DIR |= CS_CAN_BIT;
    UCB0CTL1 = UCSWRST | UCSSEL_2;
    UCB0CTL0 = (uint8_t)(mode_bits[mode] | UCMSB | UCMST | UCSYNC);
    UCB0BR0 = (uint8_t)div;
    UCB0BR1 = (uint8_t)(div >> 8);
    /* The pins go to the USCI (which drives SIMO and CLK itself) before it leaves reset. */
    P3SEL |= SPI_PINS;
    UCB0CTL1 = UCSSEL_2;
    rate = clk / div;
    poll_limit = (uint16_t)(16u * div / 6u + 16u); /* 2 x 8 bits x div cycles, >= 6 a poll */
    held = -1;
    return HAL_SPI_OK;
}

uint32_t hal_spi_rate(hal_spi_bus_t bus)
{
    return (unsigned)bus < HAL_SPI_BUS_COUNT ? rate : 0u;
}

int hal_spi_transfer(hal_spi_bus_t bus, hal_spi_cs_t cs, const uint8_t *tx, uint8_t *rx, uint16_t n,
                     uint8_t flags)
{
    if ((unsigned)bus >= HAL_SPI_BUS_COUNT || (unsigned)cs >= HAL_SPI_CS_COUNT ||
        (flags & (uint8_t)~HAL_SPI_HOLD) != 0u)
        return HAL_SPI_ERR_ARG;
    if (rate == 0u || (held >= 0 && held != (int8_t)cs))
        return HAL_SPI_ERR_STATE;
    P3OUT &= (uint8_t)~CS_CAN_BIT;
    const uint16_t limit = poll_limit;
    while (n--) {
        UCB0TXBUF = tx != NULL ? *tx++ : 0u;
        uint16_t polls = limit;
        while ((IFG2 & UCB0RXIFG) == 0u) {
            if (--polls == 0u) {
                held = -1;
                P3OUT |= CS_CAN_BIT;
                return HAL_SPI_ERR_TIMEOUT;
            }
        }
        uint8_t b = UCB0RXBUF;
        if (rx != NULL)
            *rx++ = b;
    }
    if (flags & HAL_SPI_HOLD) {
        held = (int8_t)cs;
    } else {
        held = -1;
        P3OUT |= CS_CAN_BIT;
    }
    return HAL_SPI_OK;
}
