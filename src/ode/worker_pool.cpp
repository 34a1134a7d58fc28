// The process's one worker pool (worker_pool.hpp).
#include "worker_pool.hpp"

namespace gdc::ode::detail {

WorkerPool& workerPool() {
    static WorkerPool pool;
    return pool;
}

}  // namespace gdc::ode::detail
