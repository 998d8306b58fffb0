# Build helpers shared by every CMakeLists.txt of the project.

set(CY_C_WARNINGS -Wall -Wextra -Werror -Wshadow -Wstrict-prototypes -Wmissing-prototypes
    -Wundef -Wvla -Wpointer-arith -Wcast-qual)
set(CY_CXX_WARNINGS -Wall -Wextra -Werror -Wshadow -Wundef -Wpointer-arith)

# Warnings as errors on every target of the project.
function(cy_warnings tgt)
    target_compile_options(${tgt} PRIVATE
        $<$<COMPILE_LANGUAGE:C>:${CY_C_WARNINGS}>
        $<$<COMPILE_LANGUAGE:CXX>:${CY_CXX_WARNINGS}>)
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
    # cy_msp430_image(NAME KIND board|test SOURCES src... [LINK lib...])
    # An MSP430 ELF in bin/. Board images get the 32 KB layout and the UART console, test
    # images the whole flash and the simulator console. Every image is checked against the
    # budget (32 KB flash, 2 KB RAM) and its sizes recorded in images/<name>.json.
    function(cy_msp430_image name)
        cmake_parse_arguments(A "" "KIND" "SOURCES;LINK" ${ARGN})
        add_executable(${name} ${A_SOURCES})
        cy_warnings(${name})
        if(A_KIND STREQUAL "board")
            set(ld ${PROJECT_SOURCE_DIR}/hal/msp430/ld/f249_board.ld)
            set(console cy_hal_msp430_uart)
        else()
            set(ld ${PROJECT_SOURCE_DIR}/hal/msp430/ld/f249_test.ld)
            set(console cy_hal_msp430_simcon)
        endif()
        target_link_libraries(${name} PRIVATE ${A_LINK} cy_hal_msp430 ${console} cy_mspabi)
        target_link_options(${name} PRIVATE -T ${ld} -L ${PROJECT_SOURCE_DIR}/hal/msp430/ld
            --gc-sections -Map=${CMAKE_BINARY_DIR}/bin/${name}.map)
        set_target_properties(${name} PROPERTIES LINK_DEPENDS
            "${ld};${PROJECT_SOURCE_DIR}/hal/msp430/ld/f249_sections.ld")
        if(A_KIND STREQUAL "board")
            set(limits --flash-limit 32768 --ram-limit 2048)
        else()
            set(limits --flash-limit 61152 --ram-limit 2048)
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
