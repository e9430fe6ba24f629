# Cortex-A53 (ARMv8.0-A, in-order dual-issue, NEON, 1.2 GHz on the flight computer): the default target core.
# -mcpu sets both the instruction set (armv8-a + crc, NEON) and the scheduling model; gcc also enables the
# A53 erratum 835769/843419 workarounds for this core.
set(CMAKE_C_FLAGS_INIT "-mcpu=cortex-a53")
set(CMAKE_CXX_FLAGS_INIT "-mcpu=cortex-a53")
