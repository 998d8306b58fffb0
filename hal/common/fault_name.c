/*
 * fault_name.c - names of the fault codes, shared by both HAL implementations.
 */
#include "hal/fault.h"

const char *hal_fault_name(uint16_t code)
{
    switch (code) {
    case HAL_FAULT_CRITICAL_UNDERFLOW:
        return "critical-section exit without enter";
    case HAL_FAULT_CRITICAL_OVERFLOW:
        return "critical sections nested too deeply";
    case HAL_FAULT_BAD_ARGUMENT:
        return "bad argument to a HAL call";
    case HAL_FAULT_UNEXPECTED_IRQ:
        return "unexpected interrupt";
    case HAL_FAULT_ASSERT:
        return "firmware invariant violated";
    case HAL_FAULT_DIV_ZERO:
        return "division by zero";
    case HAL_FAULT_CLOCK_UNCALIBRATED:
        return "DCO calibration data erased";
    case HAL_FAULT_SUPPLY_LOW:
        return "supply too low for a calibrated clock";
    default:
        return "unknown";
    }
}
