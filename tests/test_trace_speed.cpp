// The ray-query figures of docs/performance.md stay within 2× of what `refract bench
// --trace` measures: a short run of the benchmark (CPU time of its thread, the best of its
// rounds, so that a loaded machine slows it little) against the figures the document
// quotes from the full run's output.
#include <catch2/catch.hpp>

#include <cstdio>
#include <fstream>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

namespace {

std::string command_output(const std::string& cmd) {
    std::string out;
    if (FILE* p = popen(cmd.c_str(), "r")) {
        char buf[4096];
        size_t k;
        while ((k = fread(buf, 1, sizeof buf, p)) > 0) out.append(buf, k);
        pclose(p);
    }
    return out;
}

// The number after "best " on the line that contains `label` (the benchmark's wording).
std::optional<double> best_of(const std::string& text, const std::string& label) {
    const size_t at = text.find(label);
    if (at == std::string::npos) return std::nullopt;
    const size_t end = text.find('\n', at);
    const std::string line = text.substr(at, end == std::string::npos ? std::string::npos : end - at);
    const size_t b = line.find("best ");
    if (b == std::string::npos) return std::nullopt;
    return std::stod(line.substr(b + 5));
}

}  // namespace

TEST_CASE("Ray queries: the documented trace and trace_rays figures are within 2x of the benchmark's", "[trace][bench]") {
    std::ifstream f(REFRACT_SOURCE_DIR "/docs/performance.md");
    std::stringstream doc;
    doc << f.rdbuf();
    // A benchmark on a loaded machine (ctest -j, other processes) can be slowed past 2x
    // in one run: the figure counts as kept when one of three short runs is within 2x.
    const std::vector<std::string> labels = {"trace, one ray through a session:", "trace_rays, one thread:"};
    std::string run;
    bool within = false;
    for (int attempt = 0; attempt < 3 && !within; ++attempt) {
        run = command_output(std::string(REFRACT_EXE) + " bench --trace --trace-quick --rounds 3 2>&1");
        within = true;
        for (const std::string& label : labels) {
            const auto documented = best_of(doc.str(), label), measured = best_of(run, label);
            within = within && documented && measured && *measured <= 2 * *documented &&
                     *measured >= 0.5 * *documented;
        }
    }
    INFO(run);
    for (const std::string& label : labels) {
        INFO(label);
        const auto documented = best_of(doc.str(), label), measured = best_of(run, label);
        REQUIRE(documented);
        REQUIRE(measured);
        CHECK(*measured <= 2 * *documented);
        CHECK(*measured >= 0.5 * *documented);
    }
}
