#pragma once
// The few MPI calls `refract sweep` makes (cli/sweep.cpp), compiled with MPI when CMake
// finds it (REFRACT_HAVE_MPI) and as a one-rank stand-in otherwise. MPI is initialised
// only when the process runs under mpirun (Open MPI sets OMPI_COMM_WORLD_SIZE; PMI_SIZE
// and PMIX_RANK cover other launchers), so every other command runs without it.
#include <cstdint>
#include <string>
#include <vector>

namespace refract::cli::mpi {

bool under_mpirun();
bool available();  // built with MPI

class Session {
public:
    Session();  // MPI_Init when under mpirun (InputError if refract was built without MPI)
    ~Session();  // MPI_Finalize
    Session(const Session&) = delete;
    Session& operator=(const Session&) = delete;
    int rank() const { return rank_; }
    int size() const { return size_; }
    // Rank 0's `text` on every rank.
    std::string broadcast(const std::string& text) const;
    // Every rank's `text`, concatenated in rank order on rank 0 (empty elsewhere).
    std::string gather(const std::string& text) const;
    void barrier() const;
    // Ends every rank (MPI_Abort) after an error on one: the others would wait forever.
    [[noreturn]] void abort(int code) const;
    bool active() const { return active_; }

private:
    bool active_ = false;
    int rank_ = 0, size_ = 1;
};

}  // namespace refract::cli::mpi
