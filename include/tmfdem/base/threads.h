/**
 * @file
 * How MPI ranks and threads share the cores, and the thread-parallel loop
 * of the discrete layer (fixed chunks: results do not depend on the thread
 * count).
 *
 * The rule (doc/performance.md): a rank may use
 *   cores_per_rank = max(1, min(cores in its affinity mask,
 *                               cores of the node / ranks on the node)),
 * which is the thread limit of deal.II and TBB (the continuum assembly,
 * deal.II's vector and matrix operations). The discrete layer runs
 * `Discrete mechanics/Threads` threads (0: cores_per_rank), capped at
 * cores_per_rank unless `Discrete mechanics/Allow oversubscription` is
 * true, so that ranks x threads never exceeds the cores by default.
 */
#ifndef tmfdem_base_threads_h
#define tmfdem_base_threads_h

#include <algorithm>
#include <cstddef>
#include <map>
#include <memory>
#include <mpi.h>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>
#include <vector>

namespace tmfdem
{
  /** What the rule above gives on this machine for this rank. */
  struct CoreShare
  {
    unsigned int affinity_cores = 1; ///< cores in this process's mask
    unsigned int node_cores     = 1; ///< std::thread::hardware_concurrency
    unsigned int ranks_on_node  = 1; ///< MPI ranks sharing the node
    unsigned int cores_per_rank = 1; ///< the rule's result
  };

  /** Evaluates the rule for this rank (collective on @p communicator). */
  CoreShare
  core_share(MPI_Comm communicator);

  /**
   * Sets deal.II's and TBB's thread limit (MultithreadInfo, a
   * tbb::global_control) to @p threads; DEAL_II_NUM_THREADS, if set, may
   * lower it. Called by main() with cores_per_rank, and by the discrete
   * layer to raise it when oversubscription is asked for.
   */
  void
  set_thread_limit(unsigned int threads);

  /** The thread limit now in force (tbb::global_control). */
  unsigned int
  thread_limit();

  /** The task arena of @p threads threads (one per thread count, kept). */
  tbb::task_arena &
  arena_for(unsigned int threads);

  /**
   * Measures how many threads of @p arena really run at the same time: one
   * task per arena slot, each waiting (at most @p timeout_s seconds) until
   * all have started; returns the number of distinct threads that were
   * inside together. 1 if the arena has one slot.
   */
  unsigned int
  measure_concurrency(tbb::task_arena &arena, double timeout_s = 2.);

  /** CPU time of this process, all threads, user + system [s]. */
  double
  process_cpu_time();

  /** CPU time, user + system, of each thread of this process now, by
   *  thread id (/proc/self/task; empty where that is unreadable) [s]. */
  std::map<long, double>
  thread_cpu_times();

  /** Per-thread CPU time between the snapshots @p before and @p after
   *  (thread_cpu_times()), largest first, threads under 10 ms left out
   *  [s]. */
  std::vector<double>
  thread_cpu_time_differences(const std::map<long, double> &before,
                              const std::map<long, double> &after);

  /**
   * Runs @p body(chunk_begin, chunk_end, chunk_index) over the fixed chunks
   * [c chunk, min(n, (c+1) chunk)) of @p n items in @p arena. The chunks do
   * not depend on the thread count; a body that writes per item or per
   * chunk, with chunk results combined in chunk order afterwards, gives
   * results independent of the thread count.
   */
  template <typename Body>
  void
  for_each_chunk(tbb::task_arena  &arena,
                 const std::size_t n,
                 const std::size_t chunk,
                 const Body       &body)
  {
    const std::size_t n_chunks = (n + chunk - 1) / chunk;
    if (n_chunks == 0)
      return;
    if (n_chunks == 1 || arena.max_concurrency() == 1)
      {
        for (std::size_t c = 0; c < n_chunks; ++c)
          body(c * chunk, std::min(n, (c + 1) * chunk), c);
        return;
      }
    arena.execute([&] {
      tbb::parallel_for(tbb::blocked_range<std::size_t>(0, n_chunks),
                        [&](const tbb::blocked_range<std::size_t> &r) {
                          for (std::size_t c = r.begin(); c != r.end(); ++c)
                            body(c * chunk, std::min(n, (c + 1) * chunk), c);
                        });
    });
  }
} // namespace tmfdem

#endif
