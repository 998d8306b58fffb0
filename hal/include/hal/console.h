/*
 * hal/console.h - a byte console for diagnostics and test output.
 *
 * MSP430: test images write to the mspdebug simulator's console device (one byte register
 * at 0x00FF); board images write to USCI_A0 (UART, 115200 8N1 at 16 MHz) without blocking:
 * a byte is dropped when the transmitter is busy (counted in hal_console_dropped()).
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

/** Number of bytes dropped because the transmitter was busy (0 where that cannot happen). */
uint16_t hal_console_dropped(void);

#ifdef __cplusplus
}
#endif

#endif
