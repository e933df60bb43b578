#pragma once
// One driver per paper and study; each is registered in experiments/experiment.cpp.
#include "experiments/birefringence.h"
#include "experiments/experiment.h"
#include "experiments/gem_cuts.h"
#include "experiments/gem_geometry.h"
#include "experiments/gem_metrics_experiment.h"
#include "experiments/ohtsuka1998.h"
#include "experiments/ohtsuka1998_result.h"
#include "experiments/optics_bench.h"
#include "experiments/polarisation.h"
#include "experiments/rtiow.h"
#include "experiments/yasuda1984.h"

namespace refract::experiments {
}  // namespace refract::experiments
