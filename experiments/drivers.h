#pragma once
// One driver per paper and study; each is registered in experiments/experiment.cpp.
#include <refract/experiments/birefringence.h>
#include <refract/experiments/experiment.h>
#include <refract/experiments/gem_cuts.h>
#include <refract/experiments/gem_geometry.h>
#include <refract/experiments/gem_metrics_experiment.h>
#include <refract/experiments/grin.h>
#include <refract/experiments/grin_layers.h>
#include <refract/experiments/ohtsuka1998.h>
#include <refract/experiments/ohtsuka1998_result.h>
#include <refract/experiments/optics_bench.h>
#include <refract/experiments/polarisation.h>
#include <refract/experiments/rtiow.h>
#include <refract/experiments/yasuda1984.h>

namespace refract::experiments {
}  // namespace refract::experiments
