/*
 * spi_usci_test.c - hal/spi.h on USCI_B0 (hal/msp430/spi_usci_b0.c) in mspdebug's simulator,
 * where the USCI and port 3 are plain memory, after the start-up (hal_cpu_init) chose the
 * clock on the supply the runner emulates (16 or 12 MHz, tests/target/CMakeLists.txt): the
 * register values hal_spi_init() leaves (typed from SLAU144's UCBxCTL0/UCBxCTL1 descriptions,
 * "USCI: SPI Mode", not from the HAL's header; the bit clock is BRCLK / UCBRx, BRCLK = SMCLK),
 * the pins (/CS high and an output, SIMO/SOMI/CLK selected), the argument checks, the chip
 * select around a transfer and a held frame, the timeout when the USCI never completes a byte
 * (UCB0RXIFG stays clear) and, with the flag preset, the cycles of the transfer loop itself
 * ("@cycles spi_transfer_22": 22 bytes, the SPI traffic of one received CAN frame;
 * on the chip each byte also waits 16 MCLK cycles of shifting at 8 MHz).
 */
#include <stdint.h>

#include "cy_test.h"
#include "f2618.h"
#include "hal/cpu.h"
#include "hal/spi.h"

/* SLAU144, UCBxCTL0 in SPI mode: UCCKPH bit 7, UCCKPL bit 6, UCMSB bit 5, UCMST bit 3,
 * UCMODEx bits 2-1 (00 = 3-pin), UCSYNC bit 0; UCBxCTL1: UCSSELx bits 7-6 (10 = SMCLK),
 * UCSWRST bit 0. IFG2: UCB0RXIFG bit 2. */
#define CTL0_MODE0 0xA9u /* CKPH | MSB | MST | SYNC */
#define CTL0_MODE1 0x29u /* MSB | MST | SYNC */
#define CTL0_MODE2 0xE9u /* CKPH | CKPL | MSB | MST | SYNC */
#define CTL0_MODE3 0x69u /* CKPL | MSB | MST | SYNC */
#define CTL1_RUN   0x80u
#define RXIFG_B0   0x04u

static cy_bench_stat_t st_22 = {"spi_transfer_22", 0, 0, 0};
static uint32_t smclk; /* the clock the start-up chose, from the DCO's calibration bytes */

/* SLAU144: f_bitclock = f_BRCLK / UCBRx; the HAL takes the fastest not above the request. */
static uint16_t divider(uint32_t rate)
{
    return (uint16_t)((smclk + rate - 1u) / rate);
}

static void check_reg(uint8_t got, uint8_t want, const char *what)
{
    if (got != want) {
        cy_print("# ");
        cy_print(what);
        cy_print(" = ");
        cy_print_hex16(got);
        cy_println();
    }
    cy_check(got == want, what);
}

int main(void)
{
    hal_cpu_init();
    smclk = (BCSCTL1 == CALBC1_16MHZ && DCOCTL == CALDCO_16MHZ)   ? 16000000ul
            : (BCSCTL1 == CALBC1_12MHZ && DCOCTL == CALDCO_12MHZ) ? 12000000ul
                                                                  : 0u;
    cy_check(smclk != 0u, "a calibrated clock");
    cy_print("# SMCLK ");
    cy_print_dec((int32_t)smclk);
    cy_println();
    cy_bench_init();
    P3OUT &= (uint8_t)~0x01u; /* /CS as after a power-up: an input with its latch low */
    P3DIR &= (uint8_t)~0x01u;
    P3SEL &= (uint8_t)~0x0Fu;
    IFG2 = 0x00u;

    cy_check(hal_spi_rate(HAL_SPI_BUS_B0) == 0u, "rate 0 before init");
    uint8_t tx[22], rx[22];
    cy_check(hal_spi_transfer(HAL_SPI_BUS_B0, HAL_SPI_CS_CAN, tx, rx, 1u, 0u) == HAL_SPI_ERR_STATE,
             "transfer before init");

    /* MCP2515: 10 MHz at most -> SMCLK / 2 (8 or 6 MHz), mode 0,0. */
    cy_check(hal_spi_init(HAL_SPI_BUS_B0, 10000000ul, HAL_SPI_MODE_0) == HAL_SPI_OK, "init");
    check_reg(UCB0CTL0, CTL0_MODE0, "UCB0CTL0 mode 0");
    check_reg(UCB0CTL1, CTL1_RUN, "UCB0CTL1");
    check_reg(UCB0BR0, 2u, "UCB0BR0");
    check_reg(UCB0BR1, 0u, "UCB0BR1");
    check_reg((uint8_t)(P3SEL & 0x0Fu), 0x0Eu, "P3SEL: P3.1-P3.3 to USCI_B0, P3.0 GPIO");
    check_reg((uint8_t)(P3DIR & 0x01u), 0x01u, "P3DIR: /CS output");
    check_reg((uint8_t)(P3OUT & 0x01u), 0x01u, "P3OUT: /CS high");
    cy_check(hal_spi_rate(HAL_SPI_BUS_B0) == smclk / 2u, "SMCLK / 2");

    cy_check(hal_spi_init(HAL_SPI_BUS_B0, 8000000ul, HAL_SPI_MODE_1) == HAL_SPI_OK, "mode 1");
    check_reg(UCB0CTL0, CTL0_MODE1, "UCB0CTL0 mode 1");
    cy_check(hal_spi_init(HAL_SPI_BUS_B0, 8000000ul, HAL_SPI_MODE_2) == HAL_SPI_OK, "mode 2");
    check_reg(UCB0CTL0, CTL0_MODE2, "UCB0CTL0 mode 2");
    cy_check(hal_spi_init(HAL_SPI_BUS_B0, 100000ul, HAL_SPI_MODE_3) == HAL_SPI_OK, "mode 3");
    check_reg(UCB0CTL0, CTL0_MODE3, "UCB0CTL0 mode 3");
    check_reg(UCB0BR0, (uint8_t)divider(100000ul), "UCB0BR0 for 100 kHz");
    cy_check(hal_spi_rate(HAL_SPI_BUS_B0) == 100000ul, "100 kHz");
    cy_check(hal_spi_init(HAL_SPI_BUS_B0, 300001ul, HAL_SPI_MODE_0) == HAL_SPI_OK, "300 kHz");
    cy_check(hal_spi_rate(HAL_SPI_BUS_B0) == smclk / divider(300001ul), "not above 300 kHz");
    cy_check(hal_spi_rate(HAL_SPI_BUS_B0) <= 300001ul, "not above the request");
    uint32_t slowest = (smclk + 16382u) / 16383u; /* UCBRx at most 16383 */
    cy_check(hal_spi_init(HAL_SPI_BUS_B0, slowest - 1u, HAL_SPI_MODE_0) == HAL_SPI_ERR_RATE,
             "below SMCLK / 16383");
    cy_check(hal_spi_init(HAL_SPI_BUS_B0, 0ul, HAL_SPI_MODE_0) == HAL_SPI_ERR_ARG, "rate 0");
    cy_check(hal_spi_init(HAL_SPI_BUS_COUNT, 1000000ul, HAL_SPI_MODE_0) == HAL_SPI_ERR_ARG, "bus");
    cy_check(hal_spi_init(HAL_SPI_BUS_B0, 1000000ul, HAL_SPI_MODE_COUNT) == HAL_SPI_ERR_ARG,
             "mode");
    cy_check(hal_spi_rate(HAL_SPI_BUS_B0) == smclk / divider(300001ul),
             "a refused init changes nothing");
    cy_check(hal_spi_init(HAL_SPI_BUS_B0, slowest, HAL_SPI_MODE_0) == HAL_SPI_OK, "slowest");
    check_reg(UCB0BR1, (uint8_t)(divider(slowest) >> 8), "UCB0BR1, slowest");
    check_reg(UCB0BR0, (uint8_t)divider(slowest), "UCB0BR0, slowest");
    cy_check(hal_spi_init(HAL_SPI_BUS_B0, 10000000ul, HAL_SPI_MODE_0) == HAL_SPI_OK, "again");

    cy_check(hal_spi_transfer(HAL_SPI_BUS_COUNT, HAL_SPI_CS_CAN, tx, rx, 1u, 0u) == HAL_SPI_ERR_ARG,
             "transfer: bus");
    cy_check(hal_spi_transfer(HAL_SPI_BUS_B0, HAL_SPI_CS_COUNT, tx, rx, 1u, 0u) == HAL_SPI_ERR_ARG,
             "transfer: chip select");
    cy_check(hal_spi_transfer(HAL_SPI_BUS_B0, HAL_SPI_CS_CAN, tx, rx, 1u, 0x80u) == HAL_SPI_ERR_ARG,
             "transfer: flags");

    /* The USCI never completes a byte (the simulator's USCI is memory): a timeout, /CS
     * released. */
    cy_check(hal_spi_transfer(HAL_SPI_BUS_B0, HAL_SPI_CS_CAN, tx, rx, 2u, 0u) ==
                 HAL_SPI_ERR_TIMEOUT,
             "timeout");
    check_reg((uint8_t)(P3OUT & 0x01u), 0x01u, "/CS high after a timeout");

    /* With UCB0RXIFG preset every byte completes at once: UCB0RXBUF's content comes back. */
    IFG2 = RXIFG_B0;
    UCB0RXBUF = 0x5Au;
    for (uint8_t i = 0; i < sizeof tx; i++) {
        tx[i] = (uint8_t)(0x30u + i);
        rx[i] = 0u;
    }
    cy_check(hal_spi_transfer(HAL_SPI_BUS_B0, HAL_SPI_CS_CAN, tx, rx, 3u, HAL_SPI_HOLD) ==
                 HAL_SPI_OK,
             "held transfer");
    check_reg((uint8_t)(P3OUT & 0x01u), 0x00u, "/CS low while held");
    check_reg(UCB0TXBUF, 0x32u, "the last byte sent");
    check_reg(rx[0], 0x5Au, "a byte received");
    check_reg(rx[2], 0x5Au, "the last byte received");
    cy_check(hal_spi_transfer(HAL_SPI_BUS_B0, HAL_SPI_CS_CAN, 0, 0, 2u, 0u) == HAL_SPI_OK,
             "NULL buffers: zeros out, input dropped");
    check_reg(UCB0TXBUF, 0x00u, "0x00 sent for a NULL tx");
    check_reg((uint8_t)(P3OUT & 0x01u), 0x01u, "/CS high at the end of the frame");

    for (uint8_t k = 0; k < 8u; k++)
        CY_BENCH(&st_22, hal_spi_transfer(HAL_SPI_BUS_B0, HAL_SPI_CS_CAN, tx, rx, 22u, 0u));
    cy_bench_report(&st_22); /* cycles, the same on either clock (both runs report it) */
    cy_test_end();
    return 0;
}
