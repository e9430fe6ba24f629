// visnav_step allocates nothing: the allocation counter (operator new everywhere, and the malloc family
// outside ASan) over the whole 750 m -> 5 m approach (far range, acquisition, near range), frames missing,
// commands and a re-run from far range: 0 allocations after visnav_create.
#include <cstdint>

#include "alloc_counter.hpp"
#include "capi_test_support.hpp"
#include "gtest/gtest.h"
#include "visnav/visnav.h"

namespace {

TEST(CApiNoAlloc, CreateAllocatesTheCounterSeesIntoTheLibrary) {
  // Positive control: the counter sees allocations made inside libvisnav.so (else a zero proves nothing).
  const std::uint64_t before = visnav::test::allocationCount();
  visnav_handle* h = nullptr;
  char err[256];
  ASSERT_EQ(visnav_create(visnav::test::configPath().c_str(), visnav::test::cameraPath().c_str(),
                          visnav::test::modelPath().c_str(), &h, err, sizeof(err)),
            VISNAV_OK)
      << err;
  EXPECT_GT(visnav::test::allocationCount(), before + 10);
  visnav_destroy(h);
}

TEST(CApiNoAlloc, StepAllocatesNothingInAnyMode) {
  const visnav::test::RenderedSequence& seq = visnav::test::fullApproachFrames();
  ASSERT_EQ(seq.frames.size(), 198U);
  visnav_handle* h = nullptr;
  char err[256];
  ASSERT_EQ(visnav_create(visnav::test::configPath().c_str(), visnav::test::cameraPath().c_str(),
                          visnav::test::modelPath().c_str(), &h, err, sizeof(err)),
            VISNAV_OK)
      << err;
  ASSERT_EQ(visnav_set_timing(h, 1), VISNAV_OK);  // the clock path too
  int per_mode[4] = {0, 0, 0, 0};
  int steps = 0;
  const std::uint64_t before = visnav::test::allocationCount();
  std::int64_t t_ns = 0;
  for (int pass = 0; pass < 2; ++pass) {
    for (std::size_t i = 0; i < seq.frames.size(); ++i) {
      const visnav::test::RenderedFrame& f = seq.frames[i];
      t_ns = f.exposure_time_ns + pass * 100'000'000'000LL;
      visnav_solution sol;
      const bool drop = i % 37 == 36;  // a missing frame now and then
      const int rc = drop ? visnav_step(h, nullptr, 0, 0, 0, 0, t_ns, &sol)
                          : visnav_step(h, f.pixels.data(), seq.width, seq.height, 0, 8, t_ns, &sol);
      if (rc != VISNAV_OK) {
        ADD_FAILURE() << visnav_last_error(h);
        break;
      }
      ++per_mode[sol.mode];
      ++steps;
    }
    visnav_command_ack ack;
    visnav_command(h, VISNAV_COMMAND_FORCE_FAR_RANGE, 1, &ack);  // second pass from far range again
  }
  const std::uint64_t allocations = visnav::test::allocationCount() - before;
  visnav_destroy(h);
  EXPECT_EQ(allocations, 0U) << "over " << steps << " steps (malloc counted: " << visnav::test::countsMalloc()
                             << ")";
  EXPECT_EQ(steps, 396);
  EXPECT_GT(per_mode[VISNAV_MODE_FAR_RANGE], 200);
  // Near range is reached from far range only through an acquisition (beside far range by default).
  EXPECT_GT(per_mode[VISNAV_MODE_NEAR_RANGE], 100);
}

}  // namespace
