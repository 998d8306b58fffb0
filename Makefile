# cyclopion - a thin wrapper over the CMake presets (CMakePresets.json).
#   make demo   install what is missing, build, run the main job and print its summary
#   make test   install what is missing, build host + MSP430, run every test under ctest
#   make fuzz   run every fuzz harness longer (FUZZ_SECONDS each, default 600; docs/fuzzing.md)
#   make flash BOARD=main|main-pursuit|nav [PROBE=uif|tilib|olimex|sim]   program a board (README)
#   make debug BOARD=main|main-pursuit|nav [PROBE=...] | make debug SIM=1 BOARD=...|IMAGE=...
#   make sim IMAGE=name|path.elf   run one MSP430 image in mspdebug's simulator, as ctest does
#   make lcm-spy [LCM_URL=...]   lcm-spy with the project's LCM types (README "Watching a run live")
.PHONY: all deps host host-asan msp430 fuzz-build build test fuzz demo format clean flash debug \
    sim image lcm-spy

FUZZ_SECONDS ?= 600

all: build

deps:
	@tools/install-deps.sh

host host-asan: deps
	@cmake --preset $@ >/dev/null
	@cmake --build --preset $@

# The MSP430 tree compares its images with the host build (bit-identical results).
msp430: deps host
	@cmake --preset $@ >/dev/null
	@cmake --build --preset $@

# The libFuzzer harnesses (clang-16, ASan, UBSan): tests/fuzz, docs/fuzzing.md.
fuzz-build: deps
	@cmake --preset fuzz >/dev/null
	@cmake --build --preset fuzz

build: host host-asan msp430 fuzz-build

test: build
	ctest --preset host-asan
	ctest --preset fuzz
	@rm -f build/msp430/cycles.json # rewritten by the target tests, without stale entries
	ctest --preset msp430
	@python3 tools/cycles_report.py build/msp430/cycles.json

fuzz: fuzz-build
	tools/fuzz.py --seconds $(FUZZ_SECONDS) $(FUZZERS)

demo: host
	@python3 tools/demo.py

format:
	@tools/check_format.py --fix .

clean:
	rm -rf build

# --- the MSP430 boards: flash, debug, simulate (README "Flashing a board") ------------------
BOARD ?= main
PROBE ?= uif
BIN := build/msp430/bin
# A name (irq_test, main_board) or a path to an ELF.
IMAGE_ELF = $(if $(filter %.elf,$(IMAGE)),$(IMAGE),$(BIN)/$(IMAGE).elf)
# The image of each BOARD: the main board's beacon travel (main), its pursuit travel
# (main-pursuit: seed 002's pursuit on the position receiver), the nav board.
BOARD_IMAGE_main = main_board
BOARD_IMAGE_main-pursuit = main_board_pursuit
BOARD_IMAGE_nav = nav_board
BOARD_IMAGE = $(or $(BOARD_IMAGE_$(BOARD)),$(error BOARD=$(BOARD): use main, main-pursuit or nav))
BOARD_ELF = $(BIN)/$(BOARD_IMAGE).elf
# The MSP430F2618 is JTAG-only (no Spy-Bi-Wire): mspdebug's -j. uif: FET430UIF/eZ430 over
# its USB serial chip (UIF_TTY=/dev/ttyUSB0 to use the kernel's tty); tilib: TI's
# libmsp430.so (MSP-FET, FET430UIF with v3 firmware; Debian does not ship it); olimex:
# MSP430-JTAG-TINY. rf2500 (eZ430-RF2500, LaunchPad) speaks only Spy-Bi-Wire: it cannot.
MSPDEBUG_uif = mspdebug -j uif$(if $(UIF_TTY), -d $(UIF_TTY))
MSPDEBUG_tilib = mspdebug tilib
MSPDEBUG_olimex = mspdebug -j olimex
# sim: mspdebug's simulator, no board: the same commands as a dry run (the docs test uses it).
MSPDEBUG_sim = mspdebug sim
MSPDEBUG_PROBE = $(or $(MSPDEBUG_$(PROBE)),$(error PROBE=$(PROBE): use uif, tilib, olimex or sim (the F2618 is JTAG-only; rf2500 cannot program it)))

# The board image, built with the MSP430 preset only.
image:
	@cmake --preset msp430 >/dev/null
	cmake --build --preset msp430 --target $(BOARD_IMAGE)

flash: image
	$(MSPDEBUG_PROBE) "prog $(BOARD_ELF)"

ifeq ($(SIM),1)
# The simulator with the image loaded, the devices of tools/mspdebug-f2618.cfg, the chip's
# reset state (calibration data, transmit flags): break and step at the prompt.
debug:
	@test -f "$(if $(IMAGE),$(IMAGE_ELF),$(BOARD_ELF))" || { echo "no $(if $(IMAGE),$(IMAGE_ELF),$(BOARD_ELF)): make msp430 first" >&2; exit 2; }
	python3 tools/msp430sim.py --elf $(if $(IMAGE),$(IMAGE_ELF),$(BOARD_ELF)) --mspdebug-script build/msp430/debug.mspdebug
	mspdebug -q -C build/msp430/debug.mspdebug sim
else
# The board on the probe: programmed, then mspdebug's prompt (break, step, regs, md);
# mspdebug's `gdb` command serves an msp430-elf-gdb where one is installed (Debian has none).
debug: flash
	$(MSPDEBUG_PROBE)
endif

sim:
	@test -n "$(IMAGE)" || { echo "IMAGE=name|path.elf (e.g. make sim IMAGE=irq_test)" >&2; exit 2; }
	@test -f "$(IMAGE_ELF)" || { echo "no $(IMAGE_ELF): make msp430 first" >&2; exit 2; }
	python3 tools/msp430sim.py --elf $(IMAGE_ELF) --verbose

# --- live telemetry: lcm-spy with the project's types (README "Watching a run live") --------
# Debian's lcm-spy script passes -Xincgc, which Java 17 refuses: java is called directly, with
# lcm-spy's jars (liblcm-java, libjchart2d-java) and the types lcm-gen made for Java
# (build/host/java/cyclopion_lcm.jar) on the CLASSPATH. lcm-spy is a window: it needs a display.
LCM_URL ?= udpm://239.255.76.67:7667?ttl=0
LCM_SPY_CLASSPATH = /usr/share/java/lcm.jar:/usr/share/java/jchart2d.jar:build/host/java/cyclopion_lcm.jar

lcm-spy: host
	@test -n "$$DISPLAY$$WAYLAND_DISPLAY" || { echo "make lcm-spy: lcm-spy opens a window: it needs a display (DISPLAY)" >&2; exit 2; }
	java -Djava.net.preferIPv4Stack=true -Xmx256m -cp $(LCM_SPY_CLASSPATH) lcm.spy.Spy --lcm-url='$(LCM_URL)'
