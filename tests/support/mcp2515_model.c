/*
 * mcp2515_model.c - the MCP2515 register model (mcp2515_model.h). Its register addresses and
 * bits are typed here from DS20001801 on their own, not shared with the driver
 * (firmware/can), so that the tests of the driver against the model compare two readings of
 * the data sheet.
 */
#include "mcp2515_model.h"

#include <stddef.h>

/* Table 12-1 */
enum {
    I_WRITE = 0x02,
    I_READ = 0x03,
    I_BIT_MODIFY = 0x05,
    I_READ_STATUS = 0xA0,
    I_RX_STATUS = 0xB0,
    I_RESET = 0xC0,
};

/* Table 11-1 */
enum {
    R_BFPCTRL = 0x0C,
    R_TXRTSCTRL = 0x0D,
    R_CANSTAT = 0x0E,
    R_CANCTRL = 0x0F,
    R_TEC = 0x1C,
    R_REC = 0x1D,
    R_CNF3 = 0x28,
    R_CNF2 = 0x29,
    R_CNF1 = 0x2A,
    R_CANINTE = 0x2B,
    R_CANINTF = 0x2C,
    R_EFLG = 0x2D,
    R_TXB0CTRL = 0x30,
    R_RXB0CTRL = 0x60,
    R_RXB1CTRL = 0x70,
};

/* CANINTE / CANINTF (Registers 7-1, 7-2) */
#define F_RX0     0x01u
#define F_RX1     0x02u
#define F_TX0     0x04u
#define F_ERR     0x20u
#define F_WAK     0x40u
#define F_MERR    0x80u
/* EFLG (Register 6-3) */
#define E_RX1OVR  0x80u
#define E_RX0OVR  0x40u
#define E_TXBO    0x20u
#define E_TXEP    0x10u
#define E_RXEP    0x08u
#define E_TXWAR   0x04u
#define E_RXWAR   0x02u
#define E_EWARN   0x01u
/* TXBnCTRL (Register 3-1) */
#define T_ABTF    0x40u
#define T_MLOA    0x20u
#define T_TXERR   0x10u
#define T_TXREQ   0x08u
/* CANCTRL (Register 10-1), CANSTAT (Register 10-2) */
#define C_ABAT    0x10u
#define OP_NORMAL 0u
#define OP_SLEEP  1u
#define OP_LOOP   2u
#define OP_LISTEN 3u
#define OP_CONFIG 4u
/* RXBnCTRL (Registers 4-1, 4-2), RXBnSIDL (4-5), RXBnDLC (4-8) */
#define X_RXRTR   0x08u
#define X_BUKT    0x04u
#define X_BUKT1   0x02u
#define S_SRR     0x10u
#define S_IDE     0x08u
#define D_RTR     0x40u

static uint8_t opmode(const mcp2515_model_t *m)
{
    return (uint8_t)(m->reg[R_CANSTAT] >> 5);
}

static uint8_t canonical(uint8_t addr)
{
    addr &= 0x7Fu;
    if ((addr & 0x0Fu) == 0x0Eu)
        return R_CANSTAT;
    if ((addr & 0x0Fu) == 0x0Fu)
        return R_CANCTRL;
    return addr;
}

/* Transmit buffer (0..2) an address belongs to, or -1. */
static int tx_buffer_of(uint8_t a)
{
    return (a >= 0x30u && a <= 0x5Du && (a & 0x0Fu) <= 0x0Du) ? (int)((a >> 4) - 3u) : -1;
}

static int config_only(uint8_t a)
{
    return (a <= 0x0Bu) || (a >= 0x10u && a <= 0x1Bu) || a == R_TXRTSCTRL ||
           (a >= 0x20u && a <= 0x27u) || a == R_CNF3 || a == R_CNF2 || a == R_CNF1;
}

/* Bits the MCU may write at @p a (read-only and unimplemented bits excluded). */
static uint8_t writable(uint8_t a)
{
    if (a == R_CANCTRL)
        return 0xFFu;
    if (a == R_CANSTAT || a == R_TEC || a == R_REC)
        return 0x00u;
    if (a <= 0x0Bu || (a >= 0x10u && a <= 0x1Bu)) /* RXFnSIDL: SID2-0, EXIDE, EID17-16 */
        return (a & 3u) == 1u ? 0xEBu : 0xFFu;
    if (a == R_BFPCTRL)
        return 0x3Fu;
    if (a == R_TXRTSCTRL)
        return 0x07u;             /* B2RTSM..B0RTSM; the pin states are read-only */
    if (a >= 0x20u && a <= 0x27u) /* RXMnSIDL: SID2-0, EID17-16 */
        return (a & 3u) == 1u ? 0xE3u : 0xFFu;
    if (a == R_CNF3)
        return 0xC7u;
    if (a == R_CNF2 || a == R_CNF1 || a == R_CANINTE || a == R_CANINTF)
        return 0xFFu;
    if (a == R_EFLG)
        return E_RX1OVR | E_RX0OVR;
    if (tx_buffer_of(a) >= 0) {
        switch (a & 0x0Fu) {
        case 0x0u:
            return T_TXREQ | 0x03u; /* TXREQ, TXP1-0 */
        case 0x2u:
            return 0xEBu; /* SID2-0, EXIDE, EID17-16 */
        case 0x5u:
            return 0x4Fu; /* RTR, DLC3-0 */
        default:
            return 0xFFu;
        }
    }
    if (a == R_RXB0CTRL)
        return 0x64u; /* RXM1-0, BUKT */
    if (a == R_RXB1CTRL)
        return 0x60u; /* RXM1-0 */
    return 0x00u;     /* receive buffers: read-only */
}

/* Registers BIT MODIFY acts on (the shaded cells of Table 11-1). */
static int bit_modifiable(uint8_t a)
{
    return a == R_BFPCTRL || a == R_TXRTSCTRL || a == R_CANCTRL || a == R_CNF3 || a == R_CNF2 ||
           a == R_CNF1 || a == R_CANINTE || a == R_CANINTF || a == R_EFLG || a == R_TXB0CTRL ||
           a == R_TXB0CTRL + 0x10u || a == R_TXB0CTRL + 0x20u || a == R_RXB0CTRL || a == R_RXB1CTRL;
}

/* EFLG's error state bits from the counters; ERRIF when any of them changes. */
static void error_state(mcp2515_model_t *m)
{
    uint8_t e = 0u;
    if (m->tec >= 96u || m->rec >= 96u)
        e |= E_EWARN;
    if (m->rec >= 96u)
        e |= E_RXWAR;
    if (m->tec >= 96u)
        e |= E_TXWAR;
    if (m->rec >= 128u)
        e |= E_RXEP;
    if (m->tec >= 128u)
        e |= E_TXEP;
    if (m->bus_off)
        e |= E_TXBO;
    uint8_t old = m->reg[R_EFLG];
    if ((old & 0x3Fu) != e)
        m->reg[R_CANINTF] |= F_ERR;
    m->reg[R_EFLG] = (uint8_t)((old & (E_RX1OVR | E_RX0OVR)) | e);
    m->reg[R_TEC] = m->tec > 255u ? 255u : (uint8_t)m->tec;
    m->reg[R_REC] = m->rec;
}

static void overflow(mcp2515_model_t *m, uint8_t bit)
{
    m->reg[R_EFLG] |= bit;
    m->reg[R_CANINTF] |= F_ERR;
}

static void power_on(mcp2515_model_t *m)
{
    for (unsigned a = 0; a < sizeof m->reg; a++)
        m->reg[a] = 0u;
    m->reg[R_CANCTRL] = 0x87u; /* REQOP = configuration, CLKEN, CLKPRE = /8 */
    m->reg[R_CANSTAT] = 0x80u; /* OPMOD = configuration */
    m->tec = 0u;
    m->rec = 0u;
    m->bus_off = 0u;
    m->idle_sequences = 0u;
}

void mcp2515_model_init(mcp2515_model_t *m, mcp2515_model_bus_cb_t bus, void *arg)
{
    *m = (mcp2515_model_t){0};
    m->bus = bus;
    m->bus_arg = arg;
    power_on(m);
}

static void abort_all(mcp2515_model_t *m)
{
    for (unsigned n = 0; n < 3u; n++) {
        uint8_t *c = &m->reg[R_TXB0CTRL + 0x10u * n];
        if (*c & T_TXREQ)
            *c = (uint8_t)((*c & (uint8_t)~T_TXREQ) | T_ABTF);
    }
}

/* A write of @p v by the MCU to (canonical) address @p a, with its side effects. */
static void write_reg(mcp2515_model_t *m, uint8_t a, uint8_t v)
{
    if (config_only(a) && opmode(m) != OP_CONFIG) {
        m->violations++;
        return;
    }
    int txb = tx_buffer_of(a);
    if (txb >= 0 && (a & 0x0Fu) != 0u && (m->reg[R_TXB0CTRL + 0x10u * (unsigned)txb] & T_TXREQ)) {
        m->violations++; /* section 3.1: TXREQ must be clear before the buffer is written */
        return;
    }
    uint8_t w = writable(a);
    uint8_t old = m->reg[a];
    uint8_t nv = (uint8_t)((old & (uint8_t)~w) | (v & w));
    if (a == R_CANCTRL) {
        m->reg[a] = nv;
        uint8_t req = (uint8_t)(nv >> 5);
        if (req <= OP_CONFIG)
            m->reg[R_CANSTAT] = (uint8_t)((req << 5) | (m->reg[R_CANSTAT] & 0x1Fu));
        if ((nv & C_ABAT) && !(old & C_ABAT))
            abort_all(m);
        return;
    }
    if (txb >= 0 && (a & 0x0Fu) == 0u) {
        if ((nv & T_TXREQ) && !(old & T_TXREQ))
            nv &= (uint8_t) ~(T_ABTF | T_MLOA | T_TXERR);
        else if (!(nv & T_TXREQ) && (old & T_TXREQ))
            nv |= T_ABTF; /* the MCU aborted the pending frame */
    }
    m->reg[a] = nv;
}

/* Interrupt code of CANSTAT: the highest-priority enabled flag (Register 10-2). */
static uint8_t icod(const mcp2515_model_t *m)
{
    uint8_t f = (uint8_t)(m->reg[R_CANINTF] & m->reg[R_CANINTE]);
    static const uint8_t order[7] = {F_ERR, F_WAK, F_TX0, F_TX0 << 1, F_TX0 << 2, F_RX0, F_RX1};
    for (uint8_t i = 0; i < 7u; i++)
        if (f & order[i])
            return (uint8_t)(i + 1u);
    return 0u;
}

static uint8_t read_reg(const mcp2515_model_t *m, uint8_t a)
{
    if (a == R_CANSTAT)
        return (uint8_t)((m->reg[R_CANSTAT] & 0xE0u) | (uint8_t)(icod(m) << 1));
    return m->reg[a];
}

uint8_t mcp2515_model_peek(const mcp2515_model_t *m, uint8_t addr)
{
    return read_reg(m, canonical(addr));
}

uint8_t mcp2515_model_int(const mcp2515_model_t *m)
{
    return (m->reg[R_CANINTF] & m->reg[R_CANINTE]) ? 0u : 1u;
}

static uint8_t read_status(const mcp2515_model_t *m)
{
    uint8_t f = m->reg[R_CANINTF];
    uint8_t s = (uint8_t)(f & (F_RX0 | F_RX1));
    for (unsigned n = 0; n < 3u; n++) {
        if (m->reg[R_TXB0CTRL + 0x10u * n] & T_TXREQ)
            s |= (uint8_t)(0x04u << (2u * n));
        if (f & (F_TX0 << n))
            s |= (uint8_t)(0x08u << (2u * n));
    }
    return s;
}

static uint8_t rx_status(const mcp2515_model_t *m)
{
    uint8_t f = m->reg[R_CANINTF] & (F_RX0 | F_RX1);
    if (f == 0u)
        return 0u;
    uint8_t s = (uint8_t)(f << 6);
    uint8_t base = (f & F_RX0) ? R_RXB0CTRL : R_RXB1CTRL; /* RXB0 first */
    if (m->reg[base + 2u] & S_IDE)
        s |= 0x10u;
    if (m->reg[base] & X_RXRTR)
        s |= 0x08u;
    if (base == R_RXB0CTRL) {
        s |= (uint8_t)(m->reg[base] & 1u);
    } else {
        uint8_t hit = (uint8_t)(m->reg[base] & 7u);
        s |= hit <= 1u ? (uint8_t)(6u + hit) : hit; /* 110, 111: rolled over from RXB0 */
    }
    return s;
}

void mcp2515_model_select(mcp2515_model_t *m)
{
    m->selected = 1u;
    m->phase = 0u;
    m->clear_on_deselect = 0u;
    m->reset_on_deselect = 0u;
}

static void start_instruction(mcp2515_model_t *m, uint8_t b)
{
    static const uint8_t rxb_addr[4] = {0x61u, 0x66u, 0x71u, 0x76u};
    static const uint8_t txb_addr[6] = {0x31u, 0x36u, 0x41u, 0x46u, 0x51u, 0x56u};
    m->instr = b;
    if (b == I_RESET) {
        m->reset_on_deselect = 1u;
    } else if ((b & 0xF9u) == 0x90u) { /* READ RX BUFFER 1001 0nm0 */
        uint8_t nm = (uint8_t)((b >> 1) & 3u);
        m->addr = rxb_addr[nm];
        m->clear_on_deselect = (nm & 2u) ? F_RX1 : F_RX0;
    } else if ((b & 0xF8u) == 0x40u && (b & 7u) < 6u) { /* LOAD TX BUFFER 0100 0abc */
        m->addr = txb_addr[b & 7u];
    } else if ((b & 0xF8u) == 0x80u) { /* RTS 1000 0nnn */
        for (uint8_t n = 0; n < 3u; n++)
            if (b & (1u << n))
                write_reg(m, (uint8_t)(R_TXB0CTRL + 0x10u * n),
                          (uint8_t)(m->reg[R_TXB0CTRL + 0x10u * n] | T_TXREQ));
    }
}

uint8_t mcp2515_model_exchange(mcp2515_model_t *m, uint8_t mosi)
{
    if (!m->selected)
        return 0xFFu;
    m->spi_bytes++;
    uint8_t phase = m->phase;
    if (m->phase < 255u)
        m->phase++;
    if (phase == 0u) {
        start_instruction(m, mosi);
        return 0xFFu;
    }
    uint8_t out = 0xFFu;
    uint8_t i = m->instr;
    if (i == I_READ || i == I_WRITE || i == I_BIT_MODIFY) {
        if (phase == 1u) {
            m->addr = (uint8_t)(mosi & 0x7Fu);
            return 0xFFu;
        }
    }
    if (i == I_READ || (i & 0xF9u) == 0x90u) {
        out = read_reg(m, canonical(m->addr));
        m->addr = (uint8_t)((m->addr + 1u) & 0x7Fu);
    } else if (i == I_WRITE || ((i & 0xF8u) == 0x40u && (i & 7u) < 6u)) {
        write_reg(m, canonical(m->addr), mosi);
        m->addr = (uint8_t)((m->addr + 1u) & 0x7Fu);
    } else if (i == I_BIT_MODIFY) {
        if (phase == 2u) {
            m->mask = mosi;
        } else if (phase == 3u) {
            uint8_t a = canonical(m->addr);
            uint8_t mask = bit_modifiable(a) ? m->mask : 0xFFu;
            write_reg(m, a, (uint8_t)((m->reg[a] & (uint8_t)~mask) | (mosi & mask)));
        }
    } else if (i == I_READ_STATUS) {
        out = read_status(m);
    } else if (i == I_RX_STATUS) {
        out = rx_status(m);
    }
    return out;
}

void mcp2515_model_deselect(mcp2515_model_t *m)
{
    if (!m->selected)
        return;
    m->selected = 0u;
    if (m->reset_on_deselect)
        power_on(m);
    else
        m->reg[R_CANINTF] &= (uint8_t)~m->clear_on_deselect;
}

/* Does filter @p fn (0..5) with mask @p mn (0, 1) accept @p f under receive mode @p rxm? */
static int filter_hit(const mcp2515_model_t *m, uint8_t fn, uint8_t mn, uint8_t rxm,
                      const mcp2515_model_frame_t *f)
{
    const uint8_t *fr = &m->reg[fn < 3u ? 4u * fn : 0x10u + 4u * (fn - 3u)];
    const uint8_t *mr = &m->reg[0x20u + 4u * mn];
    uint16_t fsid = (uint16_t)((fr[0] << 3) | (fr[1] >> 5));
    uint16_t msid = (uint16_t)((mr[0] << 3) | (mr[1] >> 5));
    uint32_t feid = ((uint32_t)(fr[1] & 3u) << 16) | ((uint32_t)fr[2] << 8) | fr[3];
    uint32_t meid = ((uint32_t)(mr[1] & 3u) << 16) | ((uint32_t)mr[2] << 8) | mr[3];
    if (rxm == 1u && f->ext)
        return 0; /* standard frames only */
    if (rxm == 2u && !f->ext)
        return 0; /* extended frames only */
    if (rxm == 0u && ((fr[1] & S_IDE) != 0u) != (f->ext != 0u))
        return 0; /* EXIDE: the filter applies to one frame format */
    uint16_t sid = (uint16_t)(f->ext ? (f->id >> 18) & 0x7FFu : f->id & 0x7FFu);
    if ((fsid ^ sid) & msid)
        return 0;
    if (f->ext)
        return ((feid ^ (f->id & 0x3FFFFu)) & meid) == 0u;
    if (rxm == 1u)
        return 1; /* the extended filter bits are ignored for standard frames */
    uint8_t n = f->rtr ? 0u : (f->dlc > 8u ? 8u : f->dlc);
    uint16_t d = (uint16_t)(((n > 0u ? f->data[0] : 0u) << 8) | (n > 1u ? f->data[1] : 0u));
    return ((feid ^ d) & meid & 0xFFFFu) == 0u;
}

/* The lowest filter of receive buffer @p b that accepts @p f, or -1 (RXM = 11: 0). */
static int buffer_hit(const mcp2515_model_t *m, uint8_t b, const mcp2515_model_frame_t *f)
{
    uint8_t rxm = (uint8_t)((m->reg[b ? R_RXB1CTRL : R_RXB0CTRL] >> 5) & 3u);
    if (rxm == 3u)
        return b ? 2 : 0;
    uint8_t first = b ? 2u : 0u, last = b ? 5u : 1u;
    for (uint8_t fn = first; fn <= last; fn++)
        if (filter_hit(m, fn, b, rxm, f))
            return fn;
    return -1;
}

/* Load @p f into receive buffer @p b, accepted by filter @p hit. */
static void load(mcp2515_model_t *m, uint8_t b, int hit, const mcp2515_model_frame_t *f)
{
    uint8_t *r = &m->reg[b ? R_RXB1CTRL : R_RXB0CTRL];
    if (f->ext) {
        r[1] = (uint8_t)(f->id >> 21);
        r[2] = (uint8_t)((((f->id >> 18) & 7u) << 5) | S_IDE | ((f->id >> 16) & 3u));
        r[3] = (uint8_t)(f->id >> 8);
        r[4] = (uint8_t)f->id;
        r[5] = (uint8_t)((f->rtr ? D_RTR : 0u) | (f->dlc & 0x0Fu));
    } else {
        r[1] = (uint8_t)(f->id >> 3);
        r[2] = (uint8_t)(((f->id & 7u) << 5) | (f->rtr ? S_SRR : 0u));
        r[3] = 0u;
        r[4] = 0u;
        r[5] = (uint8_t)(f->dlc & 0x0Fu);
    }
    if (!f->rtr) {
        uint8_t n = f->dlc > 8u ? 8u : f->dlc;
        for (uint8_t i = 0; i < n; i++)
            r[6 + i] = f->data[i];
    }
    uint8_t ctrl = (uint8_t)(r[0] & (b ? 0x60u : 0x64u)); /* keep RXM (and RXB0's BUKT) */
    if (f->rtr)
        ctrl |= X_RXRTR;
    if (b == 0u)
        ctrl = (uint8_t)(ctrl | ((ctrl & X_BUKT) ? X_BUKT1 : 0u) | (uint8_t)(hit & 1));
    else
        ctrl |= (uint8_t)(hit & 7);
    r[0] = ctrl;
    m->reg[R_CANINTF] |= b ? F_RX1 : F_RX0;
}

/* The receive flow (Figure 4-2): RXB0's filters first, rollover, then RXB1's. */
static int deliver(mcp2515_model_t *m, const mcp2515_model_frame_t *f)
{
    int hit = buffer_hit(m, 0u, f);
    if (hit >= 0) {
        if (!(m->reg[R_CANINTF] & F_RX0)) {
            load(m, 0u, hit, f);
            return MCP2515_MODEL_RX_BUF0;
        }
        if (!(m->reg[R_RXB0CTRL] & X_BUKT)) {
            overflow(m, E_RX0OVR);
            return MCP2515_MODEL_RX_OVERFLOW;
        }
        if (!(m->reg[R_CANINTF] & F_RX1)) {
            load(m, 1u, hit, f); /* FILHIT 000/001 in RXB1: rolled over */
            return MCP2515_MODEL_RX_BUF1;
        }
        overflow(m, E_RX1OVR);
        return MCP2515_MODEL_RX_OVERFLOW;
    }
    hit = buffer_hit(m, 1u, f);
    if (hit < 0)
        return MCP2515_MODEL_RX_REJECTED;
    if (m->reg[R_CANINTF] & F_RX1) {
        overflow(m, E_RX1OVR);
        return MCP2515_MODEL_RX_OVERFLOW;
    }
    load(m, 1u, hit, f);
    return MCP2515_MODEL_RX_BUF1;
}

int mcp2515_model_receive(mcp2515_model_t *m, const mcp2515_model_frame_t *f)
{
    uint8_t op = opmode(m);
    if (op == OP_SLEEP) {
        /* Bus activity wakes the part into listen-only; the waking frame is lost. */
        m->reg[R_CANINTF] |= F_WAK;
        m->reg[R_CANSTAT] = (uint8_t)((OP_LISTEN << 5) | (m->reg[R_CANSTAT] & 0x1Fu));
        m->reg[R_CANCTRL] = (uint8_t)((OP_LISTEN << 5) | (m->reg[R_CANCTRL] & 0x1Fu));
        return MCP2515_MODEL_RX_OFF;
    }
    if ((op != OP_NORMAL && op != OP_LISTEN) || m->bus_off)
        return MCP2515_MODEL_RX_OFF;
    int r = deliver(m, f);
    if (op == OP_NORMAL && m->rec > 0u) {
        m->rec = m->rec > 127u ? 127u : (uint8_t)(m->rec - 1u);
        error_state(m);
    }
    return r;
}

void mcp2515_model_rx_error(mcp2515_model_t *m)
{
    if (opmode(m) != OP_NORMAL || m->bus_off)
        return;
    if (m->rec < 255u)
        m->rec++;
    m->reg[R_CANINTF] |= F_MERR;
    error_state(m);
}

void mcp2515_model_idle(mcp2515_model_t *m, uint16_t n)
{
    uint8_t op = opmode(m);
    if (!m->bus_off || op == OP_CONFIG || op == OP_SLEEP)
        return;
    uint16_t total = (uint16_t)(m->idle_sequences + n);
    if (total < 128u) {
        m->idle_sequences = (uint8_t)total;
        return;
    }
    m->bus_off = 0u;
    m->idle_sequences = 0u;
    m->tec = 0u;
    m->rec = 0u;
    error_state(m);
}

int mcp2515_model_bus_tick(mcp2515_model_t *m)
{
    uint8_t op = opmode(m);
    if ((op != OP_NORMAL && op != OP_LOOP) || m->bus_off || (m->reg[R_CANCTRL] & C_ABAT))
        return -1;
    int best = -1;
    uint8_t best_p = 0u;
    for (uint8_t n = 0; n < 3u; n++) {
        uint8_t c = m->reg[R_TXB0CTRL + 0x10u * n];
        if ((c & T_TXREQ) && (best < 0 || (c & 3u) >= best_p)) {
            best = n; /* equal priority: the higher buffer number goes first */
            best_p = (uint8_t)(c & 3u);
        }
    }
    if (best < 0)
        return -1;
    uint8_t *r = &m->reg[R_TXB0CTRL + 0x10u * (unsigned)best];
    mcp2515_model_frame_t f = {0};
    f.ext = (r[2] & S_IDE) ? 1u : 0u;
    if (f.ext)
        f.id = ((uint32_t)r[1] << 21) | ((uint32_t)(r[2] >> 5) << 18) |
               ((uint32_t)(r[2] & 3u) << 16) | ((uint32_t)r[3] << 8) | r[4];
    else
        f.id = ((uint32_t)r[1] << 3) | (uint32_t)(r[2] >> 5);
    f.rtr = (r[5] & D_RTR) ? 1u : 0u;
    f.dlc = (uint8_t)(r[5] & 0x0Fu);
    if (!f.rtr)
        for (uint8_t i = 0; i < 8u && i < f.dlc; i++)
            f.data[i] = r[6 + i];
    mcp2515_model_tx_t res = MCP2515_MODEL_TX_ACK;
    if (op == OP_LOOP)
        (void)deliver(m, &f);
    else
        res = m->bus != NULL ? m->bus(m->bus_arg, &f) : MCP2515_MODEL_TX_NO_ACK;
    switch (res) {
    case MCP2515_MODEL_TX_ACK:
        r[0] &= (uint8_t)~T_TXREQ;
        m->reg[R_CANINTF] |= (uint8_t)(F_TX0 << best);
        m->frames_sent++;
        if (op == OP_NORMAL && m->tec > 0u)
            m->tec--;
        break;
    case MCP2515_MODEL_TX_LOST:
        r[0] |= T_MLOA;
        break;
    case MCP2515_MODEL_TX_NO_ACK:
    case MCP2515_MODEL_TX_ERROR:
    default:
        r[0] |= T_TXERR;
        m->reg[R_CANINTF] |= F_MERR;
        if (!(res == MCP2515_MODEL_TX_NO_ACK && (m->tec >= 128u || m->rec >= 128u)))
            m->tec = (uint16_t)(m->tec + 8u);
        if (m->tec > 255u)
            m->bus_off = 1u;
        break;
    }
    error_state(m);
    return best;
}
