# Build helpers shared by every CMakeLists.txt of the project.

set(CY_C_WARNINGS -Wall -Wextra -Werror -Wshadow -Wstrict-prototypes -Wmissing-prototypes
    -Wundef -Wvla -Wpointer-arith -Wcast-qual)
set(CY_CXX_WARNINGS -Wall -Wextra -Werror -Wshadow -Wundef -Wpointer-arith)

# GCC 12 (host) deletes calls to functions whose only store it wrongly takes for a NULL
# dereference (an ivopts address with a literal 0 base read by ipa-pure-const; docs/optical.md
# "Host compiler: GCC 12 drops stores"); the project's code never relies on a NULL check
# being deleted, so every GCC compile goes without that deduction (tests/unit/
# optical_gcc_guard.c guards it). Clang (the MSP430 build) is not affected.
set(CY_GCC_WORKAROUNDS -fno-delete-null-pointer-checks)

# Warnings as errors (and the GCC workaround) on every target of the project.
function(cy_warnings tgt)
    target_compile_options(${tgt} PRIVATE
        $<$<COMPILE_LANGUAGE:C>:${CY_C_WARNINGS}>
        $<$<COMPILE_LANGUAGE:CXX>:${CY_CXX_WARNINGS}>
        $<$<AND:$<COMPILE_LANGUAGE:C>,$<C_COMPILER_ID:GNU>>:${CY_GCC_WORKAROUNDS}>
        $<$<AND:$<COMPILE_LANGUAGE:CXX>,$<CXX_COMPILER_ID:GNU>>:${CY_GCC_WORKAROUNDS}>)
endfunction()

# cy_library(NAME SOURCES src... [INCLUDE dir...] [LINK lib...])
# A static library built for whichever world this tree builds (host or MSP430).
function(cy_library name)
    cmake_parse_arguments(A "" "" "SOURCES;INCLUDE;LINK" ${ARGN})
    add_library(${name} STATIC ${A_SOURCES})
    cy_warnings(${name})
    if(A_INCLUDE)
        target_include_directories(${name} PUBLIC ${A_INCLUDE})
    endif()
    if(A_LINK)
        target_link_libraries(${name} PUBLIC ${A_LINK})
    endif()
endfunction()

if(CY_TARGET_MSP430)
    # The project budget of each board image on the MSP430F2618 (SPEC): flash (text, rodata,
    # the load image of .data, the vectors) and RAM (static data plus the proven worst-case
    # stack). Room left on purpose for what comes next.
    set(CY_BOARD_FLASH_BUDGET 49152)
    set(CY_BOARD_RAM_BUDGET 6144)

    # cy_msp430_image(NAME KIND board|test SOURCES src... [LINK lib...])
    # An MSP430 ELF in bin/. Board images get the UART console, test images the simulator
    # console; both the F2618's memory map. Board images are checked against the project
    # budget (48 KB flash, 6 KB RAM with the stack: the static part here, static + proven
    # worst-case stack in target.stack_bound.*), test images against the part; the sizes are
    # recorded in images/<name>.json.
    function(cy_msp430_image name)
        cmake_parse_arguments(A "" "KIND" "SOURCES;LINK" ${ARGN})
        add_executable(${name} ${A_SOURCES})
        cy_warnings(${name})
        if(A_KIND STREQUAL "board")
            set(ld ${PROJECT_SOURCE_DIR}/hal/msp430/ld/f2618_board.ld)
            set(console cy_hal_msp430_uart)
        else()
            set(ld ${PROJECT_SOURCE_DIR}/hal/msp430/ld/f2618_test.ld)
            set(console cy_hal_msp430_simcon)
        endif()
        target_link_libraries(${name} PRIVATE ${A_LINK} cy_hal_msp430 ${console} cy_mspabi)
        target_link_options(${name} PRIVATE -T ${ld} -L ${PROJECT_SOURCE_DIR}/hal/msp430/ld
            --gc-sections -Map=${CMAKE_BINARY_DIR}/bin/${name}.map)
        set_target_properties(${name} PROPERTIES LINK_DEPENDS
            "${ld};${PROJECT_SOURCE_DIR}/hal/msp430/ld/f2618_sections.ld")
        if(A_KIND STREQUAL "board")
            set(limits --flash-limit ${CY_BOARD_FLASH_BUDGET} --ram-limit ${CY_BOARD_RAM_BUDGET})
        else()
            set(limits --flash-limit 53056 --ram-limit 8192)
        endif()
        add_custom_command(TARGET ${name} POST_BUILD
            COMMAND ${Python3_EXECUTABLE} ${PROJECT_SOURCE_DIR}/tools/image_size.py
                --readelf ${CY_READELF} ${limits} --kind ${A_KIND}
                --json ${CMAKE_BINARY_DIR}/images/${name}.json $<TARGET_FILE:${name}>
            VERBATIM)
    endfunction()

    # cy_target_test(NAME IMAGE img [TIMEOUT s] [MAX_CYCLES n] [ARGS ...])
    # Runs an image in mspdebug's simulator under ctest (label "target").
    function(cy_target_test name)
        cmake_parse_arguments(A "" "IMAGE;TIMEOUT;MAX_CYCLES" "ARGS" ${ARGN})
        if(NOT A_TIMEOUT)
            set(A_TIMEOUT 120)
        endif()
        if(NOT A_MAX_CYCLES)
            set(A_MAX_CYCLES 200000000)
        endif()
        add_test(NAME target.${name}
            COMMAND ${Python3_EXECUTABLE} ${PROJECT_SOURCE_DIR}/tools/msp430sim.py
                --elf $<TARGET_FILE:${A_IMAGE}> --max-cycles ${A_MAX_CYCLES}
                --timeout ${A_TIMEOUT} --cycles-json ${CMAKE_BINARY_DIR}/cycles.json
                ${A_ARGS})
        set_tests_properties(target.${name} PROPERTIES LABELS target TIMEOUT ${A_TIMEOUT})
    endfunction()

    # cy_board_flash_test(NAME LIBRARY libfoo.a BUDGET bytes)
    # target.NAME: the flash a module library takes in the main board image, against its
    # budget (tests/target/board_flash.py): the board's objects and libraries linked again with
    # a roomy memory map, the library's share (text, rodata, data of every object the board
    # reaches) summed from the linker map. Deferred to the end of the configuration, when the
    # main board's target exists.
    function(cy_board_flash_test name)
        cmake_parse_arguments(A "" "LIBRARY;BUDGET" "" ${ARGN})
        # (a deferred call reads its arguments when it runs: EVAL fixes today's values)
        cmake_language(EVAL CODE "cmake_language(DEFER DIRECTORY [[${PROJECT_SOURCE_DIR}]] CALL
            cy_board_flash_test_now [[${name}]] [[${A_LIBRARY}]] [[${A_BUDGET}]])")
    endfunction()
    function(cy_board_flash_test_now name library budget)
        set(libs)
        set(todo main_board)
        while(todo)
            list(POP_FRONT todo t)
            foreach(prop LINK_LIBRARIES INTERFACE_LINK_LIBRARIES)
                get_target_property(deps ${t} ${prop})
                if(NOT deps)
                    continue()
                endif()
                foreach(d IN LISTS deps)
                    string(REGEX REPLACE "^\\$<LINK_ONLY:(.+)>$" "\\1" d "${d}")
                    if(TARGET ${d} AND NOT d IN_LIST libs)
                        list(APPEND libs ${d})
                        list(APPEND todo ${d})
                    endif()
                endforeach()
            endforeach()
        endwhile()
        set(files $<TARGET_OBJECTS:main_board>)
        foreach(l IN LISTS libs)
            get_target_property(type ${l} TYPE)
            if(type STREQUAL "STATIC_LIBRARY")
                list(APPEND files $<TARGET_FILE:${l}>)
            endif()
        endforeach()
        add_test(NAME target.${name}
            COMMAND ${Python3_EXECUTABLE} ${PROJECT_SOURCE_DIR}/tests/target/board_flash.py
                --lld ${CY_LLD} --ld-dir ${PROJECT_SOURCE_DIR}/hal/msp430/ld
                --library ${library} --budget ${budget}
                --map ${CMAKE_BINARY_DIR}/bin/main_board_${name}.map ${files})
        set_tests_properties(target.${name} PROPERTIES LABELS target)
    endfunction()
else()
    # cy_host_test(NAME SOURCES src... [LINK lib...] [LABELS l...])
    # A GoogleTest executable in bin/, registered with ctest (default label "unit").
    function(cy_host_test name)
        cmake_parse_arguments(A "" "" "SOURCES;LINK;LABELS" ${ARGN})
        add_executable(${name} ${A_SOURCES})
        cy_warnings(${name})
        target_link_libraries(${name} PRIVATE ${A_LINK} GTest::gtest GTest::gtest_main)
        if(NOT A_LABELS)
            set(A_LABELS unit)
        endif()
        gtest_discover_tests(${name} PROPERTIES LABELS "${A_LABELS}" DISCOVERY_TIMEOUT 60)
    endfunction()
endif()

# cy_vector_program(NAME SOURCES src... [LINK lib...] [MAX_CYCLES n] [TIMEOUT s] [ARGS ...])
# One C program built for both worlds from the same sources (tests/support/cy_test.h for
# output). Host tree: bin/NAME, printing to stdout. MSP430 tree: the image NAME_target, run
# in the simulator by ctest (label "target") and compared line by line with the host
# program's output (the host tree's bin/, CY_HOST_BIN_DIR): bit-identical results. The
# program's @cycles lines go to the cycle report.
function(cy_vector_program name)
    cmake_parse_arguments(A "" "MAX_CYCLES;TIMEOUT" "SOURCES;LINK;ARGS" ${ARGN})
    if(CY_TARGET_MSP430)
        cy_msp430_image(${name}_target KIND test SOURCES ${A_SOURCES} LINK ${A_LINK} cy_test_support)
        set(extra)
        if(A_MAX_CYCLES)
            list(APPEND extra MAX_CYCLES ${A_MAX_CYCLES})
        endif()
        if(A_TIMEOUT)
            list(APPEND extra TIMEOUT ${A_TIMEOUT})
        endif()
        cy_target_test(${name} IMAGE ${name}_target ${extra}
            ARGS --compare-cmd ${CY_HOST_BIN_DIR}/${name} ${A_ARGS})
    else()
        add_executable(${name} ${A_SOURCES})
        cy_warnings(${name})
        target_link_libraries(${name} PRIVATE ${A_LINK} cy_test_support cy_hal_posix)
    endif()
endfunction()

# cy_agvcalc_op(NAME op SOURCE file.c HELP "one line" [LINK lib...])
# Adds an op to agvcalc (host only): SOURCE defines
#   int agvcalc_op_<op>(json_t *req, json_t *resp, char *err, size_t errlen)
# (tools/agvcalc/agvcalc.h). Modules call this from their own CMakeLists.txt.
function(cy_agvcalc_op)
    cmake_parse_arguments(A "" "NAME;SOURCE;HELP" "LINK" ${ARGN})
    if(CY_TARGET_MSP430)
        return()
    endif()
    set_property(GLOBAL APPEND PROPERTY CY_AGVCALC_OPS ${A_NAME})
    set_property(GLOBAL APPEND PROPERTY CY_AGVCALC_HELP "${A_HELP}")
    set_property(GLOBAL APPEND PROPERTY CY_AGVCALC_SOURCES ${A_SOURCE})
    set_property(GLOBAL APPEND PROPERTY CY_AGVCALC_LIBS ${A_LINK})
endfunction()

# cy_fuzzer(NAME SOURCES src... [LINK lib...] [CORPUS dir] [DICT file] [MAX_LEN bytes])
# A libFuzzer harness (docs/fuzzing.md), built in the fuzz tree only (preset "fuzz": clang-16,
# -fsanitize=fuzzer,address,undefined; elsewhere the call does nothing): bin/fuzz_NAME, and
# the ctest fuzz.NAME (label "fuzz") that runs it for CY_FUZZ_SECONDS seconds with a fixed
# seed from the seed corpus CORPUS (default tests/fuzz/corpus/NAME). A finding fails the test
# and stays in the build tree (findings/NAME/, its path printed). tools/fuzz.py runs the
# harnesses longer (fuzzers.json lists them).
set(CY_FUZZ_SECONDS 20 CACHE STRING "Seconds each fuzz harness runs under ctest")
function(cy_fuzzer name)
    if(NOT CY_FUZZ)
        return()
    endif()
    cmake_parse_arguments(A "" "CORPUS;DICT;MAX_LEN" "SOURCES;LINK" ${ARGN})
    if(NOT A_CORPUS)
        set(A_CORPUS ${PROJECT_SOURCE_DIR}/tests/fuzz/corpus/${name})
    endif()
    if(NOT IS_DIRECTORY ${A_CORPUS})
        message(FATAL_ERROR "cy_fuzzer(${name}): no seed corpus at ${A_CORPUS}")
    endif()
    if(NOT A_MAX_LEN)
        set(A_MAX_LEN 4096)
    endif()
    add_executable(fuzz_${name} ${A_SOURCES})
    cy_warnings(fuzz_${name})
    target_link_libraries(fuzz_${name} PRIVATE ${A_LINK})
    target_link_options(fuzz_${name} PRIVATE -fsanitize=fuzzer)
    # built by "all" even when declared in a directory that the fuzz tree builds on demand only
    set_target_properties(fuzz_${name} PROPERTIES EXCLUDE_FROM_ALL FALSE)
    set(opts --corpus ${A_CORPUS} --max-len ${A_MAX_LEN})
    set(entry "\"name\":\"${name}\",\"binary\":\"$<TARGET_FILE:fuzz_${name}>\",\"corpus\":\"${A_CORPUS}\",\"max_len\":${A_MAX_LEN}")
    if(A_DICT)
        list(APPEND opts --dict ${A_DICT})
        string(APPEND entry ",\"dict\":\"${A_DICT}\"")
    endif()
    set_property(GLOBAL APPEND PROPERTY CY_FUZZERS "{${entry}}")
    add_test(NAME fuzz.${name}
        COMMAND ${Python3_EXECUTABLE} ${PROJECT_SOURCE_DIR}/tools/fuzz.py --build-dir
            ${CMAKE_BINARY_DIR} --test --seconds ${CY_FUZZ_SECONDS}
            --binary $<TARGET_FILE:fuzz_${name}> ${opts} ${name})
    math(EXPR timeout "${CY_FUZZ_SECONDS} * 3 + 60")
    set_tests_properties(fuzz.${name} PROPERTIES LABELS fuzz TIMEOUT ${timeout})
endfunction()

# The fuzz tree's list of harnesses for tools/fuzz.py (build/fuzz/fuzzers.json), written once
# every directory has declared its harnesses.
function(cy_fuzzers_manifest)
    get_property(list GLOBAL PROPERTY CY_FUZZERS)
    string(JOIN ",\n " body ${list})
    file(GENERATE OUTPUT ${CMAKE_BINARY_DIR}/fuzzers.json CONTENT "[\n ${body}\n]\n")
endfunction()
