/**
 * @file
 * Output of the discrete layer in the current (exploded) configuration, so
 * that cracks open visibly in ParaView: `solution.pvd` with displacement,
 * velocity, stress, material, body and joint damage per triangle, and
 * `cracks.pvd` with every broken joint as a line cell labelled by failure
 * mode (1 Mode I, 2 Mode II, 3 mixed) and break time.
 */
#ifndef tmfdem_discrete_discrete_output_h
#define tmfdem_discrete_discrete_output_h

#include <string>
#include <tmfdem/discrete/discrete_model.h>
#include <utility>
#include <vector>

namespace tmfdem
{
  class JsonObject;
} // namespace tmfdem

namespace tmfdem
{
  namespace discrete
  {
    /** A vtu time series: `<base>_NNNNN.vtu` files and `<base>.pvd`, each
     *  written atomically. */
    class VtuSeries
    {
    public:
      VtuSeries(const std::string &folder, const std::string &base_name);
      /** Writes @p vtu_text as the output at @p time [s]. */
      void
      write(const double time, const std::string &vtu_text);
      /** The (time [s], file) records so far, for checkpoints. */
      const std::vector<std::pair<double, std::string>> &
      get_records() const
      {
        return records;
      }
      /** Continues a series from a checkpoint's @p saved records: the pvd
       *  is rewritten with exactly these (atomically). */
      void
      restore(const std::vector<std::pair<double, std::string>> &saved);

    private:
      void
                                                  write_pvd() const;
      std::string                                 folder, base_name;
      std::vector<std::pair<double, std::string>> records;
    };

    /** The exploded mesh as a VTK UnstructuredGrid document. Extra nodal
     *  scalar fields (name, values per node) are added as point data. */
    std::string
    discrete_solution_vtu(
      const DiscreteModel &model,
      const std::vector<std::pair<std::string, const std::vector<double> *>>
        &extra_point_fields = {});

    /** Broken joints as line cells (one per joint, between the midpoints
     *  of its two faces' end nodes). */
    std::string
    crack_vtu(const DiscreteModel &model);

    /**
     * The current configuration as a gmsh 2.2 ASCII mesh (Output/Write
     * final mesh): one vertex per vertex of the original mesh at the mean
     * position of its copies (intact joints keep them together; a vertex
     * whose copies have separated along broken joints is averaged too, so
     * this suits meshes without broken joints, e.g. a settled heap of
     * intact blocks), triangles with their material ids as physical tags and
     * boundary edges with boundary id > 0 as line elements.
     */
    std::string
    deformed_mesh_msh(const DiscreteModel &model);
    class TemperatureSource;

    /** summary.json's heat balance of a discrete temperature source: heat
     *  in per boundary id, from sources, across contacts, stored [J/m], the
     *  boundary rates of the last step [W/m] and the imbalance. */
    JsonObject
    heat_balance_summary(const TemperatureSource &source);
  } // namespace discrete
} // namespace tmfdem

#endif
