#include <deal.II/base/mpi.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <fcntl.h>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <sys/stat.h>
#include <tmfdem/base/exceptions.h>
#include <tmfdem/io/checkpoint.h>
#include <tmfdem/io/output_files.h>
#include <unistd.h>

namespace tmfdem
{
  // ---------------------------------------------------------------- signals
  namespace internal
  {
    volatile std::sig_atomic_t stop_signal = 0;
  } // namespace internal

  namespace
  {
    extern "C" void
    handle_stop_signal(int signal)
    {
      if (internal::stop_signal != 0)
        {
          // a second signal: the default action (terminate) at once
          std::signal(signal, SIG_DFL);
          std::raise(signal);
          return;
        }
      internal::stop_signal = signal;
    }

    constexpr char          magic[8] = {'T', 'M', 'F', 'D', 'E', 'M', 'C', 'K'};
    constexpr std::uint32_t format_version = 8;
    constexpr std::size_t   header_bytes   = 32;

    std::uint64_t
    fnv1a(const std::string &data)
    {
      std::uint64_t hash = 1469598103934665603ull;
      for (const unsigned char c : data)
        {
          hash ^= c;
          hash *= 1099511628211ull;
        }
      return hash;
    }
  } // namespace

  void
  install_signal_handlers()
  {
    struct sigaction action;
    std::memset(&action, 0, sizeof(action));
    action.sa_handler = handle_stop_signal;
    sigemptyset(&action.sa_mask);
    action.sa_flags = SA_RESTART;
    sigaction(SIGINT, &action, nullptr);
    sigaction(SIGTERM, &action, nullptr);
  }

  std::string
  stop_signal_name()
  {
    switch (internal::stop_signal)
      {
        case SIGINT:
          return "SIGINT";
        case SIGTERM:
          return "SIGTERM";
        case 0:
          return "";
        default:
          return "signal " + std::to_string(internal::stop_signal);
      }
  }

  bool
  stop_requested_on_any_rank(MPI_Comm communicator)
  {
    const int local = stop_requested() ? 1 : 0;
    if (Utilities::MPI::n_mpi_processes(communicator) == 1)
      return local != 0;
    const int any = Utilities::MPI::max(local, communicator);
    if (any != 0 && internal::stop_signal == 0)
      internal::stop_signal = SIGTERM; // another rank got it
    return any != 0;
  }

  // ----------------------------------------------------------- the format
  CheckpointWriter::CheckpointWriter(const std::string &kind,
                                     const std::string &digest)
  {
    put(kind);
    put(digest);
  }

  void
  CheckpointWriter::append(const void *data, const std::size_t bytes)
  {
    payload.append(static_cast<const char *>(data), bytes);
  }

  void
  CheckpointWriter::put(const std::string &text)
  {
    put<std::uint64_t>(text.size());
    append(text.data(), text.size());
  }

  std::string
  CheckpointWriter::file_content() const
  {
    std::string         content(magic, sizeof(magic));
    const std::uint32_t version  = format_version;
    const std::uint32_t reserved = 0;
    const std::uint64_t length   = payload.size();
    const std::uint64_t checksum = fnv1a(payload);
    content.append(reinterpret_cast<const char *>(&version), 4);
    content.append(reinterpret_cast<const char *>(&reserved), 4);
    content.append(reinterpret_cast<const char *>(&length), 8);
    content.append(reinterpret_cast<const char *>(&checksum), 8);
    return content + payload;
  }

  CheckpointReader::CheckpointReader(const std::string &file_name,
                                     const std::string &kind,
                                     const std::string &digest)
    : file_name(file_name)
  {
    std::ifstream in(file_name, std::ios::binary);
    if (!in)
      throw InputError("cannot open the checkpoint '" + file_name + "'.");
    std::string       content((std::istreambuf_iterator<char>(in)),
                        std::istreambuf_iterator<char>());
    const std::string where = "the checkpoint '" + file_name + "' ";
    if (content.size() < header_bytes ||
        content.compare(0, sizeof(magic), magic, sizeof(magic)) != 0)
      throw InputError(where + "is not a tmfdem checkpoint (no TMFDEMCK "
                               "header); delete it or point "
                               "Checkpoint/Directory elsewhere.");
    std::uint32_t version;
    std::uint64_t length, checksum;
    std::memcpy(&version, content.data() + 8, 4);
    std::memcpy(&length, content.data() + 16, 8);
    std::memcpy(&checksum, content.data() + 24, 8);
    if (version != format_version)
      throw InputError(where + "has format version " + std::to_string(version) +
                       "; this tmfdem reads version " +
                       std::to_string(format_version) + ".");
    if (length != content.size() - header_bytes)
      throw InputError(where + "is truncated or corrupt: " +
                       std::to_string(content.size() - header_bytes) +
                       " bytes of data where the header announces " +
                       std::to_string(length) +
                       "; delete it to resume from an older checkpoint.");
    payload = content.substr(header_bytes);
    if (fnv1a(payload) != checksum)
      throw InputError(where + "is corrupt (checksum mismatch); delete it to "
                               "resume from an older checkpoint.");
    std::string file_kind, file_digest;
    get(file_kind);
    get(file_digest);
    if (file_kind != kind)
      throw InputError(where + "was written by the model '" + file_kind +
                       "', not '" + kind + "'.");
    if (file_digest != digest)
      throw InputError(
        where + "was written for a different input (digest " + file_digest +
        ", this input " + digest +
        "): resume with the same prm file and --set options (only Checkpoint, "
        "Output/Directory, Output/Progress interval, Discrete "
        "mechanics/Threads and Time stepping/End time may change), or start "
        "afresh without --resume.");
  }

  CheckpointReader::CheckpointReader(const CheckpointWriter &writer,
                                     const std::string      &name)
    : file_name(name)
    , payload(writer.payload)
  {
    std::string kind, digest;
    get(kind);
    get(digest);
  }

  void
  CheckpointReader::extract(void *data, const std::size_t bytes)
  {
    if (bytes > payload.size() - position)
      throw InputError("the checkpoint '" + file_name +
                       "' ends early (truncated or from another version).");
    if (bytes > 0)
      std::memcpy(data, payload.data() + position, bytes);
    position += bytes;
  }

  std::size_t
  CheckpointReader::get_size(const std::size_t expected,
                             const std::size_t element_bytes)
  {
    std::uint64_t n = 0;
    get(n);
    if (expected != static_cast<std::size_t>(-1) && n != expected)
      throw InputError("the checkpoint '" + file_name + "' holds an array of " +
                       std::to_string(n) + " entries where this run has " +
                       std::to_string(expected) + " (another mesh or model?).");
    if (n >
        (payload.size() - position) / std::max<std::size_t>(1, element_bytes))
      throw InputError("the checkpoint '" + file_name +
                       "' ends early (truncated or from another version).");
    return n;
  }

  void
  CheckpointReader::get(std::string &text)
  {
    const std::size_t n = get_size(static_cast<std::size_t>(-1), 1);
    text.assign(payload.data() + position, n);
    position += n;
  }

  void
  CheckpointReader::finish() const
  {
    if (position != payload.size())
      throw InputError("the checkpoint '" + file_name + "' has " +
                       std::to_string(payload.size() - position) +
                       " bytes more than this version of tmfdem reads.");
  }

  // ---------------------------------------------------- files and schedule
  std::string
  checkpoint_folder(const Parameters &parameters)
  {
    return parameters.checkpoint.directory.empty() ?
             parameters.output.directory + "/checkpoints" :
             parameters.checkpoint.directory;
  }

  namespace
  {
    /** (sequence, path) of the checkpoint files in @p folder, oldest
     *  first. */
    std::vector<std::pair<unsigned long, std::string>>
    list_checkpoints(const std::string &folder)
    {
      std::vector<std::pair<unsigned long, std::string>> files;
      std::error_code                                    code;
      if (!std::filesystem::is_directory(folder, code))
        return files;
      for (const auto &entry :
           std::filesystem::directory_iterator(folder, code))
        {
          const std::string name   = entry.path().filename().string();
          const std::string prefix = "checkpoint_", suffix = ".tmfchk";
          if (name.size() <= prefix.size() + suffix.size() ||
              name.compare(0, prefix.size(), prefix) != 0 ||
              name.compare(name.size() - suffix.size(),
                           suffix.size(),
                           suffix) != 0)
            continue;
          const std::string number =
            name.substr(prefix.size(),
                        name.size() - prefix.size() - suffix.size());
          if (number.find_first_not_of("0123456789") != std::string::npos)
            continue;
          files.emplace_back(std::stoul(number), entry.path().string());
        }
      std::sort(files.begin(), files.end());
      return files;
    }
  } // namespace

  std::size_t
  write_checkpoint(const Parameters       &parameters,
                   const unsigned long     sequence,
                   const CheckpointWriter &writer)
  {
    const std::string folder = checkpoint_folder(parameters);
    std::error_code   code;
    std::filesystem::create_directories(folder, code);
    if (!std::filesystem::is_directory(folder))
      throw RunError("cannot create the checkpoint folder '" + folder + "'");
    char number[32];
    std::snprintf(number, sizeof(number), "%012lu", sequence);
    const std::string file      = folder + "/checkpoint_" + number + ".tmfchk";
    const std::string temporary = file + ".tmp" + std::to_string(::getpid());
    const std::string content   = writer.file_content();
    {
      const int fd =
        ::open(temporary.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
      if (fd < 0)
        throw RunError("cannot write the checkpoint '" + temporary + "'");
      std::size_t done = 0;
      while (done < content.size())
        {
          const ssize_t n =
            ::write(fd, content.data() + done, content.size() - done);
          if (n < 0 && errno == EINTR)
            continue;
          if (n <= 0)
            {
              ::close(fd);
              throw RunError("cannot write the checkpoint '" + temporary +
                             "' (disk full?)");
            }
          done += n;
        }
      ::fsync(fd);
      ::close(fd);
    }
    if (std::rename(temporary.c_str(), file.c_str()) != 0)
      throw RunError("cannot rename '" + temporary + "' to '" + file + "'");
    auto files = list_checkpoints(folder);
    for (std::size_t i = 0; i + parameters.checkpoint.keep < files.size(); ++i)
      std::filesystem::remove(files[i].second, code);
    return content.size();
  }

  std::string
  newest_checkpoint(const Parameters &parameters)
  {
    const std::string folder = checkpoint_folder(parameters);
    const auto        files  = list_checkpoints(folder);
    if (files.empty())
      throw InputError("--resume: there is no checkpoint in '" + folder +
                       "' (set Checkpoint/Interval (steps) or Interval (wall "
                       "minutes) for the run to write them; to start afresh, "
                       "run without --resume).");
    return files.back().second;
  }

  CheckpointSchedule::CheckpointSchedule(const CheckpointParameters &p)
    : interval_steps(p.interval_steps)
    , interval_seconds(60. * p.interval_minutes)
    , last_time(Clock::now())
  {}

  bool
  CheckpointSchedule::due(const unsigned long steps)
  {
    if (interval_steps > 0 && steps >= last_steps + interval_steps)
      return true;
    if (interval_seconds > 0. && (steps & 15) == 0 &&
        std::chrono::duration<double>(Clock::now() - last_time).count() >=
          interval_seconds)
      return true;
    return false;
  }

  void
  CheckpointSchedule::written(const unsigned long steps)
  {
    last_steps = steps;
    last_time  = Clock::now();
  }

  std::uint64_t
  file_size(const std::string &file_name)
  {
    std::error_code code;
    const auto      size = std::filesystem::file_size(file_name, code);
    return code ? 0 : static_cast<std::uint64_t>(size);
  }

  void
  truncate_file(const std::string &file_name, const std::uint64_t size)
  {
    const std::uint64_t now = file_size(file_name);
    if (now < size)
      throw RunError("--resume: '" + file_name + "' has " +
                     std::to_string(now) + " bytes, fewer than the " +
                     std::to_string(size) +
                     " it had at the checkpoint; it was changed or removed "
                     "since.");
    if (now > size && ::truncate(file_name.c_str(), size) != 0)
      throw RunError("--resume: cannot truncate '" + file_name + "'");
  }
  unsigned int
  continue_output_times(const std::string         &file,
                        const double               time,
                        const double               end_time,
                        const std::vector<double> &saved,
                        const unsigned int         saved_next,
                        std::vector<double>       &fresh,
                        const double               tolerance)
  {
    if (!saved.empty() && std::abs(saved.back() - end_time) <= tolerance)
      {
        fresh = saved; // same End time: exactly as written
        return saved_next;
      }
    if (end_time < time - tolerance)
      throw InputError(
        "--resume: Time stepping/End time = " + Utilities::to_string(end_time) +
        " s lies before the time of the checkpoint '" + file +
        "', t = " + Utilities::to_string(time) +
        " s; allowed is an End time at or after it (End time may change on "
        "--resume, to continue a run).");
    if (saved_next == 0)
      return 0;
    const double last_written = saved[saved_next - 1];
    unsigned int next         = 0;
    while (next < fresh.size() && fresh[next] <= last_written + tolerance)
      ++next;
    return next;
  }
} // namespace tmfdem
