// The adapter's pool of worker threads for spaceCollide (space_collide.cpp): one parallel loop over
// indices that a producer publishes while the loop runs.
//
// Why a std::thread pool and not oneTBB: the work is one flat loop over independent pairs per
// step, which a pool of a few dozen lines does with an atomic counter; oneTBB would become a
// dependency of the installed library (its CMake config, pkg-config file and Debian package) for
// that one loop, and its own synchronisation is not visible to ThreadSanitizer unless TBB itself is
// instrumented. The pool's threads sleep on a condition variable between calls.
#pragma once

#include <algorithm>
#include <atomic>
#include <condition_variable>
#include <cstddef>
#include <cstdint>
#include <mutex>
#include <thread>
#include <vector>

namespace gdc::ode {
// Internal linkage, as everything of spaceCollide's own: the pool's types appear in template
// instantiations (std::thread's state for the worker lambda) that would otherwise be exported from
// libgdcontact.so. Included by space_collide.cpp alone.
namespace {

// One parallel loop over indices that a producer publishes while the loop runs: body(context,
// begin, end) in chunks, taken in any order by any participant (each index writes only its own
// output, so the order of execution is invisible). The producer stores `available` each time a
// whole chunk is ready, and the final count before it sets `closed`; a participant ahead of it
// waits. `next` (written by every participant) and `available` (by the producer, read by the
// waiting participants) sit on separate cache lines: on one line, every pair the broad phase
// listed would take that line away from a worker taking its next chunk, and back.
struct Job {
    void (*body)(void* context, std::size_t begin, std::size_t end) = nullptr;
    void* context = nullptr;
    std::size_t chunk = 1;
    alignas(64) std::atomic<std::size_t> next{0};
    alignas(64) std::atomic<std::size_t> available{0};
    std::atomic<bool> closed{false};

    // The producer: indices [0, count) are ready; publishes at chunk boundaries only.
    void ready(std::size_t count) {
        if (count % chunk == 0) available.store(count, std::memory_order_release);
    }
    // The producer: every index is ready; `count` is the final number.
    void close(std::size_t count) {
        available.store(count, std::memory_order_release);
        closed.store(true, std::memory_order_release);
    }

    // Takes the next chunk and runs it; false when none is left (every index taken).
    bool workChunk() {
        const std::size_t begin = next.fetch_add(chunk, std::memory_order_relaxed);
        std::size_t end = begin + chunk;
        for (int spins = 0;; ++spins) {
            if (available.load(std::memory_order_acquire) >= end) break;
            if (closed.load(std::memory_order_acquire)) {  // `available` is final now
                end = std::min(end, available.load(std::memory_order_acquire));
                break;
            }
            if (spins >= 64) std::this_thread::yield();  // the broad phase is behind
        }
        if (begin >= end) return false;
        body(context, begin, end);
        return true;
    }
    void work() {
        while (workChunk()) {
        }
    }
};

// Worker threads that sleep between jobs. One thread at a time posts a job (it holds
// WorkerPool::use) and works on it too. A worker joins a job only while it is open: one that wakes
// after the caller has finished every index (the machine busy with other work) finds it closed and
// sleeps again, so the caller never waits for a thread that has not yet run.
class WorkerPool {
public:
    std::mutex use;  // held by the thread running a job (spaceCollide try-locks it)

    ~WorkerPool() { resize(0); }

    // Sets `workers` pool threads (≥ 1) working on `job`; finish() waits for those that joined.
    // The caller publishes the job's indices meanwhile, closes it, and works on it too.
    void start(Job& job, int workers) {
        if (static_cast<int>(threads_.size()) != workers) resize(workers);
        {
            std::lock_guard<std::mutex> lock(mutex_);
            job_ = &job;
            ++generation_;
        }
        wake_.notify_all();
    }
    // Call when every index of the job is taken (Job::work has returned on the caller).
    void finish() {
        std::unique_lock<std::mutex> lock(mutex_);
        job_ = nullptr;  // no worker joins from now on
        finished_.wait(lock, [&] { return active_ == 0; });
    }

private:
    void resize(int workers) {
        if (!threads_.empty()) {
            {
                std::lock_guard<std::mutex> lock(mutex_);
                stopping_ = true;
            }
            wake_.notify_all();
            for (std::thread& thread : threads_) thread.join();
            threads_.clear();
            stopping_ = false;
        }
        threads_.reserve(static_cast<std::size_t>(workers));
        // A new thread must not take the generation current when it starts: the next job may have
        // been posted by then. Only start() changes it, on this thread, so it is read here.
        for (int i = 0; i < workers; ++i) threads_.emplace_back([this, seen = generation_] { loop(seen); });
    }

    void loop(std::uint64_t seen) {
        for (;;) {
            Job* job;
            {
                std::unique_lock<std::mutex> lock(mutex_);
                wake_.wait(lock, [&] { return stopping_ || generation_ != seen; });
                if (stopping_) return;
                seen = generation_;
                job = job_;
                if (!job) continue;  // woke too late: the caller has done it all
                ++active_;
            }
            job->work();
            bool last;
            {
                std::lock_guard<std::mutex> lock(mutex_);
                last = --active_ == 0;
            }
            if (last) finished_.notify_one();
        }
    }

    std::mutex mutex_;
    std::condition_variable wake_;
    std::condition_variable finished_;
    std::vector<std::thread> threads_;
    std::uint64_t generation_ = 0;
    Job* job_ = nullptr;  // the open job; nullptr once the caller has finished it
    int active_ = 0;      // workers inside job_->work()
    bool stopping_ = false;
};

/// The process's one pool (threads start on first use, stop at exit).
WorkerPool& workerPool() {
    static WorkerPool pool;
    return pool;
}

}  // namespace
}  // namespace gdc::ode
