# cyclopion - a thin wrapper over the CMake presets (CMakePresets.json).
#   make demo   install what is missing, build, run the main job and print its summary
#   make test   install what is missing, build host + MSP430, run every test under ctest
.PHONY: all deps host host-asan msp430 build test demo format clean

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

build: host host-asan msp430

test: build
	ctest --preset host-asan
	@rm -f build/msp430/cycles.json # rewritten by the target tests, without stale entries
	ctest --preset msp430
	@python3 tools/cycles_report.py build/msp430/cycles.json

demo: host
	@python3 tools/demo.py

format:
	@tools/check_format.py --fix .

clean:
	rm -rf build
