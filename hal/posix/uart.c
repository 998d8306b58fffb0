/*
 * uart.c - hal/uart.h on the harness: per board and instance a serial line whose far end
 * (posix_uart_send) queues bytes; each arrives 10 bit times after it started, back to back,
 * as a receive interrupt of the instance's vector (hal/pinmap.h). The byte waits in a one-byte
 * receive buffer for its handler; the next arrival before the handler ran overruns it.
 */
#include <stdbool.h>
#include <stddef.h>
#include <string.h>

#include "hal/pinmap.h"
#include "hal/uart.h"
#include "hal_posix/harness.h"

/*
 * Source bits within the vectors: instance 1 is UCA0RXIFG (bit 0 of IFG2 on the target);
 * instance 0 is UCA1RXIFG, bit 0 of UC1IFG on the target, but the harness's board link
 * (hal/posix/link.c) still models its UART on (17, 0): the receiver takes bit 1 of the vector
 * until the link leaves USCI_A1 (on a board image the two cannot share it: docs/posrx.md).
 */
static const uint8_t vec_of[HAL_UART_COUNT] = {HAL_VEC_UART0_RX, HAL_VEC_UART1_RX};
static const uint8_t bit_of[HAL_UART_COUNT] = {1, 0};

typedef struct {
    bool open;
    int board;
    int source;
    uint32_t baud;
    hal_uart_rx_cb_t cb;
    void *arg;
    /* the line: bytes sent and not yet arrived, with the instant each one ends */
    uint8_t byte[POSIX_UART_QUEUE];
    uint8_t flags[POSIX_UART_QUEUE];
    uint64_t end_ns[POSIX_UART_QUEUE];
    size_t head, n;
    uint64_t busy_until; /* end of the last byte queued */
    uint64_t ev;         /* arrival event of the head byte, 0 = none */
    /* the receive buffer */
    uint8_t rxbuf, rxflags;
    uint32_t overruns;
} line_t;

static line_t lines[POSIX_MAX_BOARDS][HAL_UART_COUNT];

void posix_uart_reset(void)
{
    memset(lines, 0, sizeof lines);
}

static line_t *line_at(int board, uint8_t instance)
{
    if (board < 0 || board >= POSIX_MAX_BOARDS || instance >= HAL_UART_COUNT)
        return NULL;
    return &lines[board][instance];
}

static void rx_isr(void *ctx)
{
    line_t *l = ctx;
    if (l->open)
        l->cb(l->arg, l->rxbuf, l->rxflags);
}

static void arrive(void *ctx, uint64_t t);

static void schedule_head(line_t *l)
{
    l->ev = 0;
    if (l->n)
        l->ev = posix_schedule(l->end_ns[l->head], arrive, l);
}

static void arrive(void *ctx, uint64_t t)
{
    (void)t;
    line_t *l = ctx;
    uint8_t b = l->byte[l->head], f = l->flags[l->head];
    l->head = (l->head + 1u) % POSIX_UART_QUEUE;
    l->n--;
    if (posix_source_pending(l->board, l->source)) {
        l->overruns++; /* the byte before was not read: lost (the USCI's UCOE) */
        f |= HAL_UART_RX_ERROR;
    }
    l->rxbuf = b;
    l->rxflags = f;
    posix_source_raise(l->board, l->source);
    schedule_head(l);
}

int hal_uart_open(uint8_t instance, uint32_t baud, hal_uart_rx_cb_t cb, void *arg)
{
    if (instance >= HAL_UART_COUNT)
        return HAL_UART_E_INSTANCE;
    if (baud != HAL_UART_BAUD_9600 && baud != HAL_UART_BAUD_115200)
        return HAL_UART_E_BAUD;
    if (cb == NULL)
        return HAL_UART_E_ARG;
    int b = posix_board_current();
    line_t *l = line_at(b, instance);
    int src = posix_source_register(b, vec_of[instance], bit_of[instance], false, rx_isr, l);
    if (src < 0)
        return HAL_UART_E_INSTANCE; /* the board's interrupt table is full */
    l->board = b;
    l->source = src;
    l->baud = baud;
    l->cb = cb;
    l->arg = arg;
    l->open = true;
    posix_source_enable(b, src, true);
    return HAL_UART_OK;
}

void hal_uart_close(uint8_t instance)
{
    line_t *l = line_at(posix_board_current(), instance);
    if (l == NULL || !l->open)
        return;
    l->open = false;
    posix_source_enable(l->board, l->source, false);
    if (l->ev)
        posix_cancel(l->ev);
    l->ev = 0;
    l->n = 0;
}

uint16_t hal_uart_overruns(uint8_t instance)
{
    line_t *l = line_at(posix_board_current(), instance);
    return l ? (uint16_t)l->overruns : 0;
}

size_t posix_uart_send(int board, uint8_t instance, const uint8_t *bytes, size_t n, uint8_t flags)
{
    line_t *l = line_at(board, instance);
    if (l == NULL || !l->open)
        return 0;
    /* 10 bits per byte, to the nearest nanosecond */
    uint64_t byte_ns = (10000000000ull + l->baud / 2u) / l->baud;
    size_t sent = 0;
    for (; sent < n && l->n < POSIX_UART_QUEUE; sent++) {
        uint64_t start = l->busy_until > posix_now_ns() ? l->busy_until : posix_now_ns();
        size_t k = (l->head + l->n) % POSIX_UART_QUEUE;
        l->byte[k] = bytes[sent];
        l->flags[k] = flags;
        l->end_ns[k] = start + byte_ns;
        l->busy_until = l->end_ns[k];
        l->n++;
        if (l->n == 1)
            schedule_head(l);
    }
    return sent;
}

uint64_t posix_uart_idle_ns(int board, uint8_t instance)
{
    line_t *l = line_at(board, instance);
    uint64_t now = posix_now_ns();
    return l && l->busy_until > now ? l->busy_until : now;
}

int posix_uart_source(int board, uint8_t instance)
{
    line_t *l = line_at(board, instance);
    return l && l->open ? l->source : -1;
}

uint32_t posix_uart_overruns(int board, uint8_t instance)
{
    line_t *l = line_at(board, instance);
    return l ? l->overruns : 0;
}
