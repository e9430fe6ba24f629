/* The header is C (C11, -Wpedantic) and a C program links libvisnav: create, step without a frame, destroy;
   exit 0 when every answer is as documented. */
#include <stdio.h>
#include <string.h>

#include "visnav/visnav.h"

int main(int argc, char** argv) {
  if (argc != 4) {
    fputs("usage: capi_c_smoke CONFIG CAMERA MODEL\n", stderr);
    return 2;
  }
  if (visnav_abi_version() != VISNAV_ABI_VERSION) {
    fprintf(stderr, "ABI %d, header %d\n", visnav_abi_version(), VISNAV_ABI_VERSION);
    return 1;
  }
  visnav_handle* h = NULL;
  char err[256];
  int rc = visnav_create(argv[1], argv[2], argv[3], &h, err, sizeof err);
  if (rc != VISNAV_OK) {
    fprintf(stderr, "visnav_create: %s: %s\n", visnav_status_text(rc), err);
    return 1;
  }
  visnav_solution sol;
  rc = visnav_step(h, NULL, 0, 0, 0, 0, 1000, &sol);
  if (rc != VISNAV_OK || sol.cycle_number != 1 || sol.frame_received != 0 ||
      strcmp(visnav_mode_name(sol.mode), "far_range") != 0) {
    fprintf(stderr, "visnav_step: rc %d, cycle %llu, mode %s\n", rc, (unsigned long long)sol.cycle_number,
            visnav_mode_name(sol.mode));
    return 1;
  }
  printf("libvisnav %s (ABI %d): %s, faults 0x%x\n", visnav_version(), visnav_abi_version(),
         visnav_mode_name(sol.mode), sol.fault_bits);
  visnav_destroy(h);
  return 0;
}
