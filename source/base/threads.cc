#include <deal.II/base/multithread_info.h>

#include <atomic>
#include <chrono>
#include <dirent.h>
#include <fstream>
#include <functional>
#include <map>
#include <mutex>
#include <sched.h>
#include <set>
#include <sstream>
#include <sys/resource.h>
#include <tbb/global_control.h>
#include <thread>
#include <tmfdem/base/threads.h>
#include <unistd.h>

namespace tmfdem
{
  CoreShare
  core_share(MPI_Comm communicator)
  {
    CoreShare share;
    share.node_cores = std::max(1u, std::thread::hardware_concurrency());
    cpu_set_t mask;
    CPU_ZERO(&mask);
    share.affinity_cores = sched_getaffinity(0, sizeof(mask), &mask) == 0 ?
                             std::max(1, CPU_COUNT(&mask)) :
                             share.node_cores;
    MPI_Comm node;
    MPI_Comm_split_type(communicator,
                        MPI_COMM_TYPE_SHARED,
                        0,
                        MPI_INFO_NULL,
                        &node);
    int ranks = 1;
    MPI_Comm_size(node, &ranks);
    MPI_Comm_free(&node);
    share.ranks_on_node = static_cast<unsigned int>(std::max(1, ranks));
    share.cores_per_rank =
      std::max(1u,
               std::min(share.affinity_cores,
                        share.node_cores / share.ranks_on_node));
    return share;
  }

  void
  set_thread_limit(const unsigned int threads)
  {
    dealii::MultithreadInfo::set_thread_limit(std::max(1u, threads));
  }

  unsigned int
  thread_limit()
  {
    return static_cast<unsigned int>(tbb::global_control::active_value(
      tbb::global_control::max_allowed_parallelism));
  }

  tbb::task_arena &
  arena_for(const unsigned int threads)
  {
    // one arena per thread count, kept (references stay valid)
    static std::map<unsigned int, std::unique_ptr<tbb::task_arena>> arenas;
    auto &arena = arenas[std::max(1u, threads)];
    if (!arena)
      arena = std::make_unique<tbb::task_arena>(std::max(1u, threads));
    return *arena;
  }

  unsigned int
  measure_concurrency(tbb::task_arena &arena, const double timeout_s)
  {
    const int slots = arena.max_concurrency();
    if (slots <= 1)
      return 1;
    std::atomic<int>          inside{0};
    std::mutex                mutex;
    std::set<std::thread::id> together;
    const auto                deadline =
      std::chrono::steady_clock::now() +
      std::chrono::duration_cast<std::chrono::steady_clock::duration>(
        std::chrono::duration<double>(timeout_s));
    arena.execute([&] {
      tbb::parallel_for(
        tbb::blocked_range<int>(0, slots, 1),
        [&](const tbb::blocked_range<int> &) {
          ++inside;
          // wait for the others: a thread that cannot run concurrently
          // (no core for it) leaves this task to the ones that can
          while (inside.load() < slots &&
                 std::chrono::steady_clock::now() < deadline)
            std::this_thread::yield();
          std::lock_guard<std::mutex> lock(mutex);
          if (inside.load() >= slots)
            together.insert(std::this_thread::get_id());
        },
        tbb::simple_partitioner());
    });
    // all slots entered together: as many threads as took part; otherwise
    // only the calling thread is proven
    return together.empty() ? 1u : static_cast<unsigned int>(together.size());
  }

  double
  process_cpu_time()
  {
    rusage usage;
    getrusage(RUSAGE_SELF, &usage);
    return usage.ru_utime.tv_sec + 1e-6 * usage.ru_utime.tv_usec +
           usage.ru_stime.tv_sec + 1e-6 * usage.ru_stime.tv_usec;
  }

  std::map<long, double>
  thread_cpu_times()
  {
    std::map<long, double> times;
    DIR                   *dir = opendir("/proc/self/task");
    if (dir == nullptr)
      return times;
    const double tick = static_cast<double>(sysconf(_SC_CLK_TCK));
    while (const dirent *entry = readdir(dir))
      {
        if (entry->d_name[0] < '0' || entry->d_name[0] > '9')
          continue;
        std::ifstream file(std::string("/proc/self/task/") + entry->d_name +
                           "/stat");
        std::string   line;
        if (!std::getline(file, line))
          continue;
        // fields after the command name in parentheses: state is field 3,
        // utime 14, stime 15
        const std::size_t close = line.rfind(')');
        if (close == std::string::npos)
          continue;
        std::istringstream rest(line.substr(close + 2));
        std::string        field;
        double             utime = 0., stime = 0.;
        for (unsigned int k = 3; k <= 15 && (rest >> field); ++k)
          if (k == 14)
            utime = std::stod(field);
          else if (k == 15)
            stime = std::stod(field);
        times[std::stol(entry->d_name)] = (utime + stime) / tick;
      }
    closedir(dir);
    return times;
  }

  std::vector<double>
  thread_cpu_time_differences(const std::map<long, double> &before,
                              const std::map<long, double> &after)
  {
    std::vector<double> differences;
    for (const auto &[id, t] : after)
      {
        const auto   old = before.find(id);
        const double d   = t - (old == before.end() ? 0. : old->second);
        if (d >= 0.01)
          differences.push_back(d);
      }
    std::sort(differences.begin(), differences.end(), std::greater<>());
    return differences;
  }
} // namespace tmfdem
