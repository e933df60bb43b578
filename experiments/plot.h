#pragma once
// Output of the experiment drivers: text files written atomically, CSV tables and
// figures drawn by gnuplot (PNG through pngcairo and PDF through pdfcairo). Each figure
// keeps its script beside it (`NAME.gp`), so `gnuplot NAME.gp` in that directory redraws
// it from the CSV files.
#include <string>
#include <vector>

namespace refract::experiments {

// Writes `text` to a temporary name beside `path` and renames it: never a half-written
// file (geometry/atomic_file.h). Throws InputError naming the path on failure.
void write_text_atomic(const std::string& path, const std::string& text);

// Number formatting for CSV cells: shortest round-trip form ("%.17g" trimmed to the
// fewest digits that read back to the same double).
std::string fmt(double v);
std::string fmt(double v, int significant);  // fixed number of significant digits
// A CSV cell from text: quoted when it holds a comma or a quote (quotes doubled, newlines
// dropped), as it is otherwise.
std::string csv_quote(const std::string& s);

// A CSV table: a header and rows of cells (already formatted).
struct Csv {
    std::vector<std::string> header;
    std::vector<std::vector<std::string>> rows;
    void add(std::vector<std::string> row) { rows.push_back(std::move(row)); }
    std::string text() const;
    // As a markdown table; `significant` > 0: numeric cells with that many significant digits.
    std::string markdown(int significant = 0) const;
};
void write_csv(const std::string& path, const Csv& table);
// Reads a CSV written by write_csv (tests, the reproduce index); throws on a bad file.
Csv read_csv(const std::string& path);

struct FigureSize {  // FigureSize{width_px, height_px, width_in, height_in}
    int width_px = 800, height_px = 560;  // PNG
    double width_in = 6.0, height_in = 4.2;  // PDF
};

// Writes DIR/NAME.gp (terminal set-up for PNG and PDF, then `body` once per terminal)
// and runs gnuplot in DIR with a time limit, producing DIR/NAME.png and DIR/NAME.pdf
// (written under temporary names and renamed). `body` uses file names relative to DIR.
// Throws std::runtime_error with one line if gnuplot is missing, fails or times out.
void gnuplot_figure(const std::string& dir, const std::string& name, const std::string& body,
                    const FigureSize& size = {}, double time_limit_s = 120);

// A grid of images (PNG files in DIR, all of the same size) with a caption above each
// and a title above all, drawn by gnuplot as DIR/NAME.png and .pdf. `panel_px` is the
// width of one panel in the PNG.
struct Panel {
    std::string file;
    std::string caption;
};
void image_grid_figure(const std::string& dir, const std::string& name, int rows, int cols,
                       const std::vector<Panel>& panels, const std::string& title, double aspect_h_over_w = 1.0,
                       int panel_px = 260);

// Colour maps for gnuplot figures: `set palette defined (...)` lines of perceptually uniform
// maps (matplotlib's viridis, 17 stops; lightness rises monotonically, readable in grey and
// by colour-blind readers).
std::string viridis_palette();

// Contour levels at round values for data within [lo, hi]: a step of 1, 2, 2.5 or 5 × 10^k,
// the smallest giving at most `max_levels` levels strictly inside (lo, hi); `format` is the
// printf format that labels them (as many decimals as the step needs). lo < hi, finite.
struct ContourLevels {
    double start = 0, step = 1, end = 0;
    int count = 0;
    std::string format;  // "%.2f"
};
ContourLevels round_contour_levels(double lo, double hi, int max_levels = 6);

// True when a gnuplot executable is found on PATH.
bool gnuplot_available();

}  // namespace refract::experiments
