/*
 * can_usci_test.c - hal/can.h on the boards' own SPI path: hal/msp430/can_mcp2515.c over the
 * driver over hal/msp430/spi_usci_b0.c, in mspdebug's simulator after the start-up. With the
 * runner's MCP2515 behind USCI_B0 (tools/msp430sim.py --mcp2515: the SPI instructions on a
 * register file, no CAN bus) hal_can_init() must succeed and leave the data sheet's bit timing
 * for 500 kbit/s from 16 MHz in CNF1-3, and a frame sent must sit in TXB0 with its request set
 * (nothing takes it off the bus); read back here over hal/spi.h with the READ instruction
 * (DS20001801 Table 12-1). Without it (the simulator's USCI does not shift) the controller
 * does not answer: HAL_CAN_E_HARDWARE, and the instance stays unusable. The image prints
 * "can init <rc>"; ctest expects 0 or -6 (tests/target/CMakeLists.txt).
 */
#include <stdint.h>

#include "cy_test.h"
#include "hal/can.h"
#include "hal/cpu.h"
#include "hal/irq.h"
#include "hal/spi.h"

static uint16_t n_rx;

static void on_rx(void *arg, const hal_can_frame_t *f)
{
    (void)arg;
    (void)f;
    n_rx++;
}

/* READ (0x03) of @p n registers from @p addr over the SPI bus, as the data sheet's Figure 12-2. */
static void read_regs(uint8_t addr, uint8_t *out, uint8_t n)
{
    uint8_t b[2 + 8] = {0x03u, addr};
    cy_check(hal_spi_transfer(HAL_SPI_BUS_B0, HAL_SPI_CS_CAN, b, b, (uint16_t)(2u + n), 0u) ==
                 HAL_SPI_OK,
             "READ");
    for (uint8_t i = 0; i < n; i++)
        out[i] = b[2u + i];
}

int main(void)
{
    hal_cpu_init();
    hal_can_config_t cfg = {500000ul, {{0x100, 0x700}, {0, 0}}, 1u, 0u, on_rx, 0};
    int rc = hal_can_init(0, &cfg);
    cy_print("can init ");
    cy_print_dec(rc);
    cy_println();
    hal_can_frame_t f = {0x123, 2, {0xAB, 0xCD}};
    if (rc != 0) {
        cy_check(rc == HAL_CAN_E_HARDWARE, "a controller that does not answer");
        cy_check(hal_can_send(0, &f) == HAL_CAN_E_STATE, "no sending without a controller");
        cy_check(hal_can_tx_room(0) == 0u, "no room without a controller");
        cy_test_end();
        return 0;
    }
    hal_irq_enable();
    /* CNF3, CNF2, CNF1 at 0x28-0x2A: 16 MHz / (2 (BRP + 1) (1 + PropSeg + PS1 + PS2)). */
    uint8_t c[3];
    read_regs(0x28u, c, 3u);
    uint32_t n = 1u + (c[1] & 7u) + 1u + ((c[1] >> 3) & 7u) + 1u + (c[0] & 7u) + 1u;
    cy_check(16000000ul / (2u * ((c[2] & 0x3Fu) + 1u) * n) == 500000ul, "500 kbit/s");
    cy_check((c[1] & 0x80u) != 0u, "BTLMODE");
    uint8_t st;
    read_regs(0x0Eu, &st, 1u);
    cy_check((st & 0xE0u) == 0x00u, "normal mode");
    hal_can_status_t s;
    cy_check(hal_can_status(0, &s) == 0 && s.state == HAL_CAN_ERROR_ACTIVE && s.tec == 0u,
             "error-active");
    cy_check(hal_can_send(0, &f) == 0, "send");
    cy_check(hal_can_tx_room(0) == HAL_CAN_TX_QUEUE - 1u, "one frame pending");
    /* TXB0CTRL (0x30): TXREQ (bit 3); TXB0SIDH/SIDL: 0x123 = SID10-3 0x24, SID2-0 011. */
    uint8_t t[8];
    read_regs(0x30u, t, 8u);
    cy_check((t[0] & 0x08u) != 0u, "TXREQ");
    cy_check(t[1] == 0x24u && t[2] == 0x60u, "identifier");
    cy_check(t[5] == 2u && t[6] == 0xABu && t[7] == 0xCDu, "DLC and data");
    cy_check(n_rx == 0u, "nothing received (no bus)");
    cy_test_end();
    return 0;
}
