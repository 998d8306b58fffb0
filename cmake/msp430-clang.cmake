# Toolchain: Debian's clang-16 for msp430-elf, linked with ld.lld-16 directly (the clang
# driver would look for msp430-elf-ld, which Debian does not ship). Part: MSP430F2618.
# clang 16 has no -mmcu entry for the F2618 (an MSP430X part): the images are built for the
# classic MSP430 ISA (clang's default CPU for msp430-elf, code and constants below 64 KB, so
# mspdebug's simulator runs them unchanged) with the part's 16 x 16 hardware multiplier.
set(CMAKE_SYSTEM_NAME Generic)
set(CMAKE_SYSTEM_PROCESSOR msp430)
set(CY_TARGET_MSP430 ON)

set(CY_MSP430_ARCH_FLAGS "-mhwmult=16bit" CACHE STRING "Code generation flags of the part (16 x 16 hardware multiplier)")

find_program(CY_CLANG NAMES clang-16 REQUIRED)
find_program(CY_LLD NAMES ld.lld-16 REQUIRED)
find_program(CMAKE_AR NAMES llvm-ar-16 REQUIRED)
find_program(CMAKE_RANLIB NAMES llvm-ranlib-16 REQUIRED)
find_program(CY_READELF NAMES llvm-readelf-16 REQUIRED)
find_program(CY_OBJDUMP NAMES llvm-objdump-16 REQUIRED)

set(CMAKE_C_COMPILER ${CY_CLANG})
set(CMAKE_C_COMPILER_TARGET msp430-elf)
set(CMAKE_ASM_COMPILER ${CY_CLANG})
set(CMAKE_ASM_COMPILER_TARGET msp430-elf)
set(CMAKE_TRY_COMPILE_TARGET_TYPE STATIC_LIBRARY)

set(CMAKE_C_FLAGS_INIT "${CY_MSP430_ARCH_FLAGS} -ffreestanding -fno-builtin -ffunction-sections -fdata-sections")
set(CMAKE_ASM_FLAGS_INIT "${CY_MSP430_ARCH_FLAGS}")
set(CMAKE_C_LINK_EXECUTABLE "${CY_LLD} <LINK_FLAGS> <OBJECTS> -o <TARGET> <LINK_LIBRARIES>")
set(CMAKE_EXECUTABLE_SUFFIX_C .elf)
set(CMAKE_EXECUTABLE_SUFFIX .elf)

set(CMAKE_FIND_ROOT_PATH_MODE_PROGRAM NEVER)
set(CMAKE_FIND_ROOT_PATH_MODE_LIBRARY ONLY)
set(CMAKE_FIND_ROOT_PATH_MODE_INCLUDE ONLY)
