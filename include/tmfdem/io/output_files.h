/**
 * @file
 * Output files that never end up half-written: text written to a temporary
 * file and renamed over the target, the solution.pvd series of vtu/pvtu
 * files, CSV series with a header and appended rows, and the progress line.
 */
#ifndef tmfdem_io_output_files_h
#define tmfdem_io_output_files_h

#include <deal.II/numerics/data_out.h>

#include <chrono>
#include <cstdint>
#include <fstream>
#include <functional>
#include <mpi.h>
#include <string>
#include <utility>
#include <vector>

namespace tmfdem
{
  using namespace dealii;

  /**
   * Writes @p content to @p file_name through a temporary file in the same
   * folder and a rename, so that readers (and a run killed meanwhile) see the
   * old or the new file, never a partial one. Throws RunError on failure.
   */
  void
  write_file_atomically(const std::string &file_name,
                        const std::string &content);

  /**
   * Runs @p write on rank 0 of @p communicator (on one rank: just runs it);
   * a failure there stops every rank with rank 0's message (RunError), so
   * no rank hangs in a later collective call.
   */
  void
  on_rank_zero(MPI_Comm communicator, const std::function<void()> &write);

  /** Creates @p folder (and parents) on rank 0; RunError if impossible. */
  void
  create_output_folder(const std::string &folder, MPI_Comm communicator);

  /**
   * The `solution.pvd` time series: one vtu per output (one per rank and a
   * pvtu record under MPI), the pvd rewritten atomically after each.
   */
  class SolutionSeries
  {
  public:
    /** @p binary: vtu files with zlib-compressed blocks (deal.II's
     *  fastest level), otherwise uncompressed ones (deal.II 9.4 writes
     *  base64-encoded Float32 blocks whenever it has zlib). */
    SolutionSeries(const std::string &folder,
                   const std::string &base_name,
                   MPI_Comm           communicator,
                   const bool         binary = true);

    /** Writes the patches built in @p data_out as the output at @p time [s]. */
    template <int dim>
    void
    write(DataOut<dim> &data_out, const double time);

  private:
    std::string                                 folder;
    std::string                                 base_name;
    MPI_Comm                                    communicator;
    bool                                        binary;
    std::vector<std::pair<double, std::string>> records;
  };

  /**
   * A CSV file with a header line and rows appended (and flushed) as the run
   * goes. Only rank 0 writes.
   */
  class CsvSeries
  {
  public:
    CsvSeries() = default;
    CsvSeries(const std::string &file_name,
              const std::string &header,
              MPI_Comm           communicator);
    /**
     * Appends the lines in @p rows (each ending in a newline) with one
     * write(2) on a file opened for appending, so whole rows reach the file
     * together; a run killed meanwhile can at worst leave one partial
     * row, which --resume cuts off (truncate_file()).
     */
    void
    append(const std::string &rows);

    /** Continues the existing file @p file_name (written by this run before
     *  a checkpoint), cut to its @p size bytes at the checkpoint. */
    static CsvSeries
    reopen(const std::string  &file_name,
           const std::uint64_t size,
           MPI_Comm            communicator);

    /** The file's current size [bytes] (0 off rank 0), for checkpoints. */
    std::uint64_t
    size() const;

  private:
    std::string file_name;
    bool        writer = false;
  };

  /**
   * Minimal JSON object builder for summary.json: keys in insertion order,
   * numbers written with 17 significant digits.
   */
  class JsonObject
  {
  public:
    JsonObject &
    add(const std::string &key, const double value);
    JsonObject &
    add(const std::string &key, const long long value);
    JsonObject &
    add(const std::string &key, const unsigned int value);
    JsonObject &
    add(const std::string &key, const std::string &value);
    JsonObject &
    add(const std::string &key, const bool value);
    JsonObject &
    add(const std::string &key, const JsonObject &value);
    JsonObject &
    add(const std::string &key, const std::vector<JsonObject> &values);
    /** The object as text, indented by @p indent spaces. */
    std::string
    str(const unsigned int indent = 0) const;

  private:
    std::vector<std::pair<std::string, std::string>> members;
    std::vector<JsonObject>                          nested;
    std::vector<std::vector<JsonObject>>             arrays;
  };

  /**
   * A progress line on stderr every @p interval seconds of wall time: step,
   * physical time, steps per second and the estimated time to the end.
   */
  class ProgressReporter
  {
  public:
    /** Lines every @p interval seconds of wall time, with an estimate of
     *  the time left where the work is proportional to the simulated time
     *  (@p eta_from_time; not so for quasi-static coupling, whose thermal
     *  steps shorten near failure). */
    ProgressReporter(const double interval,
                     const double start_time,
                     const double end_time,
                     const bool   active,
                     const bool   eta_from_time = true);
    /** Reports if the interval has passed since the last line. */
    void
    update(const unsigned long step,
           const double        time,
           const std::string  &extra = "");
    /** Wall time since construction [s]. */
    double
    elapsed() const;

  private:
    using Clock = std::chrono::steady_clock;
    double            interval, start_time, end_time;
    bool              active, eta_from_time;
    Clock::time_point start, last;
  };
} // namespace tmfdem

#endif
