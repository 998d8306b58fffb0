# cyclopion - a thin wrapper over the CMake presets (CMakePresets.json).
#   make demo   install what is missing, build, run the main job and print its summary
#   make test   install what is missing, build host + MSP430, run every test under ctest
#   make fuzz   run every fuzz harness longer (FUZZ_SECONDS each, default 600; docs/fuzzing.md)
.PHONY: all deps host host-asan msp430 fuzz-build build test fuzz demo format clean

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
