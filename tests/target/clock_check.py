"""Checker for tests/target/cpu_clock_test.c (tools/msp430sim.py --check): the tick and the
console UART's divisors the image printed for the clock it chose, against SLAU144's baud-rate
table (tests/target/datasheet/slau144_uart_baud.csv) and a millisecond of that clock."""
import csv
import os

TABLE = os.path.join(os.path.dirname(os.path.abspath(__file__)), "datasheet",
                     "slau144_uart_baud.csv")


def baud_table():
    with open(TABLE) as f:
        rows = csv.DictReader(line for line in f if not line.startswith("#"))
        return {(int(r["brclk_hz"]), int(r["baud"])): (int(r["ucbr"]), int(r["ucbrs"]))
                for r in rows}


def check(lines):
    errors = []
    clock = [l for l in lines if l.startswith("clock ")]
    tick = [l for l in lines if l.startswith("tick ")]
    if len(clock) != 1 or len(tick) != 1:
        return [f"expected one `clock` and one `tick` line, got {lines}"]
    if clock[0] == "clock uncalibrated":
        return ["the DCO does not hold a calibrated setting"]
    hz = int(clock[0].split()[1])
    f = tick[0].split()
    ticks, br0, br1, brs = int(f[1]), int(f[3]), int(f[4]), int(f[5])
    if ticks * 1000 != hz:
        errors.append(f"the tick is {ticks} cycles, a millisecond at {hz} Hz is {hz // 1000}")
    want = baud_table().get((hz, 115200))
    if want is None:
        errors.append(f"SLAU144's table has no 115200 baud entry for {hz} Hz")
    elif (br0 + 256 * br1, brs) != want:
        errors.append(f"UART divisors UCBR {br0 + 256 * br1}, UCBRS {brs}; SLAU144: "
                      f"UCBR {want[0]}, UCBRS {want[1]}")
    return errors
