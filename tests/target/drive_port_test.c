/*
 * drive_port_test.c - the drive bus of hal/msp430/drive_port.c and the delta-S line (D1) on
 * the MSP430 image: pin set-up, data on P4 and the register address on P5 after each write
 * with /WR back high, a whole 8255 load, and the delta-S pulse counted by drive_ds_handler
 * through the Port 2 ISR (its cost goes to the cycle report as isr_delta_s).
 */
#include <stdint.h>

#include "cy_test.h"
#include "drive/drive_proto.h"
#include "drive/drive_seq.h"
#include "f2618.h"
#include "hal/drive_port.h"
#include "hal/irq.h"

static drive_ds_t ds;
static cy_bench_stat_t st_ds = {"isr_delta_s", 0, 0, 0};

int main(void)
{
    cy_bench_init();
    hal_drive_port_init();
    cy_check(P4DIR == 0xFFu, "P4 drives the data bus");
    cy_check((P5DIR & 0x0Fu) == 0x0Fu, "P5.0-P5.3 drive address and /WR");
    cy_check((P5OUT & 0x08u) != 0, "/WR idles high");
    for (uint8_t reg = 0; reg < HAL_DRIVE_REG_COUNT; reg++) {
        uint8_t v = (uint8_t)(0x5Au ^ (reg * 37u));
        hal_drive_port_write((hal_drive_reg_t)reg, v);
        cy_check(P4OUT == v, "data on P4");
        cy_check((P5OUT & 0x07u) == reg, "register address on P5.0-P5.2");
        cy_check((P5OUT & 0x08u) != 0, "/WR released");
    }
    uint8_t before = P4OUT;
    hal_drive_port_write((hal_drive_reg_t)7, 0x11u);
    cy_check(P4OUT == before, "an unknown register is not written");

    drive_cmd_t cmd = {{0x9C, 0x6E}, {0xAA, 0x10}, 40, 2, {0, 0}};
    drive_wseq_t w;
    drive_ppi_load(&cmd, &w);
    drive_port_send(&w);
    cy_check(P4OUT == 0x82u && (P5OUT & 0x07u) == HAL_DRIVE_PPI_C, "a load ends with C <- 0x82");
    cy_check(hal_irq_enabled() == 0, "interrupts stay as they were");

    /* delta-S: P2.0's flag set by software with interrupts off, then the ISR runs at once. */
    cy_check(drive_ds_init(&ds) == 0, "delta-S line registered");
    for (uint8_t i = 0; i < 8u; i++) {
        cy_dint();
        P2IFG |= 0x01u;
        uint16_t t0 = cy_bench_now();
        cy_eint();
        uint16_t t1 = cy_bench_now();
        cy_dint();
        cy_bench_add(&st_ds, (uint16_t)(t1 - t0 - cy_bench_overhead));
    }
    cy_check(drive_ds_take(&ds) == 8u, "eight pulses counted");
    cy_check(drive_ds_take(&ds) == 0u, "and taken");
    cy_bench_report(&st_ds);
    cy_test_end();
    return 0;
}
