// refract report OUT: (re)writes the HTML report of a results directory, OUT/index.html and a
// page per section, from what OUT holds (`refract experiment NAME -o OUT/NAME` results, the
// validation suite's OUT/validation/); `reproduce` writes the same report at its end.
#include <filesystem>
#include <iostream>

#include "cli/commands.h"
#include <refract/experiments/report_site.h>
#include <refract/geometry/error.h>

namespace report_command {

refract::cli::Registrar reg{92, [](CLI::App& app) {
    auto out = std::make_shared<std::string>();
    auto* sub = app.add_subcommand(
        "report", "Write OUT/index.html and a page per experiment from the results in OUT (as reproduce does)");
    sub->add_option("out", *out, "Results directory (holding NAME/ per experiment, validation/)")->required();
    sub->callback([out] {
        namespace ex = refract::experiments;
        std::error_code ec;
        if (!std::filesystem::is_directory(*out, ec))
            throw refract::InputError(*out + ": not a directory (report: OUT must hold the results)");
        const auto sections = ex::report_sections_found(*out);
        if (sections.empty())
            throw refract::InputError(*out + ": no experiment or validation results in it (report: run `refract "
                                      "experiment NAME -o " + *out + "/NAME` first)");
        ex::write_report_site(*out, sections);
        std::cout << "report: " << sections.size() << " section(s), open "
                  << (std::filesystem::path(*out) / "index.html").string() << std::endl;
    });
}};

}  // namespace report_command
using namespace report_command;
