#include <refract/experiments/gem_sweep_file.h>

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>

#include <fcntl.h>
#include <unistd.h>

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

// Reads one journal into `lines`; false when the file does not exist.
bool read_journal(const std::string& path, const std::string& fingerprint, std::int64_t size, Lines& lines) {
    std::ifstream in(path, std::ios::binary);
    if (!in) return false;
    std::stringstream ss;
    ss << in.rdbuf();
    const std::string text = ss.str();
    size_t pos = text.find('\n');
    if (pos == std::string::npos) return true;  // torn before its first line: nothing finished
    const std::string head = text.substr(0, pos);
    if (head != "# " + fingerprint)
        throw InputError(path + ": the journal of an interrupted sweep with other parameters (" +
                         (head.size() > 2 ? head.substr(2) : head) +
                         "); run that sweep again to finish it, or delete the journal");
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

Lines recover(const Sweep& sweep, const std::string& out) {
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
            read_journal(e.path().string(), fp, size, lines);
            parts.push_back(e.path().string());
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
    return lines;
}

JournalWriter::JournalWriter(const std::string& path, const std::string& fingerprint) : path_(path) {
    fd_ = ::open(path.c_str(), O_WRONLY | O_APPEND | O_CREAT | O_CLOEXEC | O_NOFOLLOW, 0644);
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

std::string csv_text(const Lines& lines) {
    std::string s = csv_header() + "\n";
    for (const auto& [i, line] : lines) s += line + "\n";
    return s;
}

void finish(const Sweep& sweep, const std::string& out, const Lines& lines) {
    if (static_cast<std::int64_t>(lines.size()) != sweep.grid.size())
        throw InputError(out + ": the sweep holds " + std::to_string(lines.size()) + " of " +
                         std::to_string(sweep.grid.size()) + " rows; not written");
    write_file_atomic(out, csv_text(lines));
    std::error_code ec;
    fs::remove(journal_path(out), ec);
}

FileRunStats run_to_file(const Sweep& sweep, const std::string& out, int threads,
                         const std::function<void(std::int64_t, std::int64_t)>& progress) {
    FileRunStats st;
    st.total = sweep.grid.size();
    Lines lines = recover(sweep, out);
    st.resumed = static_cast<std::int64_t>(lines.size());
    std::vector<std::int64_t> pending;
    for (std::int64_t i = 0; i < st.total; ++i)
        if (!lines.count(i)) pending.push_back(i);
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
    return st;
}

}  // namespace refract::experiments::gem_sweep
