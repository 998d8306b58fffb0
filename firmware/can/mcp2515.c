/*
 * mcp2515.c - the MCP2515 driver (can/mcp2515.h, docs/can.md) over hal/spi.h.
 *
 * SPI traffic per operation (bytes on the bus, instruction and address included):
 *  - INT handler, per pass: READ CANINTF..EFLG (4); per received frame READ RX BUFFER
 *    (1 + 5 + data length; the read flag clears when /CS rises); one BIT MODIFY (4) clears
 *    the TX, ERR, MERR and WAK flags served; after an ERR or MERR flag READ TEC..REC (4)
 *    and, on an overflow, a BIT MODIFY of EFLG (4). A frame of 8 bytes alone: 4 + 14 + 4 =
 *    22 bytes.
 *  - send: WRITE TXBnCTRL..data (2 + 6 + data length), RTS (1), and a BIT MODIFY (4) of each
 *    pending buffer whose priority the new frame moves.
 */
#include "can/mcp2515.h"

#include <stddef.h>

#include "hal/irq.h"
#include "mcp2515_regs.h"

/* Passes of the INT handler before it hands back with the line still low. */
#define ISR_PASSES 4u
/* CANSTAT reads while waiting for a mode change (each READ is 3 bytes: >= 3 us at 8 MHz;
 * after a reset the oscillator start-up timer holds the part for 128 oscillator periods). */
#define MODE_POLLS 64u

/* Interrupts on INT: both receive buffers, the three transmit buffers, errors, message errors
 * (not wake-up: the driver never puts the part to sleep). */
#define INTE_MASK (MCP_RX0IF | MCP_RX1IF | MCP_TXIF | MCP_ERRIF | MCP_MERRF)

static const uint8_t reqop[MCP2515_MODE_COUNT] = {MCP_REQOP_NORMAL, MCP_REQOP_LOOPBACK,
                                                  MCP_REQOP_LISTEN};

static int xfer(const mcp2515_t *d, const uint8_t *tx, uint8_t *rx, uint16_t n, uint8_t flags)
{
    return hal_spi_transfer(d->bus, d->cs, tx, rx, n, flags) == HAL_SPI_OK ? MCP2515_OK
                                                                           : MCP2515_ERR_SPI;
}

static int read_regs(const mcp2515_t *d, uint8_t addr, uint8_t *buf, uint16_t n)
{
    if (n <= 2u) { /* one frame through a local buffer: the INT handler's reads */
        uint8_t b[4] = {MCP_READ, addr, 0u, 0u};
        if (xfer(d, b, b, (uint16_t)(2u + n), 0u) != MCP2515_OK)
            return MCP2515_ERR_SPI;
        for (uint16_t i = 0; i < n; i++)
            buf[i] = b[2u + i];
        return MCP2515_OK;
    }
    const uint8_t h[2] = {MCP_READ, addr};
    if (xfer(d, h, NULL, 2u, HAL_SPI_HOLD) != MCP2515_OK)
        return MCP2515_ERR_SPI;
    return xfer(d, NULL, buf, n, 0u);
}

static int write_regs(const mcp2515_t *d, uint8_t addr, const uint8_t *buf, uint16_t n)
{
    const uint8_t h[2] = {MCP_WRITE, addr};
    if (xfer(d, h, NULL, 2u, HAL_SPI_HOLD) != MCP2515_OK)
        return MCP2515_ERR_SPI;
    return xfer(d, buf, NULL, n, 0u);
}

static int bit_modify(const mcp2515_t *d, uint8_t addr, uint8_t mask, uint8_t val)
{
    const uint8_t b[4] = {MCP_BIT_MODIFY, addr, mask, val};
    return xfer(d, b, NULL, 4u, 0u);
}

static uint8_t popcount3(uint8_t v)
{
    return (uint8_t)((v & 1u) + ((v >> 1) & 1u) + ((v >> 2) & 1u));
}

static void add16(uint16_t *c, uint16_t n)
{
    *c = (uint16_t)(*c > 0xFFFFu - n ? 0xFFFFu : *c + n);
}

static void add32(uint32_t *c)
{
    if (*c != 0xFFFFFFFFul)
        (*c)++;
}

/* Request operating mode @p op (REQOP bits) and wait until CANSTAT shows it. */
static int request_mode(const mcp2515_t *d, uint8_t op)
{
    int rc = bit_modify(d, MCP_CANCTRL, MCP_REQOP_MASK, op);
    for (uint8_t i = 0; rc == MCP2515_OK && i < MODE_POLLS; i++) {
        uint8_t st;
        rc = read_regs(d, MCP_CANSTAT, &st, 1u);
        if (rc == MCP2515_OK && (st & MCP_REQOP_MASK) == op)
            return MCP2515_OK;
    }
    return rc != MCP2515_OK ? rc : MCP2515_ERR_DEVICE;
}

/* A standard identifier as the four identifier registers of a filter or mask (EXIDE = 0, no
 * extended bits: the data bytes of standard frames are never filtered). */
static void std_id_regs(uint16_t id, uint8_t *r)
{
    r[0] = (uint8_t)(id >> 3);
    r[1] = (uint8_t)((id & 7u) << 5);
    r[2] = 0u;
    r[3] = 0u;
}

static int write_filters(const mcp2515_t *d, const mcp2515_filters_t *f)
{
    uint8_t r[12];
    for (unsigned i = 0; i < 3u; i++)
        std_id_regs(f->filter[i], &r[4u * i]);
    int rc = write_regs(d, MCP_RXF0SIDH, r, 12u);
    for (unsigned i = 0; i < 3u; i++)
        std_id_regs(f->filter[3u + i], &r[4u * i]);
    if (rc == MCP2515_OK)
        rc = write_regs(d, MCP_RXF3SIDH, r, 12u);
    std_id_regs(f->mask[0], &r[0]);
    std_id_regs(f->mask[1], &r[4]);
    if (rc == MCP2515_OK)
        rc = write_regs(d, MCP_RXM0SIDH, r, 8u);
    uint8_t rxm = f->accept_all ? MCP_RXM_ANY : 0u;
    uint8_t c0 = (uint8_t)(rxm | MCP_BUKT), c1 = rxm;
    if (rc == MCP2515_OK)
        rc = write_regs(d, MCP_RXB0CTRL, &c0, 1u);
    if (rc == MCP2515_OK)
        rc = write_regs(d, MCP_RXB1CTRL, &c1, 1u);
    return rc;
}

static int filters_valid(const mcp2515_filters_t *f)
{
    if (f->accept_all > 1u || f->mask[0] > MCP2515_MAX_STD || f->mask[1] > MCP2515_MAX_STD)
        return 0;
    for (unsigned i = 0; i < MCP2515_RX_FILTERS; i++)
        if (f->filter[i] > MCP2515_MAX_STD)
            return 0;
    return 1;
}

/* Error state from EFLG. Entering bus-off aborts the pending frames (CANCTRL.ABAT, kept set
 * while bus-off so nothing is loaded meanwhile) and, with manual recovery, parks the
 * controller in configuration mode (it does not count its way back there); leaving bus-off
 * clears ABAT. */
static int update_state(mcp2515_t *d, uint8_t eflg)
{
    mcp2515_state_t s = (eflg & MCP_TXBO)                ? MCP2515_BUS_OFF
                        : (eflg & (MCP_TXEP | MCP_RXEP)) ? MCP2515_ERROR_PASSIVE
                                                         : MCP2515_ERROR_ACTIVE;
    int rc = MCP2515_OK;
    if (s == MCP2515_BUS_OFF && d->state != MCP2515_BUS_OFF) {
        add16(&d->stats.bus_offs, 1u);
        rc = bit_modify(d, MCP_CANCTRL, MCP_ABAT, MCP_ABAT);
        add16(&d->stats.tx_aborted, popcount3(d->pending));
        d->pending = 0u;
        if (d->manual_recovery) {
            d->held = 1u;
            d->recovering = 0u;
            if (rc == MCP2515_OK)
                rc = bit_modify(d, MCP_CANCTRL, MCP_REQOP_MASK, MCP_REQOP_CONFIG);
        } else {
            d->recovering = 1u;
        }
    } else if (s != MCP2515_BUS_OFF && d->state == MCP2515_BUS_OFF) {
        add16(&d->stats.recoveries, 1u);
        d->recovering = 0u;
        rc = bit_modify(d, MCP_CANCTRL, MCP_ABAT, 0u);
    }
    if (s == MCP2515_ERROR_PASSIVE && d->state == MCP2515_ERROR_ACTIVE)
        add16(&d->stats.error_passive, 1u);
    d->eflg = eflg;
    d->state = s;
    return rc;
}

/* EFLG, TEC and REC read now. */
static int refresh(mcp2515_t *d)
{
    uint8_t c[2], eflg;
    int rc = read_regs(d, MCP_TEC, c, 2u);
    if (rc == MCP2515_OK)
        rc = read_regs(d, MCP_EFLG, &eflg, 1u);
    if (rc != MCP2515_OK)
        return rc;
    d->tec = c[0];
    d->rec = c[1];
    return update_state(d, eflg);
}

int mcp2515_init(mcp2515_t *d, const mcp2515_config_t *cfg)
{
    mcp2515_cnf_t cnf;
    if (d == NULL || cfg == NULL)
        return MCP2515_ERR_ARG;
    d->ready = 0u;
    if (cfg->rx_cb == NULL || (unsigned)cfg->mode >= MCP2515_MODE_COUNT || cfg->tx_fifo > 1u ||
        cfg->manual_recovery > 1u || !filters_valid(&cfg->filters) ||
        mcp2515_bit_timing(cfg->osc_hz, cfg->bitrate_bps, &cnf) != MCP2515_OK)
        return MCP2515_ERR_ARG;
    d->bus = cfg->bus;
    d->cs = cfg->cs;
    d->mode = cfg->mode;
    d->rx_cb = cfg->rx_cb;
    d->tx_cb = cfg->tx_cb;
    d->arg = cfg->arg;
    d->tx_fifo = cfg->tx_fifo ? 1u : 0u;
    d->manual_recovery = cfg->manual_recovery ? 1u : 0u;
    d->held = 0u;
    d->recovering = 0u;
    d->pending = 0u;
    d->seq = 0u;
    d->eflg = 0u;
    d->tec = 0u;
    d->rec = 0u;
    d->state = MCP2515_ERROR_ACTIVE;
    d->stats = (mcp2515_stats_t){0};
    if (hal_spi_init(cfg->bus, MCP2515_SPI_MAX_HZ, HAL_SPI_MODE_0) != HAL_SPI_OK)
        return MCP2515_ERR_SPI;

    hal_irq_state_t s = hal_irq_disable();
    const uint8_t reset = MCP_RESET;
    int rc = xfer(d, &reset, NULL, 1u, 0u);
    /* After RESET the part is in configuration mode (CANSTAT.OPMOD = 100). */
    uint8_t st = 0u;
    for (uint8_t i = 0; rc == MCP2515_OK && i < MODE_POLLS; i++) {
        rc = read_regs(d, MCP_CANSTAT, &st, 1u);
        if ((st & MCP_REQOP_MASK) == MCP_REQOP_CONFIG)
            break;
    }
    if (rc == MCP2515_OK && (st & MCP_REQOP_MASK) != MCP_REQOP_CONFIG)
        rc = MCP2515_ERR_DEVICE;
    /* Configuration mode, CLKOUT off; bit timing, interrupt enables, no flags pending. */
    const uint8_t ctrl = MCP_REQOP_CONFIG;
    if (rc == MCP2515_OK)
        rc = write_regs(d, MCP_CANCTRL, &ctrl, 1u);
    const uint8_t regs[5] = {cnf.cnf3, cnf.cnf2, cnf.cnf1, INTE_MASK, 0u};
    if (rc == MCP2515_OK)
        rc = write_regs(d, MCP_CNF3, regs, 5u);
    if (rc == MCP2515_OK)
        rc = write_filters(d, &cfg->filters);
    /* The bit timing read back: a part that is absent or miswired does not echo it. */
    uint8_t back[3];
    if (rc == MCP2515_OK)
        rc = read_regs(d, MCP_CNF3, back, 3u);
    if (rc == MCP2515_OK && (back[0] != regs[0] || back[1] != regs[1] || back[2] != regs[2]))
        rc = MCP2515_ERR_DEVICE;
    if (rc == MCP2515_OK)
        rc = request_mode(d, reqop[cfg->mode]);
    if (rc == MCP2515_OK)
        d->ready = 1u;
    hal_irq_restore(s);
    return rc;
}

int mcp2515_set_mode(mcp2515_t *d, mcp2515_mode_t mode)
{
    if (d == NULL || (unsigned)mode >= MCP2515_MODE_COUNT)
        return MCP2515_ERR_ARG;
    if (!d->ready)
        return MCP2515_ERR_DEVICE;
    hal_irq_state_t s = hal_irq_disable();
    int rc = request_mode(d, reqop[mode]);
    if (rc == MCP2515_OK)
        d->mode = mode;
    hal_irq_restore(s);
    return rc;
}

/* Arbitration rank of a frame: the bits of its arbitration field in bus order (base
 * identifier, RTR or SRR, IDE, identifier extension, RTR), so that a lower key wins
 * arbitration on the bus. Built from 16-bit halves (the MSP430 has no barrel shifter). */
static uint32_t arb_key(const mcp2515_frame_t *f)
{
    uint16_t hi, lo;
    if (!f->ext) {
        hi = (uint16_t)((uint16_t)((uint16_t)f->id << 5) | (uint16_t)(f->rtr << 4));
        lo = 0u;
    } else {
        uint16_t ih = (uint16_t)(f->id >> 16), il = (uint16_t)f->id; /* id bits 28-16, 15-0 */
        hi = (uint16_t)(((ih >> 2) << 5) | 0x18u | ((ih & 3u) << 1) | (il >> 15));
        lo = (uint16_t)((uint16_t)(il << 1) | f->rtr);
    }
    return ((uint32_t)hi << 16) | lo;
}

/* Non-zero when the frame in transmit buffer @p a goes before the one in @p b: a lower key,
 * or the same key loaded earlier (ages compared modulo 256). */
static int precedes(const mcp2515_t *d, uint8_t a, uint8_t b)
{
    uint32_t ka = d->tx_key[a], kb = d->tx_key[b];
    return ka < kb || (ka == kb && (int8_t)(uint8_t)(d->tx_seq[a] - d->tx_seq[b]) < 0);
}

int mcp2515_send(mcp2515_t *d, const mcp2515_frame_t *f)
{
    if (d == NULL || f == NULL || f->ext > 1u || f->rtr > 1u || f->len > MCP2515_MAX_DATA ||
        f->id > (f->ext ? MCP2515_MAX_EXT : MCP2515_MAX_STD))
        return MCP2515_ERR_ARG;
    if (!d->ready)
        return MCP2515_ERR_DEVICE;
    if (d->mode == MCP2515_MODE_LISTEN)
        return MCP2515_ERR_MODE;
    hal_irq_state_t s = hal_irq_disable();
    int rc = MCP2515_OK;
    if (d->state == MCP2515_BUS_OFF)
        rc = refresh(d); /* the controller may have recovered by itself */
    uint8_t free_bufs = (uint8_t)(~d->pending & 7u);
    if (rc == MCP2515_OK && d->state == MCP2515_BUS_OFF)
        rc = MCP2515_ERR_BUS_OFF;
    else if (rc == MCP2515_OK && free_bufs == 0u)
        rc = MCP2515_ERR_FULL;
    if (rc != MCP2515_OK) {
        hal_irq_restore(s);
        return rc;
    }
    uint8_t n = (free_bufs & 1u) ? 0u : (free_bufs & 2u) ? 1u : 2u;
    uint8_t seq = (uint8_t)(d->seq + 1u);
    d->tx_key[n] = d->tx_fifo ? 0u : arb_key(f); /* FIFO: equal keys, the age decides */
    d->tx_seq[n] = seq;
    /* Transmit priorities: each frame's rank among the pending ones and the new one, TXP 3
     * for the first; pending buffers whose rank moves get their new TXP first. */
    uint8_t set = (uint8_t)(d->pending | (1u << n));
    uint8_t prio = 3u;
    for (uint8_t i = 0; rc == MCP2515_OK && i < MCP2515_TX_BUFS; i++) {
        if (!(set & (1u << i)))
            continue;
        uint8_t p = 3u;
        for (uint8_t j = 0; j < MCP2515_TX_BUFS; j++)
            if (j != i && (set & (1u << j)) && precedes(d, j, i))
                p--;
        if (i == n) {
            prio = p;
        } else if (p != d->tx_prio[i]) {
            rc = bit_modify(d, MCP_TXBCTRL(i), MCP_TXP, p);
            d->tx_prio[i] = p;
        }
    }
    /* TXBnCTRL (priority, no request yet), identifier, DLC and data in one WRITE. */
    uint8_t b[6 + MCP2515_MAX_DATA];
    b[0] = prio;
    if (f->ext) {
        uint16_t ih = (uint16_t)(f->id >> 16), il = (uint16_t)f->id; /* id bits 28-16, 15-0 */
        b[1] = (uint8_t)(ih >> 5);
        b[2] = (uint8_t)((uint8_t)(((ih >> 2) & 7u) << 5) | MCP_SIDL_EXIDE | (ih & 3u));
        b[3] = (uint8_t)(il >> 8);
        b[4] = (uint8_t)il;
    } else {
        uint16_t id = (uint16_t)f->id;
        b[1] = (uint8_t)(id >> 3);
        b[2] = (uint8_t)((id & 7u) << 5);
        b[3] = 0u;
        b[4] = 0u;
    }
    b[5] = (uint8_t)(f->len | (f->rtr ? MCP_DLC_RTR : 0u));
    uint8_t len = f->rtr ? 0u : f->len;
    for (uint8_t i = 0; i < len; i++)
        b[6 + i] = f->data[i];
    if (rc == MCP2515_OK)
        rc = write_regs(d, MCP_TXBCTRL(n), b, (uint16_t)(6u + len));
    const uint8_t rts = (uint8_t)MCP_RTS(n);
    if (rc == MCP2515_OK)
        rc = xfer(d, &rts, NULL, 1u, 0u);
    if (rc == MCP2515_OK) {
        d->pending |= (uint8_t)(1u << n);
        d->tx_prio[n] = prio;
        d->seq = seq;
    }
    hal_irq_restore(s);
    return rc;
}

uint8_t mcp2515_tx_free(const mcp2515_t *d)
{
    if (d == NULL || !d->ready || d->state == MCP2515_BUS_OFF)
        return 0u;
    return popcount3((uint8_t)(~d->pending & 7u));
}

/* Read receive buffer @p n with READ RX BUFFER (its RXnIF clears as /CS rises) and hand the
 * frame to the callback. */
static int read_rx(mcp2515_t *d, uint8_t n)
{
    /* the instruction, then SIDH, SIDL, EID8, EID0, DLC */
    uint8_t h[6] = {(uint8_t)MCP_READ_RXB(n), 0u, 0u, 0u, 0u, 0u};
    mcp2515_frame_t f;
    if (xfer(d, h, h, 6u, HAL_SPI_HOLD) != MCP2515_OK)
        return MCP2515_ERR_SPI;
    f.ext = (h[2] & MCP_SIDL_EXIDE) ? 1u : 0u;
    if (f.ext) {
        uint16_t ih =
            (uint16_t)((uint16_t)(h[1] << 5) | (uint16_t)((h[2] >> 5) << 2) | (h[2] & 3u));
        f.id = ((uint32_t)ih << 16) | (uint16_t)((uint16_t)(h[3] << 8) | h[4]);
        f.rtr = (h[5] & MCP_DLC_RTR) ? 1u : 0u;
    } else {
        f.id = (uint16_t)((uint16_t)(h[1] << 3) | (uint16_t)(h[2] >> 5));
        f.rtr = (h[2] & MCP_SIDL_SRR) ? 1u : 0u;
    }
    f.len = (uint8_t)(h[5] & 0x0Fu);
    if (f.len > MCP2515_MAX_DATA)
        f.len = MCP2515_MAX_DATA; /* DLC 9..15 carries 8 bytes */
    if (xfer(d, NULL, f.data, f.rtr ? 0u : f.len, 0u) != MCP2515_OK)
        return MCP2515_ERR_SPI;
    add32(&d->stats.rx_frames);
    d->rx_cb(d->arg, &f);
    return MCP2515_OK;
}

/* A message error (MERRF): a transmit error if TEC rose (8 a time), receive errors as REC rose;
 * neither (an acknowledge error while error-passive) a transmit error when frames were
 * pending, else a receive error. */
static void count_errors(mcp2515_t *d, uint8_t tec, uint8_t rec, uint8_t was_pending)
{
    uint16_t tx = tec > d->tec ? (uint16_t)((tec - d->tec + 7u) / 8u) : 0u;
    uint16_t rx = rec > d->rec ? (uint16_t)(rec - d->rec) : 0u;
    if (tx == 0u && rx == 0u) {
        if (was_pending)
            tx = 1u;
        else
            rx = 1u;
    }
    add16(&d->stats.tx_errors, tx);
    add16(&d->stats.rx_errors, rx);
}

int mcp2515_isr(mcp2515_t *d)
{
    if (d == NULL || !d->ready)
        return MCP2515_ERR_DEVICE;
    hal_irq_state_t s = hal_irq_disable();
    int rc = 1;
    for (uint8_t pass = 0; pass < ISR_PASSES && rc == 1; pass++) {
        uint8_t r[2]; /* CANINTF, EFLG */
        if (read_regs(d, MCP_CANINTF, r, 2u) != MCP2515_OK) {
            rc = MCP2515_ERR_SPI;
            break;
        }
        uint8_t intf = (uint8_t)(r[0] & INTE_MASK);
        if (intf == 0u) {
            rc = 0;
            break;
        }
        if ((intf & MCP_RX0IF) && read_rx(d, 0u) != MCP2515_OK)
            rc = MCP2515_ERR_SPI;
        if (rc == 1 && (intf & MCP_RX1IF) && read_rx(d, 1u) != MCP2515_OK)
            rc = MCP2515_ERR_SPI;
        uint8_t done = (uint8_t)((intf & MCP_TXIF) >> 2);
        uint8_t sent = (uint8_t)(done & d->pending);
        for (; sent; sent &= (uint8_t)(sent - 1u))
            add32(&d->stats.tx_frames);
        uint8_t was_pending = d->pending;
        d->pending &= (uint8_t)~done;
        if (rc == 1 && (r[1] & (MCP_RX0OVR | MCP_RX1OVR))) {
            add16(&d->stats.rx_overflows,
                  (uint16_t)(((r[1] & MCP_RX0OVR) ? 1u : 0u) + ((r[1] & MCP_RX1OVR) ? 1u : 0u)));
            if (bit_modify(d, MCP_EFLG, MCP_RX0OVR | MCP_RX1OVR, 0u) != MCP2515_OK)
                rc = MCP2515_ERR_SPI;
        }
        if (rc == 1 && (intf & (MCP_ERRIF | MCP_MERRF))) {
            uint8_t c[2];
            if (read_regs(d, MCP_TEC, c, 2u) != MCP2515_OK) {
                rc = MCP2515_ERR_SPI;
            } else {
                if (intf & MCP_MERRF)
                    count_errors(d, c[0], c[1], was_pending);
                d->tec = c[0];
                d->rec = c[1];
            }
        }
        if (rc == 1 && update_state(d, r[1]) != MCP2515_OK)
            rc = MCP2515_ERR_SPI;
        uint8_t clear = (uint8_t)(r[0] & (MCP_TXIF | MCP_ERRIF | MCP_MERRF | MCP_WAKIF));
        if (rc == 1 && clear && bit_modify(d, MCP_CANINTF, clear, 0u) != MCP2515_OK)
            rc = MCP2515_ERR_SPI;
        if (done && d->tx_cb != NULL && d->state != MCP2515_BUS_OFF)
            d->tx_cb(d->arg);
    }
    hal_irq_restore(s);
    return rc;
}

int mcp2515_poll(mcp2515_t *d)
{
    if (d == NULL || !d->ready)
        return MCP2515_ERR_DEVICE;
    hal_irq_state_t s = hal_irq_disable();
    int rc = refresh(d);
    hal_irq_restore(s);
    return rc;
}

int mcp2515_recover(mcp2515_t *d)
{
    if (d == NULL || !d->ready)
        return MCP2515_ERR_DEVICE;
    hal_irq_state_t s = hal_irq_disable();
    int rc = refresh(d);
    if (rc == MCP2515_OK && d->state != MCP2515_BUS_OFF)
        rc = MCP2515_ERR_STATE;
    if (rc == MCP2515_OK && d->held) {
        rc = request_mode(d, reqop[d->mode]);
        if (rc == MCP2515_OK) {
            d->held = 0u;
            d->recovering = 1u;
        }
    }
    hal_irq_restore(s);
    return rc;
}

uint8_t mcp2515_recovering(const mcp2515_t *d)
{
    return d != NULL && d->ready && d->state == MCP2515_BUS_OFF ? d->recovering : 0u;
}

mcp2515_state_t mcp2515_state(const mcp2515_t *d)
{
    return d != NULL && d->ready ? d->state : MCP2515_BUS_OFF;
}

void mcp2515_error_counters(const mcp2515_t *d, uint8_t *tec, uint8_t *rec)
{
    if (tec != NULL)
        *tec = d != NULL ? d->tec : 0u;
    if (rec != NULL)
        *rec = d != NULL ? d->rec : 0u;
}

const mcp2515_stats_t *mcp2515_stats(const mcp2515_t *d)
{
    return d != NULL ? &d->stats : NULL;
}
