#pragma once
// Helpers shared by the experiment drivers: scenes as JSON (saved beside the results so
// `refract render` re-renders them), image error, log-log fits.
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include <refract/core/render.h>
#include <refract/core/scene.h>
#include <refract/experiments/experiment.h>

namespace refract::experiments {

// Parses a scene built in code (the same parser as scene files; `name` is used in errors).
Scene scene_from_json(const nlohmann::json& j, const std::string& name);

// Writes `j` pretty-printed (2-space indent, trailing newline) to DIR/NAME atomically.
void save_json(const std::string& dir, const std::string& name, const nlohmann::json& j);
std::string json_text(const nlohmann::json& j);  // the exact text save_json writes

// Root-mean-square difference over every pixel and channel; the images must match in size.
double rmse(const Image& a, const Image& b);

// Least-squares line through (log x, log y): slope and intercept (natural logs).
struct LineFit {
    double slope = 0, intercept = 0;
};
LineFit loglog_fit(const std::vector<double>& x, const std::vector<double>& y);

// Creates DIR (and parents); throws InputError naming it when it cannot be created or
// written (bad input: exit 2). True when DIR itself did not exist before.
bool ensure_dir(const std::string& dir);

// JSON helpers for scene literals.
nlohmann::json vec(double x, double y, double z);

}  // namespace refract::experiments
