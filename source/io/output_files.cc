#include <deal.II/base/mpi.h>
#include <deal.II/base/utilities.h>

#include <cerrno>
#include <cmath>
#include <csignal>
#include <cstdio>
#include <fcntl.h>
#include <filesystem>
#include <iomanip>
#include <iostream>
#include <sstream>
#include <tmfdem/base/exceptions.h>
#include <tmfdem/io/checkpoint.h>
#include <tmfdem/io/output_files.h>
#include <unistd.h>
#include <vector>

namespace tmfdem
{
  void
  on_rank_zero(MPI_Comm communicator, const std::function<void()> &write)
  {
    if (Utilities::MPI::n_mpi_processes(communicator) == 1)
      {
        write();
        return;
      }
    std::string failure;
    if (Utilities::MPI::this_mpi_process(communicator) == 0)
      try
        {
          write();
        }
      catch (const std::exception &e)
        {
          failure = e.what();
          if (failure.empty())
            failure = "writing an output failed on rank 0";
        }
    failure = Utilities::MPI::broadcast(communicator, failure, 0);
    if (!failure.empty())
      throw RunError(failure);
  }

  void
  write_file_atomically(const std::string &file_name,
                        const std::string &content)
  {
    const std::string temporary =
      file_name + ".tmp" + std::to_string(::getpid());
    {
      std::ofstream out(temporary, std::ios::binary);
      out << content;
      out.flush();
      if (!out)
        throw RunError("cannot write '" + temporary +
                       "' (disk full or no "
                       "permission?)");
    }
    if (std::rename(temporary.c_str(), file_name.c_str()) != 0)
      {
        std::remove(temporary.c_str()); // no stray temporary left behind
        throw RunError("cannot write '" + file_name +
                       "' (renaming its temporary failed: a folder of that "
                       "name, or no permission?)");
      }
  }

  namespace
  {
    /**
     * Removes the temporaries of write_file_atomically() and of checkpoints
     * ("<file>.tmp<pid>") in @p folder that a run which is no longer alive
     * left behind (killed while writing); says so on stderr. Those of live
     * processes (other ranks, this one) stay.
     */
    void
    remove_stray_temporaries(const std::string &folder)
    {
      std::vector<std::string> removed;
      std::error_code          code;
      for (const auto &entry :
           std::filesystem::directory_iterator(folder, code))
        {
          if (!entry.is_regular_file(code))
            continue;
          const std::string name = entry.path().filename().string();
          const auto        tmp  = name.rfind(".tmp");
          if (tmp == std::string::npos || tmp == 0 || tmp + 4 == name.size() ||
              name.size() - tmp - 4 > 9 ||
              name.find_first_not_of("0123456789", tmp + 4) !=
                std::string::npos)
            continue;
          const pid_t pid = std::stoi(name.substr(tmp + 4));
          if (pid == ::getpid() || (::kill(pid, 0) == 0 || errno == EPERM))
            continue; // a live process's file
          if (std::filesystem::remove(entry.path(), code))
            removed.push_back(name);
        }
      if (removed.empty())
        return;
      std::ostringstream line;
      line << "[tmfdem] removed " << removed.size()
           << " temporary file(s) that an earlier run, stopped while writing, "
              "left in "
           << folder << ":";
      for (unsigned int i = 0; i < removed.size() && i < 5; ++i)
        line << " " << removed[i];
      if (removed.size() > 5)
        line << " ...";
      std::cerr << line.str() << std::endl;
    }
  } // namespace

  void
  create_output_folder(const std::string &folder, MPI_Comm communicator)
  {
    std::string error;
    if (Utilities::MPI::this_mpi_process(communicator) == 0)
      {
        std::error_code code;
        std::filesystem::create_directories(folder, code);
        if (code || !std::filesystem::is_directory(folder))
          error = "cannot create the output folder '" + folder +
                  "': " + code.message();
        else
          {
            remove_stray_temporaries(folder);
            // and in the default checkpoint folder (Checkpoint/Directory)
            if (std::filesystem::is_directory(folder + "/checkpoints", code))
              remove_stray_temporaries(folder + "/checkpoints");
          }
      }
    error = Utilities::MPI::broadcast(communicator, error, 0);
    if (!error.empty())
      throw RunError(error);
  }

  // ------------------------------------------------------- SolutionSeries
  SolutionSeries::SolutionSeries(const std::string &folder,
                                 const std::string &base_name,
                                 MPI_Comm           communicator,
                                 const bool         binary)
    : folder(folder)
    , base_name(base_name)
    , communicator(communicator)
    , binary(binary)
  {}

  template <int dim>
  void
  SolutionSeries::write(DataOut<dim> &data_out, const double time)
  {
    const unsigned int n_ranks = Utilities::MPI::n_mpi_processes(communicator);
    const unsigned int rank    = Utilities::MPI::this_mpi_process(communicator);
    const std::string  stem =
      base_name + "_" + Utilities::int_to_string(records.size(), 5);

    DataOutBase::VtkFlags flags;
    flags.time  = time;
    flags.cycle = records.size();
    // deal.II 9.4 writes base64 blocks whenever it has zlib: ascii leaves
    // them uncompressed
    flags.compression_level = binary ? DataOutBase::VtkFlags::best_speed :
                                       DataOutBase::VtkFlags::no_compression;
    data_out.set_flags(flags);

    const std::string piece =
      n_ranks == 1 ? stem + ".vtu" :
                     stem + "." + Utilities::int_to_string(rank, 4) + ".vtu";
    std::ostringstream vtu;
    data_out.write_vtu(vtu);
    write_file_atomically(folder + "/" + piece, vtu.str());

    std::string record = piece;
    if (n_ranks > 1)
      {
        record = stem + ".pvtu";
        if (rank == 0)
          {
            std::vector<std::string> pieces;
            for (unsigned int r = 0; r < n_ranks; ++r)
              pieces.push_back(stem + "." + Utilities::int_to_string(r, 4) +
                               ".vtu");
            std::ostringstream pvtu;
            data_out.write_pvtu_record(pvtu, pieces);
            write_file_atomically(folder + "/" + record, pvtu.str());
          }
      }
    records.emplace_back(time, record);
    if (rank == 0)
      {
        std::ostringstream pvd;
        DataOutBase::write_pvd_record(pvd, records);
        write_file_atomically(folder + "/" + base_name + ".pvd", pvd.str());
      }
  }

  template void
  SolutionSeries::write<2>(DataOut<2> &, const double);
  template void
  SolutionSeries::write<3>(DataOut<3> &, const double);

  // ------------------------------------------------------------ CsvSeries
  CsvSeries::CsvSeries(const std::string &file_name,
                       const std::string &header,
                       MPI_Comm           communicator)
    : file_name(file_name)
    , writer(Utilities::MPI::this_mpi_process(communicator) == 0)
  {
    if (writer)
      write_file_atomically(file_name, header + "\n");
  }

  void
  CsvSeries::append(const std::string &rows)
  {
    if (!writer || rows.empty())
      return;
    const int fd = ::open(file_name.c_str(), O_WRONLY | O_APPEND);
    if (fd < 0)
      throw RunError("cannot append to '" + file_name + "'");
    std::size_t done = 0;
    while (done < rows.size())
      {
        const ssize_t n = ::write(fd, rows.data() + done, rows.size() - done);
        if (n < 0 && errno == EINTR)
          continue;
        if (n <= 0)
          {
            ::close(fd);
            throw RunError("cannot append to '" + file_name + "' (disk full?)");
          }
        done += n;
      }
    ::close(fd);
  }

  CsvSeries
  CsvSeries::reopen(const std::string  &file_name,
                    const std::uint64_t size,
                    MPI_Comm            communicator)
  {
    CsvSeries series;
    series.file_name = file_name;
    series.writer    = Utilities::MPI::this_mpi_process(communicator) == 0;
    if (series.writer)
      truncate_file(file_name, size);
    return series;
  }

  std::uint64_t
  CsvSeries::size() const
  {
    return writer ? file_size(file_name) : 0;
  }

  // ----------------------------------------------------------- JsonObject
  namespace
  {
    std::string
    json_string(const std::string &text)
    {
      std::string quoted = "\"";
      for (const char c : text)
        {
          if (c == '"' || c == '\\')
            quoted += '\\';
          if (c == '\n')
            {
              quoted += "\\n";
              continue;
            }
          quoted += c;
        }
      return quoted + "\"";
    }
  } // namespace

  JsonObject &
  JsonObject::add(const std::string &key, const double value)
  {
    std::ostringstream text;
    if (std::isfinite(value))
      text << std::setprecision(17) << value;
    else
      text << "null";
    members.emplace_back(key, text.str());
    return *this;
  }

  JsonObject &
  JsonObject::add(const std::string &key, const long long value)
  {
    members.emplace_back(key, std::to_string(value));
    return *this;
  }

  JsonObject &
  JsonObject::add(const std::string &key, const unsigned int value)
  {
    members.emplace_back(key, std::to_string(value));
    return *this;
  }

  JsonObject &
  JsonObject::add(const std::string &key, const std::string &value)
  {
    members.emplace_back(key, json_string(value));
    return *this;
  }

  JsonObject &
  JsonObject::add(const std::string &key, const bool value)
  {
    members.emplace_back(key, value ? "true" : "false");
    return *this;
  }

  JsonObject &
  JsonObject::add(const std::string &key, const JsonObject &value)
  {
    members.emplace_back(key, "\x01" + std::to_string(nested.size()));
    nested.push_back(value);
    return *this;
  }

  JsonObject &
  JsonObject::add(const std::string &key, const std::vector<JsonObject> &values)
  {
    members.emplace_back(key, "\x02" + std::to_string(arrays.size()));
    arrays.push_back(values);
    return *this;
  }

  std::string
  JsonObject::str(const unsigned int indent) const
  {
    const std::string pad(indent + 2, ' ');
    std::string       text = "{\n";
    for (unsigned int i = 0; i < members.size(); ++i)
      {
        const auto &[key, value] = members[i];
        text += pad + json_string(key) + ": ";
        if (!value.empty() && value[0] == '\x01')
          text += nested[std::stoul(value.substr(1))].str(indent + 2);
        else if (!value.empty() && value[0] == '\x02')
          {
            const auto &array = arrays[std::stoul(value.substr(1))];
            text += "[";
            for (unsigned int j = 0; j < array.size(); ++j)
              text += (j > 0 ? ", " : "") + array[j].str(indent + 2);
            text += "]";
          }
        else
          text += value;
        text += (i + 1 < members.size() ? ",\n" : "\n");
      }
    return text + std::string(indent, ' ') + "}";
  }

  // ------------------------------------------------------ ProgressReporter
  ProgressReporter::ProgressReporter(const double interval,
                                     const double start_time,
                                     const double end_time,
                                     const bool   active,
                                     const bool   eta_from_time)
    : interval(interval)
    , start_time(start_time)
    , end_time(end_time)
    , active(active && interval > 0)
    , eta_from_time(eta_from_time)
    , start(Clock::now())
    , last(start)
  {}

  double
  ProgressReporter::elapsed() const
  {
    return std::chrono::duration<double>(Clock::now() - start).count();
  }

  void
  ProgressReporter::update(const unsigned long step,
                           const double        time,
                           const std::string  &extra)
  {
    if (!active)
      return;
    const auto now = Clock::now();
    if (std::chrono::duration<double>(now - last).count() < interval)
      return;
    last                    = now;
    const double       wall = elapsed();
    const double       done = (time - start_time) / (end_time - start_time);
    const double       eta  = done > 0 ? wall * (1. - done) / done : 0.;
    std::ostringstream line;
    line << std::setprecision(4) << "[tmfdem] step " << step << "  t = " << time
         << " s (" << std::fixed << std::setprecision(1) << 100. * done
         << " %)  " << std::setprecision(1) << step / std::max(wall, 1e-9)
         << " steps/s";
    if (eta_from_time)
      line << "  ETA " << eta << " s";
    line << extra << "\n";
    std::cerr << line.str() << std::flush;
  }
} // namespace tmfdem
