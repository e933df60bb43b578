#pragma once
// Experiment drivers: `refract experiment NAME -o DIR`. Each writes CSV, figures (PNG
// and PDF through gnuplot) and a short markdown summary `DIR/summary.md`.
#include <functional>
#include <string>
#include <vector>

namespace refract::experiments {

struct ExperimentOptions {
    std::string out_dir;
    int threads = 0;
    bool quick = false;  // smaller images and fewer samples (tests, smoke runs)
};

struct Experiment {
    std::string name;
    std::string description;
    std::function<void(const ExperimentOptions&)> run;
};

// All experiments, in the order `refract reproduce` runs them.
const std::vector<Experiment>& all();
const Experiment& find(const std::string& name);  // InputError listing the names

}  // namespace refract::experiments
