/*
 * misc.c - hal/cpu.h, hal/console.h and hal/fault.h on the host.
 */
#include <stdio.h>
#include <stdlib.h>

#include "hal/console.h"
#include "hal/cpu.h"
#include "hal/fault.h"
#include "hal_posix/harness.h"

static posix_console_sink_fn console_sink;
static void *console_ctx;

void hal_cpu_init(void)
{
    /* The board exists once the harness selected it; interrupts stay off until enabled. */
    (void)posix_board_current();
}

void hal_cpu_idle(void) {}

void hal_cpu_wake(void)
{
    posix_board_wake(posix_board_current());
}

void posix_console_redirect(posix_console_sink_fn sink, void *ctx)
{
    console_sink = sink;
    console_ctx = ctx;
}

void hal_console_putc(char c)
{
    if (console_sink)
        console_sink(console_ctx, posix_board_current(), c);
    else
        putchar(c);
}

void hal_console_puts(const char *s)
{
    while (*s)
        hal_console_putc(*s++);
}

void hal_console_write(const char *s, size_t n)
{
    for (size_t i = 0; i < n; i++)
        hal_console_putc(s[i]);
}

void hal_console_flush(void)
{
    fflush(stdout);
}

void hal_fault(uint16_t code)
{
    fflush(stdout);
    fprintf(stderr, "FAULT 0x%04x %s on board %s\n", code, hal_fault_name(code),
            posix_board_name(posix_board_current()));
    abort();
}
