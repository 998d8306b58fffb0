/*
 * cpu.c - start-up of the MSP430F2618 (docs/hardware.md): every pin to its reset-safe state,
 * then the fastest calibrated clock the supply allows.
 *
 * Pins: per port the output latch first, then the function select, then the direction, so
 * that no pin ever drives a level nobody chose (PxOUT is undefined after power-up) and no
 * peripheral pin is driven as a plain output before its function is selected. Inputs (the
 * receive lines, the capture and pulse inputs, the MCP2515's SOMI and /INT) are never made
 * outputs: they keep their reset state until their driver selects them.
 *
 * Clock: SLAS541's recommended operating conditions allow MCLK = 16 MHz only at
 * VCC >= 3.3 V (12 MHz at 2.7 V). The supply voltage supervisor checks the supply against
 * its 3.35 V level before the DCO goes to the calibrated 16 MHz, else against 2.8 V for the
 * calibrated 12 MHz; below that the board stops (HAL_FAULT_SUPPLY_LOW). The SVS stays on at
 * the chosen level with PORON: a supply that sags below it later resets the part, which then
 * chooses again. A part whose calibration bytes were erased (0xFF) stops with
 * HAL_FAULT_CLOCK_UNCALIBRATED instead of running at the reset DCO's ~1 MHz with every baud
 * rate and millisecond wrong.
 */
#include "hal/cpu.h"

#include "cy_clock.h"
#include "f2618.h"
#include "hal/fault.h"

/* Busy-wait loops after switching the SVS on: 300 x 3 cycles, 0.9 ms at the ~1 MHz reset
 * DCO, longer than the SVS's turn-on delay t_d(SVSon) of SLAS541. */
#define SVS_SETTLE_LOOPS 300u

/* A calibrated setting: the SVS level the supply must clear, the calibration bytes and the
 * clock they give (UART divisors for 115200 baud from SLAU144's USCI baud-rate table). */
typedef struct {
    cy_clock_t clock;
    uint8_t vld;
    volatile const uint8_t *bc1;
    volatile const uint8_t *dco;
} cy_clock_plan_t;

static const cy_clock_plan_t plans[] = {
    {{16000000ul, 16000u, 138u, 0u, 7u << 1}, VLD_3V35, &CALBC1_16MHZ, &CALDCO_16MHZ},
    {{12000000ul, 12000u, 104u, 0u, 1u << 1}, VLD_2V8, &CALBC1_12MHZ, &CALDCO_12MHZ},
};

/* The reset DCO (RSELx = 7, DCOx = 3 after a PUC; SLAU144 basic clock module+), taken as
 * 1 MHz: the fault text of an uncalibrated part may come out garbled at 115200 baud. */
static const cy_clock_t reset_clock = {1000000ul, 1000u, 8u, 0u, 6u << 1};
const cy_clock_t *cy_clock = &reset_clock;

/* Port latches, function selects and directions after start-up (docs/hardware.md). */
static void pins_init(void)
{
    P1OUT = 0x00u; /* P1.3 unused: low */
    P1DIR = 0x08u; /* P1.0-P1.2 capture inputs, P1.4-P1.7 pulse inputs */
    P2OUT = 0x02u; /* P2.1 coordinate request idle high */
    P2DIR = 0xFAu; /* P2.0 delta-S and P2.2 MCP2515 /INT inputs; P2.3-P2.7 unused: low */
    P3OUT = 0x01u; /* P3.0 MCP2515 /CS high (deselected), P3.1 SIMO and P3.3 UCLK low */
    P3SEL = 0xF0u; /* P3.4/P3.5 USCI_A0 (console), P3.6/P3.7 USCI_A1 (position receiver) */
    P3DIR = 0x0Bu; /* P3.2 SOMI input */
    P4OUT = 0x00u; /* the drive port's data bus, idle low */
    P4DIR = 0xFFu;
    P5OUT = 0x08u; /* P5.0-P5.2 bus address low, P5.3 /WR high; P5.4-P5.7 unused: low */
    P5DIR = 0xFFu;
    P6OUT = 0x00u; /* unused: low */
    P6DIR = 0xFFu;
}

/* Non-zero when the SVS finds the supply above level @p vld (SVSOP low). */
static uint8_t supply_clears(uint8_t vld)
{
    SVSCTL = vld;
    uint16_t n = SVS_SETTLE_LOOPS;
    __asm__ volatile("1: dec %0\n\tjnz 1b" : "+r"(n));
    return (SVSCTL & SVSOP) == 0u;
}

void hal_cpu_init(void)
{
    WDTCTL = WDTPW | WDTHOLD;
    pins_init();
    for (unsigned i = 0; i < sizeof plans / sizeof plans[0]; i++)
        if (*plans[i].bc1 == 0xFFu || *plans[i].dco == 0xFFu)
            hal_fault(HAL_FAULT_CLOCK_UNCALIBRATED);
    const cy_clock_plan_t *p = plans;
    while (!supply_clears(p->vld))
        if (++p == plans + sizeof plans / sizeof plans[0]) {
            SVSCTL = 0u;
            hal_fault(HAL_FAULT_SUPPLY_LOW);
        }
    SVSCTL = (uint8_t)(p->vld | PORON);
    DCOCTL = 0u; /* the lowest DCO tap while the range changes (SLAU144) */
    BCSCTL1 = *p->bc1;
    DCOCTL = *p->dco;
    BCSCTL2 = 0u; /* MCLK = SMCLK = DCO, no dividers */
    cy_clock = &p->clock;
}

void hal_cpu_idle(void) {}

void hal_cpu_wake(void) {}
