/**
 * @file
 * Named probe points and sampled lines (prm subsection `Monitors`), written
 * to probes.csv and lines.csv with the columns `time,name,x,y,<fields>`.
 */
#ifndef tmfdem_io_monitors_h
#define tmfdem_io_monitors_h

#include <deal.II/dofs/dof_handler.h>
#include <deal.II/fe/mapping.h>
#include <deal.II/lac/trilinos_vector.h>

#include <functional>
#include <string>
#include <tmfdem/base/parameters.h>
#include <tmfdem/io/output_files.h>
#include <vector>

namespace tmfdem
{
  /**
   * Samples a finite element field at the monitor points. Works under MPI:
   * the rank owning the cell around a point evaluates it, rank 0 writes.
   */
  template <int dim>
  class Monitors
  {
  public:
    /**
     * @p field_names are the CSV column names of the components of the
     * DoFHandler's finite element, in order (e.g. {"T"}).
     */
    Monitors(const MonitorParameters        &parameters,
             const std::string              &folder,
             const std::vector<std::string> &field_names,
             MPI_Comm                        communicator);

    /**
     * Throws InputError naming the first probe or line point that lies
     * outside the mesh of @p dof_handler.
     */
    void
    check_points(const Mapping<dim>    &mapping,
                 const DoFHandler<dim> &dof_handler) const;

    /** Appends the rows of output time @p time [s]; @p solution is ghosted. */
    void
    write(const double                         time,
          const Mapping<dim>                  &mapping,
          const DoFHandler<dim>               &dof_handler,
          const TrilinosWrappers::MPI::Vector &solution);

    /**
     * Computes the field values (one per column of field_names) at a point
     * given by its cell and its coordinates in the reference cell.
     */
    using PointEvaluator = std::function<std::vector<double>(
      const typename DoFHandler<dim>::active_cell_iterator &cell,
      const Point<dim>                                     &unit_point)>;

    /**
     * Appends the rows of output time @p time [s], each value computed by
     * @p evaluator (derived fields such as stress from gradients, evaluated
     * at the point itself, not averaged over its cell).
     */
    void
    write(const double           time,
          const Mapping<dim>    &mapping,
          const DoFHandler<dim> &dof_handler,
          const PointEvaluator  &evaluator);

  private:
    struct SamplePoint
    {
      std::string name;
      Point<dim>  location;
      bool        from_line;
    };

    /** Values at every sample point, summed over ranks; NaN if not found. */
    std::vector<std::vector<double>>
    evaluate(const Mapping<dim>    &mapping,
             const DoFHandler<dim> &dof_handler,
             const PointEvaluator  *evaluator) const;

    std::vector<SamplePoint> points;
    unsigned int             n_components;
    MPI_Comm                 communicator;
    CsvSeries                probes_csv, lines_csv;
  };
} // namespace tmfdem

#endif
