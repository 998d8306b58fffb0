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
    # stack). Room left on purpose for what comes next: 48 KB of flash. The main board's
    # beacon image (main_board.elf) has outgrown it: the beacon travel, the CAN link and the
    # fix gate of issue 16 take about 51.6 KB (the last 3.4 KB the gate), so its budget is the
    # whole flash below the vectors that the classic ISA reaches (0x3100-0xFFBF, 52,928 B) and
    # its margin is gone (README, "The MCU"). Pursuit mode has an image of its own
    # (main_board_pursuit.elf), within the 48 KB.
    set(CY_BOARD_FLASH_BUDGET 49152)
    set(CY_MAIN_BOARD_FLASH_BUDGET 52928)
    set(CY_BOARD_RAM_BUDGET 6144)

    # cy_msp430_image(NAME KIND board|test SOURCES src... [LINK lib...] [CONSOLE uart]
    #                 [FLASH_BUDGET bytes])
    # An MSP430 ELF in bin/. Board images get the UART console, test images the simulator
    # console (CONSOLE uart: the board's, for tests of it under tools/msp430sim.py --uart);
    # both the F2618's memory map. Board images are checked against the project
    # budget (48 KB flash unless FLASH_BUDGET says otherwise, 6 KB RAM with the stack: the static part here, static + proven
    # worst-case stack in target.stack_bound.*), test images against the part; the sizes are
    # recorded in images/<name>.json.
    function(cy_msp430_image name)
        cmake_parse_arguments(A "" "KIND;CONSOLE;FLASH_BUDGET" "SOURCES;LINK" ${ARGN})
        if(NOT A_FLASH_BUDGET)
            set(A_FLASH_BUDGET ${CY_BOARD_FLASH_BUDGET})
        endif()
        add_executable(${name} ${A_SOURCES})
        cy_warnings(${name})
        if(A_KIND STREQUAL "board")
            set(ld ${PROJECT_SOURCE_DIR}/hal/msp430/ld/f2618_board.ld)
            set(console cy_hal_msp430_uart)
        else()
            set(ld ${PROJECT_SOURCE_DIR}/hal/msp430/ld/f2618_test.ld)
            set(console cy_hal_msp430_simcon)
        endif()
        if(A_CONSOLE STREQUAL "uart")
            set(console cy_hal_msp430_uart)
        endif()
        target_link_libraries(${name} PRIVATE ${A_LINK} cy_hal_msp430 ${console} cy_mspabi)
        target_link_options(${name} PRIVATE -T ${ld} -L ${PROJECT_SOURCE_DIR}/hal/msp430/ld
            --gc-sections -Map=${CMAKE_BINARY_DIR}/bin/${name}.map)
        # (relinked when the size tool changes: its figures land in images/NAME.json)
        set_target_properties(${name} PROPERTIES LINK_DEPENDS
            "${ld};${PROJECT_SOURCE_DIR}/hal/msp430/ld/f2618_sections.ld;${PROJECT_SOURCE_DIR}/tools/image_size.py")
        if(A_KIND STREQUAL "board")
            set(limits --flash-limit ${A_FLASH_BUDGET} --ram-limit ${CY_BOARD_RAM_BUDGET})
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
                --map ${CMAKE_BINARY_DIR}/bin/main_board_${name}.map ${files}
            COMMAND_EXPAND_LISTS) # (the image's objects: a list)
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
# program's @cycles lines go to the cycle report. When the program reaches assembly kernels
# (a library it links, directly or not, declared them with cy_kernels()), it also gets its
# kernel check image NAME_check_target and the test target.NAME_check (docs/kernels.md).
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
        set(sources)
        foreach(s IN LISTS A_SOURCES)
            get_filename_component(s ${s} ABSOLUTE)
            list(APPEND sources ${s})
        endforeach()
        cy_kernel_check_later(${name} "${sources}" "${A_LINK}" "${A_MAX_CYCLES}" "${A_TIMEOUT}"
            "${A_ARGS}")
    else()
        add_executable(${name} ${A_SOURCES})
        cy_warnings(${name})
        target_link_libraries(${name} PRIVATE ${A_LINK} cy_test_support cy_hal_posix)
    endif()
endfunction()

# ------------------------------------------------------------------------------ kernels
# Assembly kernels, their C twins, generated offsets and the check mode: docs/kernels.md.

if(CY_TARGET_MSP430)
    find_program(CY_NM NAMES llvm-nm-16 REQUIRED)
    set(CY_KERNELS ASM CACHE STRING
        "MSP430 kernels: ASM (the .S files; check images link both) or C (the C twins only)")
    set_property(CACHE CY_KERNELS PROPERTY STRINGS ASM C)
    if(NOT CY_KERNELS MATCHES "^(ASM|C)$")
        message(FATAL_ERROR "CY_KERNELS is `${CY_KERNELS}`: ASM or C")
    endif()
endif()

# cy_kernels(LIB KERNELS name... C twin.c... ASM file.S... CHECK wrapper.c)
# The kernels of library LIB (made by cy_library): the functions KERNELS, defined by the C
# twin files (which hold nothing else) and, with the same names, by the assembly files. The
# build takes one side whole: the host tree and the MSP430 tree with CY_KERNELS=C compile the
# C files into LIB; the MSP430 tree with CY_KERNELS=ASM (the default) assembles the .S files
# into LIB and compiles the C files once more, every kernel renamed NAME_c, as the object
# library LIB_ctwin for the check images, with CHECK (the module's wrappers, __wrap_NAME for
# every kernel: tests/target/check/kernel_check.h). target.kernels.LIB checks that the .S
# files, the C twins and KERNELS name the same functions, and docs/kernels.md all of them.
function(cy_kernels lib)
    cmake_parse_arguments(A "" "CHECK" "KERNELS;C;ASM" ${ARGN})
    if(NOT A_KERNELS OR NOT A_C OR NOT A_ASM OR NOT A_CHECK)
        message(FATAL_ERROR "cy_kernels(${lib}): KERNELS, C, ASM and CHECK are all required")
    endif()
    if(NOT CY_TARGET_MSP430 OR CY_KERNELS STREQUAL "C")
        target_sources(${lib} PRIVATE ${A_C})
        return()
    endif()
    target_sources(${lib} PRIVATE ${A_ASM})
    # The twins' names: an -include header renaming every kernel (prototypes, definitions and
    # the twins' calls of each other alike).
    set(names ${CMAKE_CURRENT_BINARY_DIR}/kernels/${lib}_twin_names.h)
    set(text "/* Generated by cy_kernels(${lib}): the C twins' names in check images. */\n")
    foreach(k IN LISTS A_KERNELS)
        string(APPEND text "#define ${k} ${k}_c\n")
    endforeach()
    file(CONFIGURE OUTPUT ${names} CONTENT "${text}" @ONLY)
    add_library(${lib}_ctwin OBJECT ${A_C})
    cy_warnings(${lib}_ctwin)
    target_link_libraries(${lib}_ctwin PRIVATE ${lib})
    target_include_directories(${lib}_ctwin PRIVATE
        $<TARGET_PROPERTY:${lib},INCLUDE_DIRECTORIES>)
    target_compile_definitions(${lib}_ctwin PRIVATE
        $<TARGET_PROPERTY:${lib},COMPILE_DEFINITIONS>)
    target_compile_options(${lib}_ctwin PRIVATE $<TARGET_PROPERTY:${lib},COMPILE_OPTIONS>
        -include ${names})
    add_dependencies(${lib}_ctwin ${lib}) # whatever LIB generates before it compiles
    set(asm)
    foreach(s IN LISTS A_ASM)
        get_filename_component(s ${s} ABSOLUTE)
        list(APPEND asm ${s})
    endforeach()
    set(twins)
    foreach(s IN LISTS A_C)
        get_filename_component(s ${s} ABSOLUTE)
        list(APPEND twins ${s})
    endforeach()
    get_filename_component(check ${A_CHECK} ABSOLUTE)
    set_target_properties(${lib} PROPERTIES CY_KERNELS "${A_KERNELS}" CY_KERNEL_CHECK ${check}
        CY_KERNEL_TWIN ${lib}_ctwin)
    add_test(NAME target.kernels.${lib}
        COMMAND ${Python3_EXECUTABLE} ${PROJECT_SOURCE_DIR}/tools/check_kernels.py
            --nm ${CY_NM} --library $<TARGET_FILE:${lib}> --twins $<TARGET_OBJECTS:${lib}_ctwin>
            --asm ${asm} --c ${twins} --doc ${PROJECT_SOURCE_DIR}/docs/kernels.md
            --kernels ${A_KERNELS}
        COMMAND_EXPAND_LISTS)
    set_tests_properties(target.kernels.${lib} PROPERTIES LABELS target)
endfunction()

# cy_asm_offsets(LIB SOURCE msp430/M_offsets.c HEADER M_offsets.h [DEPENDS generated.h...])
# Offsets, sizes and constants for LIB's assembly, from the C headers at build time (the
# Linux asm-offsets trick): SOURCE lists them with CY_OFFSET(SYM, value) (cmake/cy_offsets.h)
# inside one non-static function; it is compiled for the MSP430 with -S (LIB's include
# directories and definitions) and tools/gen_asm_offsets.py writes HEADER (#define SYM value)
# into the build tree, on LIB's include path. DEPENDS: generated headers SOURCE includes
# (made in the same directory). Only where LIB assembles its .S files.
function(cy_asm_offsets lib)
    cmake_parse_arguments(A "" "SOURCE;HEADER" "DEPENDS" ${ARGN})
    if(NOT CY_TARGET_MSP430 OR NOT CY_KERNELS STREQUAL "ASM")
        return()
    endif()
    set(dir ${CMAKE_CURRENT_BINARY_DIR}/asm_offsets)
    add_library(${lib}_offsets_s OBJECT ${A_SOURCE} ${A_DEPENDS})
    target_compile_options(${lib}_offsets_s PRIVATE -S) # the "object" is assembly text
    # LIB's headers and those of what it links (not LIB itself: LIB waits for the header)
    target_link_libraries(${lib}_offsets_s PRIVATE $<TARGET_PROPERTY:${lib},LINK_LIBRARIES>)
    target_include_directories(${lib}_offsets_s PRIVATE ${PROJECT_SOURCE_DIR}/cmake
        $<TARGET_PROPERTY:${lib},INCLUDE_DIRECTORIES>)
    target_compile_definitions(${lib}_offsets_s PRIVATE
        $<TARGET_PROPERTY:${lib},COMPILE_DEFINITIONS>)
    get_filename_component(src ${A_SOURCE} ABSOLUTE)
    file(RELATIVE_PATH src ${PROJECT_SOURCE_DIR} ${src})
    add_custom_command(OUTPUT ${dir}/${A_HEADER}
        COMMAND ${Python3_EXECUTABLE} ${PROJECT_SOURCE_DIR}/tools/gen_asm_offsets.py
            --input $<TARGET_OBJECTS:${lib}_offsets_s> --output ${dir}/${A_HEADER}
            --source ${src}
        DEPENDS $<TARGET_OBJECTS:${lib}_offsets_s> ${PROJECT_SOURCE_DIR}/tools/gen_asm_offsets.py
        COMMENT "Generating ${A_HEADER} from ${src}"
        VERBATIM)
    add_custom_target(${lib}_offsets DEPENDS ${dir}/${A_HEADER})
    add_dependencies(${lib} ${lib}_offsets)
    target_include_directories(${lib} PRIVATE ${dir})
endfunction()

# The check images, made at the end of the configuration (when every library exists): one
# per vector program that reaches kernels.
function(cy_kernel_check_later name sources links max_cycles timeout args)
    set_property(GLOBAL APPEND PROPERTY CY_VECTOR_PROGRAMS ${name})
    set_property(GLOBAL PROPERTY CY_VP_${name}_SOURCES "${sources}")
    set_property(GLOBAL PROPERTY CY_VP_${name}_LINK "${links}")
    set_property(GLOBAL PROPERTY CY_VP_${name}_MAX_CYCLES "${max_cycles}")
    set_property(GLOBAL PROPERTY CY_VP_${name}_TIMEOUT "${timeout}")
    set_property(GLOBAL PROPERTY CY_VP_${name}_ARGS "${args}")
    get_property(deferred GLOBAL PROPERTY CY_KERNEL_CHECKS_DEFERRED)
    if(NOT deferred)
        set_property(GLOBAL PROPERTY CY_KERNEL_CHECKS_DEFERRED ON)
        cmake_language(DEFER DIRECTORY ${PROJECT_SOURCE_DIR} CALL cy_kernel_checks_now)
    endif()
endfunction()

# The libraries LIBS reach, themselves included (LINK_LIBRARIES, INTERFACE_LINK_LIBRARIES).
function(cy_link_closure out)
    set(seen)
    set(todo ${ARGN})
    while(todo)
        list(POP_FRONT todo t)
        string(REGEX REPLACE "^\\$<LINK_ONLY:(.+)>$" "\\1" t "${t}")
        if(NOT TARGET ${t} OR t IN_LIST seen)
            continue()
        endif()
        list(APPEND seen ${t})
        foreach(prop LINK_LIBRARIES INTERFACE_LINK_LIBRARIES)
            get_target_property(deps ${t} ${prop})
            if(deps)
                list(APPEND todo ${deps})
            endif()
        endforeach()
    endwhile()
    set(${out} ${seen} PARENT_SCOPE)
endfunction()

# cy_kernel_check_scope(PROGRAM lib...)
# Narrows the check image of vector program PROGRAM to the kernels of the libraries named
# (default: every library with kernels the program reaches); none of them with kernels: no
# check image. Only for an image that cannot hold every twin: say why where it is called.
function(cy_kernel_check_scope program)
    set_property(GLOBAL PROPERTY CY_VP_${program}_SCOPE "${ARGN}")
    set_property(GLOBAL PROPERTY CY_VP_${program}_SCOPED ON)
endfunction()

# cy_kernel_check_must_fail(NAME PROGRAM prog PERTURB wrong.c WRAP NAME_c KERNEL kernel)
# The proof that a check image can fail: PROGRAM's check image once more, with PERTURB linked
# in and --wrap=WRAP (PERTURB defines __wrap_WRAP: a C twin made wrong for one input). The
# test target.NAME passes only when the image stops at a KERNEL-MISMATCH naming KERNEL.
function(cy_kernel_check_must_fail name)
    cmake_parse_arguments(A "" "PROGRAM;PERTURB;WRAP;KERNEL" "" ${ARGN})
    if(NOT CY_TARGET_MSP430)
        return()
    endif()
    get_filename_component(perturb ${A_PERTURB} ABSOLUTE)
    set_property(GLOBAL APPEND PROPERTY CY_KERNEL_MUST_FAIL ${name})
    set_property(GLOBAL PROPERTY CY_KMF_${name} "${A_PROGRAM};${perturb};${A_WRAP};${A_KERNEL}")
endfunction()

# The check image IMG of vector program NAME (recorded by cy_vector_program) with the extra
# SOURCES and link OPTIONS; FOUND_OUT: whether the program reaches kernels at all.
function(cy_kernel_check_image img name found_out)
    cmake_parse_arguments(A "" "" "SOURCES;OPTIONS" ${ARGN})
    get_property(sources GLOBAL PROPERTY CY_VP_${name}_SOURCES)
    get_property(links GLOBAL PROPERTY CY_VP_${name}_LINK)
    cy_link_closure(libs ${links})
    get_property(scoped GLOBAL PROPERTY CY_VP_${name}_SCOPED)
    if(scoped)
        get_property(scope GLOBAL PROPERTY CY_VP_${name}_SCOPE)
        set(kept)
        foreach(l IN LISTS libs)
            if(l IN_LIST scope)
                list(APPEND kept ${l})
            endif()
        endforeach()
        set(libs ${kept})
    endif()
    set(wrappers)
    set(twins)
    set(wraps)
    set(incs)
    foreach(l IN LISTS libs)
        get_target_property(kernels ${l} CY_KERNELS)
        if(NOT kernels)
            continue()
        endif()
        get_target_property(check ${l} CY_KERNEL_CHECK)
        get_target_property(twin ${l} CY_KERNEL_TWIN)
        list(APPEND wrappers ${check})
        list(APPEND twins ${twin})
        list(APPEND incs $<TARGET_PROPERTY:${l},INCLUDE_DIRECTORIES>) # the module's own headers
        foreach(k IN LISTS kernels)
            list(APPEND wraps --wrap=${k})
        endforeach()
    endforeach()
    if(NOT twins)
        set(${found_out} OFF PARENT_SCOPE)
        return()
    endif()
    set(${found_out} ON PARENT_SCOPE)
    list(REMOVE_DUPLICATES wrappers)
    cy_msp430_image(${img} KIND test
        SOURCES ${sources} ${wrappers} ${PROJECT_SOURCE_DIR}/tests/target/check/kernel_check.c
            ${A_SOURCES}
        LINK ${links} cy_test_support ${twins})
    target_link_options(${img} PRIVATE ${wraps} ${A_OPTIONS})
    # what the program's own image was given after cy_vector_program (include directories of
    # generated headers, the targets generating them)
    get_target_property(inc ${name}_target INCLUDE_DIRECTORIES)
    if(inc)
        target_include_directories(${img} PRIVATE ${inc})
    endif()
    get_target_property(deps ${name}_target MANUALLY_ADDED_DEPENDENCIES)
    if(deps)
        add_dependencies(${img} ${deps})
    endif()
    target_include_directories(${img} PRIVATE ${PROJECT_SOURCE_DIR}/tests/target/check ${incs})
    target_compile_definitions(${img} PRIVATE CY_KCHECK_IMAGE="${name}")
endfunction()

function(cy_kernel_checks_now)
    if(NOT CY_KERNELS STREQUAL "ASM")
        return()
    endif()
    get_property(programs GLOBAL PROPERTY CY_VECTOR_PROGRAMS)
    foreach(name IN LISTS programs)
        cy_kernel_check_image(${name}_check_target ${name} found)
        if(NOT found)
            continue()
        endif()
        foreach(p MAX_CYCLES TIMEOUT ARGS)
            get_property(${p} GLOBAL PROPERTY CY_VP_${name}_${p})
        endforeach()
        # Both sides of every kernel call run: allow three times the program's cycles.
        if(NOT MAX_CYCLES)
            set(MAX_CYCLES 200000000)
        endif()
        math(EXPR MAX_CYCLES "${MAX_CYCLES} * 3")
        set(extra MAX_CYCLES ${MAX_CYCLES})
        if(TIMEOUT)
            math(EXPR TIMEOUT "${TIMEOUT} * 2")
            list(APPEND extra TIMEOUT ${TIMEOUT})
        endif()
        cy_target_test(${name}_check IMAGE ${name}_check_target ${extra}
            ARGS --compare-cmd ${CY_HOST_BIN_DIR}/${name} ${ARGS})
    endforeach()
    get_property(must_fail GLOBAL PROPERTY CY_KERNEL_MUST_FAIL)
    foreach(name IN LISTS must_fail)
        get_property(spec GLOBAL PROPERTY CY_KMF_${name})
        list(GET spec 0 program)
        list(GET spec 1 perturb)
        list(GET spec 2 wrap)
        list(GET spec 3 kernel)
        cy_kernel_check_image(${name}_target ${program} found SOURCES ${perturb}
            OPTIONS --wrap=${wrap})
        if(NOT found)
            message(FATAL_ERROR "cy_kernel_check_must_fail(${name}): ${program} reaches no kernels")
        endif()
        get_property(max_cycles GLOBAL PROPERTY CY_VP_${program}_MAX_CYCLES)
        if(NOT max_cycles)
            set(max_cycles 200000000)
        endif()
        math(EXPR max_cycles "${max_cycles} * 3")
        cy_target_test(${name} IMAGE ${name}_target MAX_CYCLES ${max_cycles}
            ARGS --expect-kernel-mismatch ${kernel})
    endforeach()
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
