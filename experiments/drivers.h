#pragma once
// One driver per paper and study; each is registered in experiments/experiment.cpp.
#include "experiments/experiment.h"

namespace refract::experiments {
}  // namespace refract::experiments
