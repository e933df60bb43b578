#pragma once
// A sweep into one CSV file, resumable (docs/gem-metrics.md, "Sweep"): every finished row
// is appended to a journal beside the output (OUT.journal; under MPI, rank r > 0 appends
// to OUT.journal.r) with one write() per line, so an interrupted sweep (Ctrl-C, kill)
// loses no finished row; the journal's first line is the sweep's fingerprint, and a
// journal is resumed only under the same fingerprint. When every row is in, the CSV is
// written atomically in cut order and the journals are removed.
#include <cstdint>
#include <map>
#include <string>

#include <nlohmann/json_fwd.hpp>

#include <refract/experiments/gem_sweep.h>

namespace refract::experiments::gem_sweep {

// Finished rows by cut index: their CSV lines (no newline).
using Lines = std::map<std::int64_t, std::string>;

std::string journal_path(const std::string& out);               // OUT.journal
std::string part_journal_path(const std::string& out, int rank);  // OUT.journal.RANK

// Reads OUT.journal and any part journals an earlier (MPI) run left, checks their
// fingerprint (InputError naming the journal when it belongs to another sweep), drops a
// torn last line, rewrites OUT.journal (atomically) with every finished row and removes
// the parts. Returns the finished rows; `*found` (when given) tells whether there was
// any journal. Journals are opened without following links and must be regular files
// (InputError naming the journal otherwise, quoting none of it).
Lines recover(const Sweep& sweep, const std::string& out, bool* found = nullptr);

// Removes the journal `path` a run began when it is refused after starting (a regular
// file only: nothing else at that name is touched).
void remove_new_journal(const std::string& path);

// Appends rows to a journal, creating it with the fingerprint line when it is new.
class JournalWriter {
public:
    JournalWriter(const std::string& path, const std::string& fingerprint);
    ~JournalWriter();
    JournalWriter(const JournalWriter&) = delete;
    JournalWriter& operator=(const JournalWriter&) = delete;
    void append(const std::string& line);  // one write() of line + '\n'; InputError on failure

private:
    std::string path_;
    int fd_ = -1;
};

// The index at the start of a CSV line, or -1.
std::int64_t line_index(const std::string& line);

// The CSV text: header, then the lines in index order.
std::string csv_text(const Lines& lines);

// The sweep's settings as JSON (axes, base cut, material, rays, wavelengths, polarisation
// model, seed, fingerprint): the CSV's sidecar OUT + ".json" (core/provenance.h).
nlohmann::json settings_json(const Sweep& sweep);

// Writes the CSV atomically once `lines` holds every cut of the sweep (InputError
// otherwise) and its sidecar OUT + ".json" (settings_json), then removes the journal.
void finish(const Sweep& sweep, const std::string& out, const Lines& lines);

// Refuses (InputError naming `out`), before any work, an output that cannot be written: a
// missing or unwritable directory, a directory at its name.
void check_output(const std::string& out);

// The whole sweep in one process (check_output first): recover, evaluate the missing cuts on `threads`
// threads (journalled), finish. `progress(done, total)` after each row, if given.
struct FileRunStats {
    std::int64_t total = 0, resumed = 0, computed = 0, impossible = 0;
};
FileRunStats run_to_file(const Sweep& sweep, const std::string& out, int threads,
                         const std::function<void(std::int64_t, std::int64_t)>& progress = {});

}  // namespace refract::experiments::gem_sweep
