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

#include <array>
#include <map>
#include <string>
#include <tmfdem/discrete/discrete_model.h>
#include <utility>
#include <vector>

namespace tmfdem
{
  class CheckpointWriter;
  class CheckpointReader;

  class JsonObject;
  struct OutputParameters;
} // namespace tmfdem

namespace tmfdem
{
  namespace discrete
  {
    /**
     * How the discrete layer's vtu files hold their arrays (Output/Vtu
     * format, Output/Vtu precision).
     */
    struct VtuEncoding
    {
      /** true: VTK XML appended raw data (`<AppendedData
       *  encoding="raw">`), every DataArray one zlib block with a UInt64
       *  header (vtkZLibDataCompressor, level vtu_zlib_level); false:
       *  ascii, each value the shortest text that reads back as exactly
       *  the stored value. */
      bool binary = true;
      /** true: point coordinates and real point and cell data as Float32,
       *  each the double rounded to the nearest float; false: Float64.
       *  Integer arrays keep their types either way. */
      bool single_precision = true;
    };

    /** The encoding that @p output (Output/Vtu format, Vtu precision)
     *  names. */
    VtuEncoding
    vtu_encoding(const OutputParameters &output);

    /** zlib level of every binary DataArray (1: fastest; higher levels
     *  save a few per cent of the size at several times the time,
     *  doc/performance.md "Output files"). */
    constexpr int vtu_zlib_level = 1;

    /**
     * A vtu time series: `<base>_NNNNN.vtu` files and `<base>.pvd`, each
     * written atomically. On several MPI ranks each output is one piece per
     * rank, `<base>_NNNNN.RRRR.vtu` (write_piece() on every rank), and a
     * `<base>_NNNNN.pvtu` record of the pieces that the pvd lists
     * (write_parallel_record() on rank 0; add_parallel_record() on the
     * others keeps their count of outputs).
     */
    class VtuSeries
    {
    public:
      VtuSeries(const std::string &folder, const std::string &base_name);
      /** Writes @p vtu_text as the output at @p time [s]. */
      void
      write(const double time, const std::string &vtu_text);
      /** Writes this rank's piece @p vtu_text of the next output. */
      void
      write_piece(const unsigned int rank, const std::string &vtu_text) const;
      /** After every rank wrote its piece of the next output: writes its
       *  pvtu record of @p n_ranks pieces (the array declarations taken from
       *  @p piece_text, one of the pieces) and the pvd. */
      void
      write_parallel_record(const double       time,
                            const unsigned int n_ranks,
                            const std::string &piece_text);
      /** Counts the next output at @p time without writing (ranks other
       *  than 0). */
      void
      add_parallel_record(const double time);
      /** Appends the records (time [s], file) to a checkpoint. */
      void
      save_records(CheckpointWriter &out) const;
      /** The records save_records() wrote; InputError if corrupt. */
      static std::vector<std::pair<double, std::string>>
      load_records(CheckpointReader &in);
      /** The (time [s], file) records so far, for checkpoints. */
      const std::vector<std::pair<double, std::string>> &
      get_records() const
      {
        return records;
      }
      /** Continues a series from a checkpoint's @p saved records: the pvd
       *  is rewritten with exactly these (atomically) if @p write_pvd. */
      void
      restore(const std::vector<std::pair<double, std::string>> &saved,
              const bool write_pvd = true);

    private:
      /** `<base>_NNNNN` of the next output. */
      std::string
      next_stem() const;
      void
                                                  write_pvd() const;
      std::string                                 folder, base_name;
      std::vector<std::pair<double, std::string>> records;
    };

    /** The exploded mesh as a VTK UnstructuredGrid document in the
     *  @p encoding (binary documents hold raw bytes after their
     *  `<AppendedData encoding="raw">` mark; ascii and binary hold the
     *  same values). Extra nodal scalar fields
     *  (name, values per node) are added as point data. Only the triangles
     *  [@p first_element, @p end_element) and their nodes (one rank's
     *  piece); end_element = -1: to the last. With a @p polar_centre
     *  (x, y) [m] the cells also hold srr and stt, the stress in the polar
     *  frame about it (directions to the deformed cell's centroid). */
    std::string
    discrete_solution_vtu(
      const DiscreteModel &model,
      const VtuEncoding   &encoding,
      const std::vector<std::pair<std::string, const std::vector<double> *>>
                                  &extra_point_fields = {},
      const unsigned int           first_element      = 0,
      const unsigned int           end_element  = static_cast<unsigned int>(-1),
      const std::array<double, 2> *polar_centre = nullptr);

    /** Broken joints as line cells (one per joint, between the midpoints
     *  of its two faces' end nodes), of the joints [@p first_joint,
     *  @p end_joint) (one rank's piece); end_joint = -1: to the last.
     *  Without broken joints the piece holds one placeholder cell, a
     *  poly-vertex (VTK type 2) of no points with failure_mode 0 and
     *  break_time NaN, as meshio reads no vtu file without cells (it skips
     *  this cell type). @p encoding as in discrete_solution_vtu(). */
    std::string
    crack_vtu(const DiscreteModel &model,
              const VtuEncoding   &encoding,
              const unsigned int   first_joint = 0,
              const unsigned int   end_joint   = static_cast<unsigned int>(-1));

    /**
     * The current configuration as a gmsh 2.2 ASCII mesh (Output/Write
     * final mesh): one vertex per vertex of the original mesh at the mean
     * position of its copies (intact joints keep them together; a vertex
     * whose copies have separated along broken joints is averaged too, so
     * this suits meshes without broken joints, e.g. a settled heap of
     * intact blocks), triangles (3D: tetrahedra) with their material ids as
     * physical tags and boundary edges (3D: faces) with boundary id > 0 as
     * line (triangle) elements.
     */
    std::string
    deformed_mesh_msh(const DiscreteModel &model);
    class TemperatureSource;
    struct HeatBalance;

    /** summary.json's heat balance of a discrete temperature source: heat
     *  in per boundary id, from sources, across contacts, stored [J/m], the
     *  boundary rates of the last step [W/m] and the imbalance. */
    JsonObject
    heat_balance_summary(const TemperatureSource &source);
    /** The same of a @p balance and the boundary rates of the last step
     *  @p last_rates (per boundary id). */
    JsonObject
    heat_balance_summary(
      const HeatBalance                          &balance,
      const std::map<types::boundary_id, double> &last_rates);
  } // namespace discrete
} // namespace tmfdem

#endif
