/*
 * proto.c - the drive-board port protocols and their decoder (drive_proto.h).
 */
#include <stddef.h>

#include "drive/drive_proto.h"
#include "hal/irq.h"

static void put(drive_wseq_t *s, hal_drive_reg_t reg, uint8_t value)
{
    s->w[s->n].reg = (uint8_t)reg;
    s->w[s->n].value = value;
    s->n++;
}

/*
 * An 8255 transfer of @p n items: C <- 0x02, CTRL <- 0x80, per item A <- data ^ 0xFF (the
 * drive_cmd_t byte at offset pick[i]), B <- its strobe code, B <- 0x00; CTRL <- 0x90,
 * C <- 0x82.
 */
static const uint8_t load_pick[5] = {0, 2, 1, 3, 4}; /* steer[0], arc[0], steer[1], arc[1], speed */
_Static_assert(offsetof(drive_cmd_t, steer) == 0 && offsetof(drive_cmd_t, arc) == 2 &&
                   offsetof(drive_cmd_t, speed) == 4,
               "drive_cmd_t: the bytes of a load moved");
static const uint8_t load_code[5] = {DRIVE_STROBE_STEER1, DRIVE_STROBE_ARC1, DRIVE_STROBE_STEER2,
                                     DRIVE_STROBE_ARC2, DRIVE_STROBE_SPEED};

static void transfer(drive_wseq_t *s, const drive_cmd_t *cmd, uint8_t first)
{
    const uint8_t *bytes = (const uint8_t *)cmd;
    drive_write_t *w = s->w;
    w[0].reg = HAL_DRIVE_PPI_C;
    w[0].value = DRIVE_PPI_C_BEGIN;
    w[1].reg = HAL_DRIVE_PPI_CTRL;
    w[1].value = DRIVE_PPI_CTRL_OUT;
    w += 2;
    for (uint8_t i = first; i < 5u; i++, w += 3) {
        w[0].reg = HAL_DRIVE_PPI_A;
        w[0].value = (uint8_t)(bytes[load_pick[i]] ^ 0xFFu);
        w[1].reg = w[2].reg = HAL_DRIVE_PPI_B;
        w[1].value = load_code[i];
        w[2].value = 0x00u;
    }
    w[0].reg = HAL_DRIVE_PPI_CTRL;
    w[0].value = DRIVE_PPI_CTRL_REL;
    w[1].reg = HAL_DRIVE_PPI_C;
    w[1].value = DRIVE_PPI_C_DONE;
    s->n = (uint8_t)(w + 2 - s->w);
}

void drive_ppi_init(drive_wseq_t *out)
{
    out->n = 0;
    put(out, HAL_DRIVE_PPI_CTRL, DRIVE_PPI_CTRL_REL);
}

void drive_ppi_load(const drive_cmd_t *cmd, drive_wseq_t *out)
{
    transfer(out, cmd, 0);
}

void drive_ppi_speed(int8_t speed, drive_wseq_t *out)
{
    drive_cmd_t c;
    c.speed = speed;
    transfer(out, &c, 4);
}

void drive_dac_set(uint8_t angle_value, uint8_t speed_value, drive_wseq_t *out)
{
    out->n = 0;
    put(out, HAL_DRIVE_DAC_ANGLE, angle_value);
    put(out, HAL_DRIVE_DAC_SPEED, speed_value);
}

void drive_dac_outputs(uint8_t outputs, drive_wseq_t *out)
{
    out->n = 0;
    put(out, HAL_DRIVE_DIGITAL, outputs);
}

void drive_dac_start(uint8_t center, drive_wseq_t *out)
{
    out->n = 0;
    put(out, HAL_DRIVE_DIGITAL, DRIVE_OUT_DRIVE_OFF | DRIVE_OUT_STEER_OFF); /* brake on */
    put(out, HAL_DRIVE_DAC_SPEED, 128u);
    put(out, HAL_DRIVE_DAC_ANGLE, center);
    put(out, HAL_DRIVE_DIGITAL, DRIVE_OUT_DRIVE_OFF | DRIVE_OUT_STEER_OFF | DRIVE_OUT_BRAKE_REL);
    put(out, HAL_DRIVE_DIGITAL, DRIVE_OUT_DRIVE_OFF | DRIVE_OUT_BRAKE_REL);
    put(out, HAL_DRIVE_DIGITAL, DRIVE_OUT_BRAKE_REL);
}

void drive_dac_stop(uint8_t center, drive_wseq_t *out)
{
    out->n = 0;
    put(out, HAL_DRIVE_DAC_ANGLE, center);
    put(out, HAL_DRIVE_DAC_SPEED, 128u);
    put(out, HAL_DRIVE_DIGITAL, DRIVE_OUT_DRIVE_OFF | DRIVE_OUT_STEER_OFF); /* brake on */
}

void drive_port_send(const drive_wseq_t *seq)
{
    hal_irq_state_t s = hal_irq_disable();
    for (uint8_t i = 0; i < seq->n; i++)
        hal_drive_port_write((hal_drive_reg_t)seq->w[i].reg, seq->w[i].value);
    hal_irq_restore(s);
}

/* ------------------------------------------------------------------ decoder */

/* 8255 control word bits (mode-set words have bit 7 set). */
#define CW_MODE_SET 0x80u
#define CW_MODES    0x64u /* group A mode (bits 6-5), group B mode (bit 2): 0 for mode 0 */
#define CW_A_IN     0x10u
#define CW_CU_IN    0x08u
#define CW_B_IN     0x02u
#define CW_CL_IN    0x01u
#define CW_RESET    0x9Bu /* all ports input */

void drive_decoder_init(drive_decoder_t *d, uint8_t dac_center)
{
    d->ctrl = CW_RESET;
    d->a = d->b = d->c = 0;
    d->mask = 0;
    d->dac_center = dac_center;
    d->items.steer[0] = d->items.steer[1] = DRIVE_STEER_STRAIGHT;
    d->items.arc[0] = d->items.arc[1] = 0;
    d->items.speed = 0;
    d->items.pulses = 0;
    d->items.alpha[0] = d->items.alpha[1] = 0;
}

static bool fail(drive_decoder_t *d, drive_event_t *ev, drive_perr_t e)
{
    d->mask = 0;
    ev->type = DRIVE_EV_ERROR;
    ev->error = e;
    return true;
}

static fx_angle_t steer_alpha(uint8_t byte)
{
    return (fx_angle_t)((int32_t)(128 - (int32_t)byte) * (1l << 23));
}

/* Port C changed: PC7 rising commits the latched items. */
static bool port_c(drive_decoder_t *d, uint8_t v, drive_event_t *ev)
{
    uint8_t old = d->c;
    d->c = v;
    if ((old & 0x80u) || !(v & 0x80u) || d->mask == 0)
        return false;
    ev->type = d->mask == DRIVE_ITEM_ALL     ? DRIVE_EV_LOAD
               : d->mask == DRIVE_ITEM_SPEED ? DRIVE_EV_SPEED
                                             : DRIVE_EV_PARTIAL;
    ev->mask = d->mask;
    ev->cmd = d->items;
    ev->cmd.alpha[0] = steer_alpha(d->items.steer[0]);
    ev->cmd.alpha[1] = steer_alpha(d->items.steer[1]);
    d->mask = 0;
    return true;
}

bool drive_decoder_feed(drive_decoder_t *d, uint8_t reg, uint8_t value, drive_event_t *ev)
{
    ev->type = DRIVE_EV_NONE;
    ev->error = DRIVE_PERR_NONE;
    ev->mask = 0;
    ev->value = value;
    ev->alpha = 0;
    ev->cmd = d->items;
    switch (reg) {
    case HAL_DRIVE_PPI_CTRL:
        if (value & CW_MODE_SET) {
            d->ctrl = value;
            d->a = d->b = d->c = 0; /* a mode set clears the output latches */
            if (value & CW_MODES)
                return fail(d, ev, DRIVE_PERR_MODE);
            return false;
        }
        /* Bit set/reset of port C: bit (value >> 1) & 7 to (value & 1). */
        {
            uint8_t bit = (uint8_t)(1u << ((value >> 1) & 7u));
            bool upper = bit >= 0x10u;
            if (d->ctrl & (upper ? CW_CU_IN : CW_CL_IN))
                return fail(d, ev, DRIVE_PERR_PORT_INPUT);
            return port_c(d, (uint8_t)((value & 1u) ? (d->c | bit) : (d->c & ~bit)), ev);
        }
    case HAL_DRIVE_PPI_A:
        if (d->ctrl & CW_A_IN)
            return fail(d, ev, DRIVE_PERR_PORT_INPUT);
        d->a = value;
        return false;
    case HAL_DRIVE_PPI_B: {
        if (d->ctrl & CW_B_IN)
            return fail(d, ev, DRIVE_PERR_PORT_INPUT);
        uint8_t old = d->b;
        d->b = value;
        if (value == 0)
            return false;
        if (old != 0)
            return fail(d, ev, DRIVE_PERR_STROBE_HELD);
        if (d->ctrl & CW_A_IN)
            return fail(d, ev, DRIVE_PERR_NO_DATA);
        uint8_t data = (uint8_t)(d->a ^ 0xFFu);
        switch (value) {
        case DRIVE_STROBE_STEER1:
            d->items.steer[0] = data;
            d->mask |= DRIVE_ITEM_STEER1;
            break;
        case DRIVE_STROBE_ARC1:
            d->items.arc[0] = data;
            d->mask |= DRIVE_ITEM_ARC1;
            break;
        case DRIVE_STROBE_STEER2:
            d->items.steer[1] = data;
            d->mask |= DRIVE_ITEM_STEER2;
            break;
        case DRIVE_STROBE_ARC2:
            d->items.arc[1] = data;
            d->mask |= DRIVE_ITEM_ARC2;
            break;
        case DRIVE_STROBE_SPEED:
            d->items.speed = (int8_t)data;
            d->mask |= DRIVE_ITEM_SPEED;
            break;
        default:
            return fail(d, ev, DRIVE_PERR_STROBE_CODE);
        }
        return false;
    }
    case HAL_DRIVE_PPI_C:
        if ((d->ctrl & (CW_CU_IN | CW_CL_IN)) == (CW_CU_IN | CW_CL_IN))
            return fail(d, ev, DRIVE_PERR_PORT_INPUT);
        return port_c(d, value, ev);
    case HAL_DRIVE_DAC_ANGLE: {
        int32_t span = 255 - (int32_t)d->dac_center, a = 0;
        (void)fx_div_shift((int32_t)d->dac_center - (int32_t)value, span > 0 ? span : 1, 30, &a);
        ev->type = DRIVE_EV_DAC_ANGLE;
        ev->alpha = (fx_angle_t)a;
        return true;
    }
    case HAL_DRIVE_DAC_SPEED:
        ev->type = DRIVE_EV_DAC_SPEED;
        ev->cmd.speed = (int8_t)(value - 128);
        return true;
    case HAL_DRIVE_DIGITAL:
        ev->type = DRIVE_EV_OUTPUTS;
        return true;
    default:
        return fail(d, ev, DRIVE_PERR_REGISTER);
    }
}
