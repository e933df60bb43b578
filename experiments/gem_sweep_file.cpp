#include <refract/experiments/gem_sweep_file.h>

#include <cerrno>
#include <cstring>
#include <filesystem>

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <nlohmann/json.hpp>

#include <refract/core/provenance.h>
#include <refract/geometry/atomic_file.h>
#include <refract/geometry/error.h>

namespace refract::experiments::gem_sweep {

namespace fs = std::filesystem;

std::string journal_path(const std::string& out) { return out + ".journal"; }
std::string part_journal_path(const std::string& out, int rank) { return out + ".journal." + std::to_string(rank); }

std::int64_t line_index(const std::string& line) {
    std::int64_t v = 0;
    size_t i = 0;
    for (; i < line.size() && line[i] >= '0' && line[i] <= '9' && i < 15; ++i) v = v * 10 + (line[i] - '0');
    return i > 0 && i < line.size() && line[i] == ',' ? v : -1;
}

namespace {

constexpr const char* kJournal = "the sweep's journal";

// Reads one journal into `lines`; false when the file does not exist.
bool read_journal(const std::string& path, const std::string& fingerprint, std::int64_t size, Lines& lines) {
    struct stat st {};
    if (::lstat(path.c_str(), &st) != 0 && errno == ENOENT) return false;
    const std::string text = read_own_file(path, kJournal);  // no link followed, a regular file
    size_t pos = text.find('\n');
    if (pos == std::string::npos) return true;  // torn before its first line: nothing finished
    const std::string head = text.substr(0, pos);
    if (head != "# " + fingerprint) {
        // Another sweep's fingerprint is shown (refract's own line); any other text is not.
        const std::string sweep = "# refract sweep ";
        if (head.compare(0, sweep.size(), sweep) != 0 || head.size() > 1024)
            throw InputError(path + ": not a journal of refract sweep (its first line is no sweep's fingerprint); "
                                    "delete it or choose another -o");
        throw InputError(path + ": the journal of an interrupted sweep with other parameters (" + head.substr(2) +
                         "); run that sweep again to finish it, or delete the journal");
    }
    for (size_t b = pos + 1; b < text.size();) {
        const size_t e = text.find('\n', b);
        if (e == std::string::npos) break;  // a torn last line: the row is computed again
        const std::string line = text.substr(b, e - b);
        const std::int64_t i = line_index(line);
        if (i < 0 || i >= size) throw InputError(path + ": a journal line that is not a row of this sweep");
        lines[i] = line;
        b = e + 1;
    }
    return true;
}

}  // namespace

Lines recover(const Sweep& sweep, const std::string& out, bool* found) {
    const std::string fp = fingerprint(sweep);
    const std::int64_t size = sweep.grid.size();
    Lines lines;
    const std::string journal = journal_path(out);
    bool any = read_journal(journal, fp, size, lines);
    std::vector<std::string> parts;
    const fs::path dir = fs::path(out).parent_path().empty() ? fs::path(".") : fs::path(out).parent_path();
    const std::string prefix = fs::path(journal_path(out)).filename().string() + ".";
    std::error_code ec;
    for (const auto& e : fs::directory_iterator(dir, ec)) {
        const std::string name = e.path().filename().string();
        if (name.size() > prefix.size() && name.compare(0, prefix.size(), prefix) == 0 &&
            name.find_first_not_of("0123456789", prefix.size()) == std::string::npos) {
            const std::string part = (fs::path(out).parent_path() / name).string();  // as OUT is written
            read_journal(part, fp, size, lines);
            parts.push_back(part);
            any = true;
        }
    }
    if (any) {
        write_file_atomic(journal, "# " + fp + "\n" + [&] {
            std::string s;
            for (const auto& [i, line] : lines) s += line + "\n";
            return s;
        }());
        for (const auto& p : parts) fs::remove(p, ec);
    }
    if (found) *found = any;
    return lines;
}

JournalWriter::JournalWriter(const std::string& path, const std::string& fingerprint) : path_(path) {
    fd_ = open_own_file(path, O_WRONLY | O_APPEND | O_CREAT, kJournal);  // no link followed, a regular file
    if (fd_ < 0) throw InputError(path + ": cannot open the sweep's journal (" + std::strerror(errno) + ")");
    if (::lseek(fd_, 0, SEEK_END) == 0) append("# " + fingerprint);
}

JournalWriter::~JournalWriter() {
    if (fd_ >= 0) ::close(fd_);
}

void JournalWriter::append(const std::string& line) {
    const std::string s = line + "\n";
    size_t done = 0;
    while (done < s.size()) {
        const ssize_t n = ::write(fd_, s.data() + done, s.size() - done);
        if (n < 0 && errno == EINTR) continue;
        if (n <= 0) throw InputError(path_ + ": cannot append to the sweep's journal (" + std::strerror(errno) + ")");
        done += static_cast<size_t>(n);
    }
}

void remove_new_journal(const std::string& path) {
    struct stat st {};
    if (::lstat(path.c_str(), &st) == 0 && S_ISREG(st.st_mode)) ::unlink(path.c_str());
}

std::string csv_text(const Lines& lines) {
    std::string s = csv_header() + "\n";
    for (const auto& [i, line] : lines) s += line + "\n";
    return s;
}

nlohmann::json settings_json(const Sweep& s) {
    nlohmann::json axes = nlohmann::json::object();
    for (const Axis& a : s.grid.axes) axes[a.name] = a.text();
    const BrilliantCut& b = s.grid.base;
    return {{"sweep", "brilliant"},
            {"axes", axes},
            {"culet", b.culet},
            {"girdle_facets", b.girdle_facets},
            {"bruted_planes", b.bruted_planes},
            {"material", s.metric.material},
            {"rays", s.metric.rays},
            {"wavelengths", s.metric.wavelengths},
            {"polarisation_model", s.metric.exact_polarisation ? "exact" : "natural"},
            {"observer", s.metric.observer},
            {"seed", s.metric.seed},
            {"cuts", s.grid.size()},
            {"fingerprint", fingerprint(s)}};
}

void finish(const Sweep& sweep, const std::string& out, const Lines& lines) {
    if (static_cast<std::int64_t>(lines.size()) != sweep.grid.size())
        throw InputError(out + ": the sweep holds " + std::to_string(lines.size()) + " of " +
                         std::to_string(sweep.grid.size()) + " rows; not written");
    write_file_atomic(out, csv_text(lines));
    std::error_code ec;
    try {
        write_csv_sidecar(out, settings_json(sweep));  // OUT.json, OUT + ".json": what produced it (core/provenance.h)
    } catch (...) {
        fs::remove(out, ec);  // no CSV without its settings; the journal stays to resume
        throw;
    }
    fs::remove(journal_path(out), ec);
}

void check_output(const std::string& out) {
    const fs::path dir = fs::path(out).parent_path().empty() ? fs::path(".") : fs::path(out).parent_path();
    std::error_code ec;
    if (!fs::is_directory(dir, ec)) throw InputError(out + ": the directory " + dir.string() + " does not exist");
    if (fs::is_directory(out, ec)) throw InputError(out + ": is a directory, not a CSV file");
    if (::access(dir.c_str(), W_OK) != 0) throw InputError(out + ": the directory " + dir.string() + " is not writable");
}

FileRunStats run_to_file(const Sweep& sweep, const std::string& out, int threads,
                         const std::function<void(std::int64_t, std::int64_t)>& progress) {
    check_output(out);
    FileRunStats st;
    st.total = sweep.grid.size();
    bool resuming = false;
    Lines lines = recover(sweep, out, &resuming);
    st.resumed = static_cast<std::int64_t>(lines.size());
    std::vector<std::int64_t> pending;
    for (std::int64_t i = 0; i < st.total; ++i)
        if (!lines.count(i)) pending.push_back(i);
    try {
        JournalWriter journal(journal_path(out), fingerprint(sweep));
        std::int64_t done = st.resumed;
        const auto rows = run(sweep, pending, threads, [&](const Row& r) {
            journal.append(csv_line(r));
            ++done;
            if (progress) progress(done, st.total);
        });
        for (const Row& r : rows) {
            lines[r.index] = csv_line(r);
            st.impossible += !r.possible;
        }
        st.computed = static_cast<std::int64_t>(rows.size());
        finish(sweep, out, lines);
    } catch (const InputError&) {
        // Refused after it started (a disk full, an output that became a directory): the
        // journal this run began goes too; one resumed from an earlier run stays.
        if (!resuming) remove_new_journal(journal_path(out));
        throw;
    }
    return st;
}

}  // namespace refract::experiments::gem_sweep
