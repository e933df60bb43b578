#include <refract/experiments/plot.h>

#include <algorithm>
#include <atomic>
#include <cerrno>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fcntl.h>
#include <filesystem>
#include <fstream>
#include <signal.h>
#include <sstream>
#include <stdexcept>
#include <sys/stat.h>
#include <sys/wait.h>
#include <thread>
#include <unistd.h>

#include <refract/core/provenance.h>
#include <refract/geometry/atomic_file.h>
#include <refract/geometry/error.h>
#include <refract/geometry/format.h>
#include <refract/validation/process.h>


namespace refract::experiments {
namespace fs = std::filesystem;

namespace {

std::string gnuplot_quote(const std::string& s) {  // single-quoted gnuplot string
    std::string out = "'";
    for (char c : s) out += (c == '\'') ? std::string("''") : std::string(1, c);
    return out + "'";
}

std::string last_line(const std::string& text) {
    std::istringstream in(text);
    std::string line, last;
    while (std::getline(in, line))
        if (line.find_first_not_of(" \t\r^") != std::string::npos) last = line;
    return last;
}

}  // namespace

void write_text_atomic(const std::string& path, const std::string& text) { write_file_atomic(path, text); }

std::string fmt(double v) { return format_shortest(v); }  // geometry/format.h

std::string fmt(double v, int significant) { return format_significant(v, significant); }

std::string csv_quote(const std::string& s) {
    if (s.find_first_of(",\"\n") == std::string::npos) return s;
    std::string q = "\"";
    for (const char c : s) {
        if (c == '\n') continue;
        q += c;
        if (c == '"') q += '"';
    }
    return q + "\"";
}

std::string Csv::text() const {
    std::string s;
    auto line = [&s](const std::vector<std::string>& cells) {
        for (size_t k = 0; k < cells.size(); ++k) s += (k ? "," : "") + cells[k];
        s += "\n";
    };
    line(header);
    for (const auto& r : rows) line(r);
    return s;
}

std::string Csv::markdown(int significant) const {
    std::ostringstream t;
    t << "|";
    for (const auto& h : header) t << " " << h << " |";
    t << "\n|";
    for (size_t k = 0; k < header.size(); ++k) t << "---|";
    t << "\n";
    for (const auto& row : rows) {
        t << "|";
        for (const auto& v : row) {
            char* end = nullptr;
            const double x = std::strtod(v.c_str(), &end);
            const bool number = significant > 0 && !v.empty() && end && *end == '\0';
            t << " " << (number ? fmt(x, significant) : v) << " |";
        }
        t << "\n";
    }
    return t.str();
}

void write_csv(const std::string& path, const Csv& table) {
    for (const auto& r : table.rows)
        if (r.size() != table.header.size())
            throw std::logic_error(path + ": a row has " + std::to_string(r.size()) + " cells, the header " +
                                   std::to_string(table.header.size()));
    write_text_atomic(path, table.text());
    try {
        write_csv_sidecar(path);  // the run's settings beside it (core/provenance.h)
    } catch (...) {
        std::error_code ec;
        fs::remove(path, ec);  // no CSV without its settings
        throw;
    }
}

Csv read_csv(const std::string& path) {
    std::ifstream in(path);
    if (!in) throw std::runtime_error(path + ": cannot open CSV file");
    Csv t;
    std::string line;
    bool first = true;
    while (std::getline(in, line)) {
        if (line.empty()) continue;
        std::vector<std::string> cells;
        std::stringstream ss(line);
        std::string cell;
        while (std::getline(ss, cell, ',')) cells.push_back(cell);
        if (first) t.header = cells;
        else t.rows.push_back(cells);
        first = false;
    }
    return t;
}

bool gnuplot_available() {
    const char* path = std::getenv("PATH");
    if (!path) return false;
    std::stringstream ss(path);
    std::string dir;
    while (std::getline(ss, dir, ':')) {
        if (dir.empty()) continue;
        if (::access((fs::path(dir) / "gnuplot").c_str(), X_OK) == 0) return true;
    }
    return false;
}

void gnuplot_figure(const std::string& dir, const std::string& name, const std::string& body, const FigureSize& size,
                    double time_limit_s) {
    const fs::path base = fs::path(dir) / name;
    std::ostringstream gp;
    gp << "# " << name << ": drawn by refract; run `gnuplot " << name << ".gp` in this directory to redraw\n"
       << "# " << name << ".png and " << name << ".pdf from the CSV files beside it.\n"
       << "if (!exists(\"outbase\")) outbase = \"" << name << "\"\n"
       << "do for [fmt in \"png pdf\"] {\n"
       << "reset\n"
       << "if (fmt eq \"png\") {\n"
       << "  set terminal pngcairo size " << size.width_px << "," << size.height_px
       << " enhanced font \"Sans,12\" linewidth 1.5\n"
       << "} else {\n"
       << "  set terminal pdfcairo size " << size.width_in << "in," << size.height_in
       << "in enhanced font \"Sans,9\" linewidth 1.5\n"
       << "}\n"
       << "set output outbase.\".\".fmt\n"
       << body << (body.empty() || body.back() == '\n' ? "" : "\n")
       << "set output\n"
       << "}\n";
    write_text_atomic(base.string() + ".gp", gp.str());

    if (!gnuplot_available())
        throw std::runtime_error("gnuplot not found on PATH: install it (Debian: apt-get install gnuplot-nox) to draw " +
                                 base.string() + ".png/.pdf; the CSV files and " + name + ".gp are written");

    // gnuplot writes the figures and its log into a private directory beside them
    // (geometry/atomic_file.h PrivateDir), reached through /proc/self/fd/N, a descriptor it
    // inherits: no name in the output directory is followed. They are renamed into place
    // from there.
    const PrivateDir priv(base.string());
    const int inherited = ::fcntl(priv.fd(), F_DUPFD, 3);  // without FD_CLOEXEC: gnuplot inherits it
    if (inherited < 0) throw std::runtime_error(base.string() + ": cannot pass a directory to gnuplot: " + std::strerror(errno));
    struct Closer {
        int fd;
        ~Closer() { ::close(fd); }
    } closer{inherited};
    const bool proc = ::access("/proc/self/fd", X_OK) == 0;
    const std::string via = proc ? "/proc/self/fd/" + std::to_string(inherited) : priv.path();
    const std::string setup = "cd " + gnuplot_quote(dir) + "; outbase=" + gnuplot_quote(via + "/" + name);
    const std::string script = name + ".gp";
    // The one subprocess runner (validation/process.h): gnuplot that hangs is killed.
    validation::ProcessOptions popt;
    popt.stdout_path = via + "/gnuplot.log";
    popt.timeout_seconds = time_limit_s;
    validation::ProcessResult run;
    try {
        run = validation::run_process({"gnuplot", "-e", setup, script}, popt);
    } catch (const InputError& e) {
        throw std::runtime_error("cannot start gnuplot for " + base.string() + ".gp: " + e.what());
    }
    if (run.exited && run.status == 127)  // the child could not execute gnuplot
        throw std::runtime_error("cannot start gnuplot for " + base.string() + ".gp");
    std::string log_text;
    try {
        log_text = read_own_file("gnuplot.log", "gnuplot's log", priv.fd());
    } catch (const InputError&) {  // not what gnuplot wrote: not quoted
    }
    if (run.timed_out)
        throw std::runtime_error("gnuplot " + base.string() + ".gp: killed after " + fmt(time_limit_s, 3) + " s");
    if (!run.ok()) throw std::runtime_error("gnuplot " + base.string() + ".gp failed: " + last_line(log_text));
    for (const char* ext : {".png", ".pdf"}) {
        struct stat st {};
        if (::fstatat(priv.fd(), (name + ext).c_str(), &st, AT_SYMLINK_NOFOLLOW) != 0)
            throw std::runtime_error("gnuplot " + base.string() + ".gp wrote no " + ext + " file: " + last_line(log_text));
        try {
            priv.move_out(name + ext, base.filename().string() + ext, base.string() + ext);
        } catch (const InputError& e) {
            throw std::runtime_error(std::string(e.what()) + " (cannot rename the figure into place)");
        }
    }
}

std::string viridis_palette() {
    return "set palette defined (0 '#440154', 0.0625 '#48186a', 0.125 '#472d7b', 0.1875 '#424086', "
           "0.25 '#3b528b', 0.3125 '#33638d', 0.375 '#2c728e', 0.4375 '#26828e', 0.5 '#21918c', "
           "0.5625 '#1fa088', 0.625 '#28ae80', 0.6875 '#3fbc73', 0.75 '#5ec962', 0.8125 '#84d44b', "
           "0.875 '#addc30', 0.9375 '#d8e219', 1 '#fde725')";
}

ContourLevels round_contour_levels(double lo, double hi, int max_levels) {
    if (!(lo < hi) || !std::isfinite(lo) || !std::isfinite(hi) || max_levels < 1)
        throw std::logic_error("round_contour_levels: needs finite lo < hi and max_levels >= 1");
    const double decade = std::pow(10.0, std::floor(std::log10(hi - lo)) - 2);
    for (int e = 0; e < 5; ++e)
        for (double m : {1.0, 2.0, 2.5, 5.0}) {
            const double step = m * decade * std::pow(10.0, e);
            // Strictly inside (lo, hi), with a tolerance for lo or hi on a level.
            const double first = std::floor(lo / step + 1e-9) + 1, last = std::ceil(hi / step - 1e-9) - 1;
            const int count = static_cast<int>(last - first) + 1;
            if (count > max_levels) continue;
            ContourLevels c;
            c.step = step;
            c.start = first * step;
            c.end = last * step;
            c.count = std::max(count, 0);
            const int decimals = std::max(0, -static_cast<int>(std::floor(std::log10(step) + 1e-9))) + (m == 2.5 ? 1 : 0);
            c.format = "%." + std::to_string(decimals) + "f";
            return c;
        }
    throw std::logic_error("round_contour_levels: no step found");  // unreachable: 10^(e+log) covers the range
}

void image_grid_figure(const std::string& dir, const std::string& name, int rows, int cols,
                       const std::vector<Panel>& panels, const std::string& title, double aspect, int panel_px) {
    // Pixel budget: panels, a caption line above each, the title line on top.
    const double caption_px = 30, title_px = 44;
    const double w = cols * panel_px, h = rows * (panel_px * aspect + caption_px) + title_px;
    std::ostringstream b;
    b << "set multiplot layout " << rows << "," << cols << " margins 0.004,0.996,0.004," << 1 - title_px / h
      << " spacing 0.006," << caption_px / h << " title \"" << title << "\" font \",13\"\n"
      << "unset border; unset tics; unset key; set size ratio -1\n";
    for (const auto& p : panels)
        b << "set title \"" << p.caption << "\" offset 0,-0.6\n"
          << "plot '" << p.file << "' binary filetype=png with rgbimage\n";
    b << "unset multiplot\n";
    const FigureSize size{static_cast<int>(w), static_cast<int>(h), w / 130.0, h / 130.0};
    gnuplot_figure(dir, name, b.str(), size);
}

}  // namespace refract::experiments
