/*
 * hal/console.h - a byte console for diagnostics and test output.
 *
 * MSP430: test images write to the mspdebug simulator's console device (one byte register
 * at 0x00FF); board images write to USCI_A0 (UART, 115200 8N1 from SMCLK, whichever clock
 * hal_cpu_init() chose), waiting for the transmit buffer: no byte is ever dropped, and a
 * write waits up to one character time (87 us) per byte. Not for interrupt handlers.
 * POSIX: stdout of the harness process (or a capture buffer, see hal/posix/posix.h).
 */
#ifndef HAL_CONSOLE_H
#define HAL_CONSOLE_H

#include <stddef.h>
#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

/** Write one byte. */
void hal_console_putc(char c);

/** Write a NUL-terminated string. */
void hal_console_puts(const char *s);

/** Write @p n bytes. */
void hal_console_write(const char *s, size_t n);

/** Wait until every byte written so far has left the transmitter (MSP430: the UART's shift
 * register is empty; POSIX: stdout flushed). hal_fault() calls it before stopping. */
void hal_console_flush(void);

#ifdef __cplusplus
}
#endif

#endif
