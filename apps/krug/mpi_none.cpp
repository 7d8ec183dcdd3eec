// A krug built without MPI: the study commands run on this machine only (--jobs).
#include <stdexcept>

#include "mpi_workers.hpp"

namespace krug::app {

bool mpi_built() { return false; }

MpiStudy::MpiStudy() { throw std::logic_error("krug was built without MPI"); }
MpiStudy::~MpiStudy() = default;
Workers MpiStudy::workers(const std::atomic<bool>&, const volatile std::sig_atomic_t&) { return {}; }
void MpiStudy::serve(const std::atomic<bool>&, const volatile std::sig_atomic_t&) {}

}  // namespace krug::app
