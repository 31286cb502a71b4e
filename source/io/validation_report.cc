#include <deal.II/base/mpi.h>

#include <cmath>
#include <iomanip>
#include <sstream>
#include <sys/resource.h>
#include <tmfdem/io/validation_report.h>

namespace tmfdem
{
  namespace
  {
    /** Peak resident memory of this process so far [bytes]. */
    double
    resident_bytes()
    {
      rusage usage{};
      getrusage(RUSAGE_SELF, &usage);
      return static_cast<double>(usage.ru_maxrss) * 1024.;
    }
  } // namespace

  namespace validation
  {
    void
    describe_steps(std::ostream      &out,
                   const std::string &what,
                   const double       stable,
                   const double       used,
                   const Parameters  &parameters)
    {
      out << "  " << what << ": ";
      if (stable > 0.)
        out << "stable " << stable << " s, ";
      out << "used " << used << " s";
      if (used > 0.)
        out << ", "
            << static_cast<long long>(std::ceil(
                 (parameters.time.end_time - parameters.time.start_time) /
                   used -
                 1e-9))
            << " steps to End time = " << parameters.time.end_time << " s";
      out << "\n";
    }
  } // namespace validation

  std::string
  validation_report(Simulation       &simulation,
                    const Parameters &parameters,
                    MPI_Comm          communicator)
  {
    std::ostringstream out;
    out << std::setprecision(4);
    if (const auto *reporter =
          dynamic_cast<const ValidationReporter *>(&simulation))
      reporter->report_validation(out, parameters, communicator);
    if (!parameters.sections_read.empty())
      {
        out << "  subsections read by Model = " << parameters.model << ":";
        for (const std::string &name : parameters.sections_read)
          out << (name == parameters.sections_read.front() ? " " : ", ")
              << name;
        out << "\n";
      }
    for (const std::string &entry : parameters.unread_entries)
      out << "  not read by this model: " << entry << "\n";
    out << "  resident memory after the checks: "
        << Utilities::MPI::max(resident_bytes(), communicator) /
             validation::mebibyte
        << " MiB per process\n";
    return out.str();
  }
} // namespace tmfdem
