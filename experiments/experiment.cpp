#include "experiments/experiment.h"

#include "experiments/drivers.h"
#include "geometry/error.h"

namespace refract::experiments {

const std::vector<Experiment>& all() {
    static const std::vector<Experiment> list{
        // name, description, driver (experiments/drivers.h)
    };
    return list;
}

const Experiment& find(const std::string& name) {
    std::string names;
    for (const auto& e : all()) {
        if (e.name == name) return e;
        names += (names.empty() ? "" : ", ") + e.name;
    }
    throw InputError("experiment '" + name + "': unknown (known: " + names + ")");
}

}  // namespace refract::experiments
