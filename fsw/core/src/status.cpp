#include "visnav/core/status.hpp"

namespace visnav {

const char* toString(Status status) {
  switch (status) {
    case Status::kOk: return "ok";
    case Status::kInvalidArgument: return "invalid argument";
    case Status::kCapacityExceeded: return "capacity exceeded";
    case Status::kNotEnoughData: return "not enough data";
    case Status::kNotConverged: return "not converged";
    case Status::kDegenerate: return "degenerate";
    case Status::kOutOfImage: return "out of image";
    case Status::kGaveUp: return "gave up";
  }
  return "unknown";
}

}  // namespace visnav
