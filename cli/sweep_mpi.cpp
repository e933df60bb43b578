#include "cli/sweep_mpi.h"

#include <algorithm>
#include <cstdlib>

#include <refract/geometry/error.h>

#ifdef REFRACT_HAVE_MPI
#include <mpi.h>
#endif

namespace refract::cli::mpi {

bool under_mpirun() {
    return std::getenv("OMPI_COMM_WORLD_SIZE") || std::getenv("PMI_SIZE") || std::getenv("PMIX_RANK");
}

#ifdef REFRACT_HAVE_MPI

bool available() { return true; }

Session::Session() {
    if (!under_mpirun()) return;
    int initialised = 0;
    MPI_Initialized(&initialised);
    if (!initialised) MPI_Init(nullptr, nullptr);
    active_ = true;
    MPI_Comm_rank(MPI_COMM_WORLD, &rank_);
    MPI_Comm_size(MPI_COMM_WORLD, &size_);
}

Session::~Session() {
    if (active_) MPI_Finalize();
}

std::string Session::broadcast(const std::string& text) const {
    if (!active_) return text;
    std::uint64_t n = text.size();
    MPI_Bcast(&n, 1, MPI_UINT64_T, 0, MPI_COMM_WORLD);
    std::string s = rank_ == 0 ? text : std::string(n, '\0');
    for (std::uint64_t off = 0; off < n;) {  // in pieces below INT_MAX
        const int piece = static_cast<int>(std::min<std::uint64_t>(n - off, 1u << 30));
        MPI_Bcast(s.data() + off, piece, MPI_CHAR, 0, MPI_COMM_WORLD);
        off += static_cast<std::uint64_t>(piece);
    }
    return s;
}

std::string Session::gather(const std::string& text) const {
    if (!active_) return text;
    // Rank by rank through point-to-point messages: sizes first, then the bytes.
    if (rank_ != 0) {
        std::uint64_t n = text.size();
        MPI_Send(&n, 1, MPI_UINT64_T, 0, 1, MPI_COMM_WORLD);
        for (std::uint64_t off = 0; off < n;) {
            const int piece = static_cast<int>(std::min<std::uint64_t>(n - off, 1u << 30));
            MPI_Send(text.data() + off, piece, MPI_CHAR, 0, 2, MPI_COMM_WORLD);
            off += static_cast<std::uint64_t>(piece);
        }
        return {};
    }
    std::string all = text;
    for (int r = 1; r < size_; ++r) {
        std::uint64_t n = 0;
        MPI_Recv(&n, 1, MPI_UINT64_T, r, 1, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
        std::string s(n, '\0');
        for (std::uint64_t off = 0; off < n;) {
            const int piece = static_cast<int>(std::min<std::uint64_t>(n - off, 1u << 30));
            MPI_Recv(s.data() + off, piece, MPI_CHAR, r, 2, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
            off += static_cast<std::uint64_t>(piece);
        }
        all += s;
    }
    return all;
}

void Session::barrier() const {
    if (active_) MPI_Barrier(MPI_COMM_WORLD);
}

void Session::abort(int code) const {
    if (active_) MPI_Abort(MPI_COMM_WORLD, code);
    std::exit(code);
}

#else

bool available() { return false; }

Session::Session() {
    if (under_mpirun())
        throw InputError("refract sweep: running under mpirun, but this refract was built without MPI "
                         "(install libopenmpi-dev and rebuild)");
}
Session::~Session() = default;
std::string Session::broadcast(const std::string& text) const { return text; }
std::string Session::gather(const std::string& text) const { return text; }
void Session::barrier() const {}
void Session::abort(int code) const { std::exit(code); }

#endif

}  // namespace refract::cli::mpi
