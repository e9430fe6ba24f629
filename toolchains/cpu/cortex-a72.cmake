# Cortex-A72 (ARMv8.0-A, out-of-order 3-wide, NEON): the larger flight-computer option
# (-DVISNAV_TARGET_CPU=cortex-a72).
set(CMAKE_C_FLAGS_INIT "-mcpu=cortex-a72")
set(CMAKE_CXX_FLAGS_INIT "-mcpu=cortex-a72")
