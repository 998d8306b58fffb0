/*
 * hal/fault.h - unrecoverable errors.
 *
 * hal_fault() never returns. On the MSP430 it disables interrupts, records the code in
 * hal_fault_code (readable with the debugger: `md hal_fault_code 2`), prints "FAULT 0x...."
 * on the console and stops the CPU. On the host it prints the code and its name on stderr and
 * aborts, so a test can catch it as a death test.
 */
#ifndef HAL_FAULT_H
#define HAL_FAULT_H

#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

/** Fault codes. 0x01xx are HAL misuse, 0x02xx firmware invariants, 0x03xx run time. */
enum hal_fault_code {
    HAL_FAULT_CRITICAL_UNDERFLOW = 0x0101, /**< hal_critical_exit() without enter */
    HAL_FAULT_CRITICAL_OVERFLOW = 0x0102,  /**< critical sections nested too deeply */
    HAL_FAULT_BAD_ARGUMENT = 0x0103,       /**< a HAL call got an argument out of range */
    HAL_FAULT_UNEXPECTED_IRQ = 0x0104,     /**< an interrupt without a handler fired */
    HAL_FAULT_ASSERT = 0x0201,             /**< a firmware invariant does not hold */
    HAL_FAULT_DIV_ZERO = 0x0301,           /**< reserved for callers that trap division by 0 */
    HAL_FAULT_CLOCK_UNCALIBRATED = 0x0302, /**< MSP430: the DCO calibration data is erased */
    HAL_FAULT_SUPPLY_LOW = 0x0303,         /**< MSP430: the supply allows no calibrated clock */
};

/** Stop for good with @p code (one of enum hal_fault_code). Never returns. */
_Noreturn void hal_fault(uint16_t code);

/** Human-readable name of a fault code, "unknown" for others. */
const char *hal_fault_name(uint16_t code);

#ifdef __cplusplus
}
#endif

#endif
