/**
 * @file
 * Long runs: checkpoints, `--resume`, and stopping on SIGINT/SIGTERM
 * (doc/reliability.md).
 *
 * A checkpoint is one binary file of a simple versioned format of its own:
 * a 32-byte header (magic "TMFDEMCK", format version, payload length,
 * FNV-1a 64 checksum of the payload) and the payload: the kind of solver,
 * the digest of the input that wrote it, and the solver's state as a
 * sequence of plain values and sized arrays. Files are written to a
 * temporary name, flushed to disk and renamed, so a run killed at any moment
 * leaves the previous complete checkpoint readable. Reading checks magic,
 * version, length, checksum, kind, input digest and every array size, and
 * turns any mismatch into an error message (never a crash).
 */
#ifndef tmfdem_io_checkpoint_h
#define tmfdem_io_checkpoint_h

#include <chrono>
#include <csignal>
#include <cstdint>
#include <cstring>
#include <map>
#include <string>
#include <tmfdem/base/exceptions.h>
#include <tmfdem/base/parameters.h>
#include <type_traits>
#include <vector>

namespace tmfdem
{
  // ---------------------------------------------------------------- signals
  namespace internal
  {
    /** The signal that asked the run to stop, or 0. */
    extern volatile std::sig_atomic_t stop_signal;
  } // namespace internal

  /**
   * Installs handlers for SIGINT and SIGTERM that only set a flag; the time
   * loops test it once per step (stop_requested()), finish the step, write
   * the outputs and a checkpoint, and throw StopRequested. A second signal
   * while the first is pending kills the program at once (default action).
   */
  void
  install_signal_handlers();

  /** True once SIGINT or SIGTERM arrived (one load of a volatile flag). */
  inline bool
  stop_requested()
  {
    return internal::stop_signal != 0;
  }

  /** "SIGINT", "SIGTERM" or "" (no signal). */
  std::string
  stop_signal_name();

  /**
   * The same as stop_requested() on every rank of @p communicator (a
   * logical or over the ranks), for the MPI-parallel continuum loops.
   */
  bool
  stop_requested_on_any_rank(MPI_Comm communicator);

  // ----------------------------------------------------------- the format
  /** Builds the payload of a checkpoint in memory. */
  class CheckpointWriter
  {
  public:
    /** Starts a payload for a solver of kind @p kind (e.g. "discrete
     *  mechanics") and the input digest @p digest. */
    CheckpointWriter(const std::string &kind, const std::string &digest);

    /** Appends a plain value (trivially copyable). */
    template <typename T>
    void
    put(const T &value)
    {
      static_assert(std::is_trivially_copyable_v<T>);
      append(&value, sizeof(T));
    }
    /** Appends the size and the elements of @p values. */
    template <typename T>
    void
    put(const std::vector<T> &values)
    {
      static_assert(std::is_trivially_copyable_v<T>);
      put<std::uint64_t>(values.size());
      append(values.data(), values.size() * sizeof(T));
    }
    /** Appends @p n elements starting at @p data, with the count. */
    template <typename T>
    void
    put_array(const T *data, const std::size_t n)
    {
      static_assert(std::is_trivially_copyable_v<T>);
      put<std::uint64_t>(n);
      append(data, n * sizeof(T));
    }
    /** Appends a string (size and characters). */
    void
    put(const std::string &text);
    /** Appends a map of plain keys and values (size, then the pairs). */
    template <typename K, typename V>
    void
    put(const std::map<K, V> &map)
    {
      put<std::uint64_t>(map.size());
      for (const auto &[key, value] : map)
        {
          put(key);
          put(value);
        }
    }

    /** The complete file content: header and payload. */
    std::string
    file_content() const;

  private:
    friend class CheckpointReader;
    void
                append(const void *data, const std::size_t bytes);
    std::string payload;
  };

  /** Reads a checkpoint file written by CheckpointWriter. */
  class CheckpointReader
  {
  public:
    /**
     * Reads and checks @p file_name: header, checksum, kind @p kind and input
     * digest @p digest. Throws InputError naming the file and what is wrong
     * (not a checkpoint, other version, truncated, corrupt, other model,
     * other input).
     */
    CheckpointReader(const std::string &file_name,
                     const std::string &kind,
                     const std::string &digest);

    /**
     * Reads the payload of @p writer in memory (a state kept for a while,
     * e.g. the start of a thermal step that may be re-run); @p name names it
     * in messages. Kind and digest are read past unchecked.
     */
    CheckpointReader(const CheckpointWriter &writer, const std::string &name);

    /** Reads a plain value. */
    template <typename T>
    void
    get(T &value)
    {
      static_assert(std::is_trivially_copyable_v<T>);
      extract(&value, sizeof(T));
    }
    /** Reads an array; with @p expected_size != npos its size must match. */
    template <typename T>
    void
    get(std::vector<T>   &values,
        const std::size_t expected_size = static_cast<std::size_t>(-1))
    {
      static_assert(std::is_trivially_copyable_v<T>);
      const std::size_t n = get_size(expected_size, sizeof(T));
      values.resize(n);
      extract(values.data(), n * sizeof(T));
    }
    /** Reads an array of exactly @p n elements into @p data. */
    template <typename T>
    void
    get_array(T *data, const std::size_t n)
    {
      static_assert(std::is_trivially_copyable_v<T>);
      get_size(n, sizeof(T));
      extract(data, n * sizeof(T));
    }
    /** Reads a string. */
    void
    get(std::string &text);
    /** Reads a map written by CheckpointWriter::put(map); InputError if it
     *  claims more than @p max_size entries (a corrupt file). */
    template <typename K, typename V>
    void
    get(std::map<K, V> &map, const std::uint64_t max_size = 65536)
    {
      std::uint64_t n = 0;
      get(n);
      if (n > max_size)
        throw InputError("the checkpoint '" + file_name +
                         "' is corrupt (map size).");
      map.clear();
      for (std::uint64_t i = 0; i < n; ++i)
        {
          K key;
          V value;
          get(key);
          get(value);
          map[key] = value;
        }
    }
    /** Throws unless everything was read. */
    void
    finish() const;

    /** The file being read. */
    const std::string &
    name() const
    {
      return file_name;
    }

  private:
    std::size_t
    get_size(const std::size_t expected, const std::size_t element_bytes);
    void
                extract(void *data, const std::size_t bytes);
    std::string file_name;
    std::string payload;
    std::size_t position = 0;
  };

  // ---------------------------------------------------- files and schedule
  /** The folder of the checkpoints: Checkpoint/Directory, or
   *  <Output/Directory>/checkpoints. */
  std::string
  checkpoint_folder(const Parameters &parameters);

  /**
   * Writes @p writer's content as checkpoint number @p sequence (the step
   * count) atomically (temporary file, fsync, rename), then removes all but
   * the newest Checkpoint/Keep checkpoints. Returns the file size [bytes].
   */
  std::size_t
  write_checkpoint(const Parameters       &parameters,
                   const unsigned long     sequence,
                   const CheckpointWriter &writer);

  /** The newest checkpoint file; InputError if there is none. */
  std::string
  newest_checkpoint(const Parameters &parameters);

  /**
   * When to write checkpoints: every Checkpoint/Interval (steps) steps
   * and/or every Checkpoint/Interval (wall minutes) of wall time.
   */
  class CheckpointSchedule
  {
  public:
    explicit CheckpointSchedule(const CheckpointParameters &parameters);
    /** True if a checkpoint is due after @p steps steps (cheap). */
    bool
    due(const unsigned long steps);
    /** Records that a checkpoint was written after @p steps steps. */
    void
    written(const unsigned long steps);
    /** True if checkpoints are written at all. */
    bool
    active() const
    {
      return interval_steps > 0 || interval_seconds > 0.;
    }

  private:
    using Clock = std::chrono::steady_clock;
    unsigned long     interval_steps;
    double            interval_seconds;
    unsigned long     last_steps = 0;
    Clock::time_point last_time;
  };

  /**
   * Truncates the CSV file @p file_name to @p size bytes (its length at the
   * checkpoint): rows written after the checkpoint, or a partial row of a
   * killed run, are dropped. RunError if the file is shorter.
   */
  void
  truncate_file(const std::string &file_name, const std::uint64_t size);

  /** Size of @p file_name in bytes, 0 if it does not exist. */
  std::uint64_t
  file_size(const std::string &file_name);

  /**
   * --resume with another Time stepping/End time (the only entry that may
   * change besides Checkpoint, Output/Directory, Output/Progress interval and
   * Discrete mechanics/Threads): the output times of the checkpoint
   * @p saved, of which the first @p saved_next were written, and the output
   * times @p fresh of this input (its End time). Throws InputError naming
   * @p file if End time [s] lies before the checkpoint's @p time [s]. Returns
   * the index into @p fresh of the next output: the entries up to the last
   * written one (within @p tolerance [s]) count as written. With the same
   * End time @p fresh is replaced by @p saved and @p saved_next returned.
   */
  unsigned int
  continue_output_times(const std::string         &file,
                        const double               time,
                        const double               end_time,
                        const std::vector<double> &saved,
                        const unsigned int         saved_next,
                        std::vector<double>       &fresh,
                        const double               tolerance);
} // namespace tmfdem

#endif
