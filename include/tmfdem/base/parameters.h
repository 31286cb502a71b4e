/**
 * @file
 * The parameter structs of tmfdem: one struct per subsection of the prm file,
 * each with `declare_parameters` and `parse_parameters` (deal.II step-8/18,
 * ASPECT and Lethe style). Every entry carries a pattern, its units and a
 * documentation string; `tmfdem --print-parameters` prints them all.
 *
 * The subsections here are those every model shares. Subsections that
 * belong to one part of the code (the discrete layer's `Discrete
 * mechanics`, `Discrete bodies`, `Discrete heat`) are declared where that
 * part lives and registered with register_parameter_section() (as ASPECT's
 * plugins declare theirs); they are reached with Parameters::get<T>(), and
 * base/ knows nothing of them.
 *
 * All quantities are SI; temperatures are in degrees Celsius.
 */
#ifndef tmfdem_base_parameters_h
#define tmfdem_base_parameters_h

#include <deal.II/base/numbers.h>
#include <deal.II/base/point.h>
#include <deal.II/base/tensor.h>
#include <deal.II/base/types.h>

#include <algorithm>
#include <array>
#include <bitset>
#include <cmath>
#include <map>
#include <memory>
#include <string>
#include <tmfdem/base/constitutive.h>
#include <typeindex>
#include <vector>

namespace dealii
{
  class ParameterHandler;
}

namespace tmfdem
{
  using namespace dealii;

  /** Subsection `Mesh`: where the triangulation comes from. */
  struct MeshParameters
  {
    /** How the mesh is made. */
    enum class Source
    {
      rectangle,
      annulus,
      disc,
      file,
      block_heap,
      box,
      ball,
      spherical_shell,
      cylinder,
      hollow_cylinder
    };
    /** Cell shape of generated meshes (files bring their own): in 3D
     *  triangles stand for tetrahedra, quadrilaterals for hexahedra. */
    enum class ElementType
    {
      triangles,
      quadrilaterals
    };

    /** Space dimension of the domain: 2 (plane, per unit thickness) or 3
     *  [-]. */
    unsigned int dimension    = 2;
    Source       source       = Source::rectangle;
    ElementType  element_type = ElementType::triangles;
    /** Target edge length of generated cells [m]. */
    double element_size = 0.05;
    /** Rectangle and box corners [m] (z = 0 in 2D). */
    Point<3> lower_left, upper_right;
    /** Centre of annulus, disc, ball and spherical shell [m] (z = 0 in
     *  2D). */
    Point<3> center;
    /** Annulus and spherical shell inner radius [m]. */
    double inner_radius = 0.03;
    /** Annulus, disc, ball and spherical shell outer radius [m]. */
    double outer_radius = 0.15;
    /** Cylinder and hollow cylinder: length along z, centred at Center
     *  [m]. */
    double length = 0.1;
    /** Annulus, spherical shell and hollow cylinder: the layers of cells
     *  lie at r = a + (b - a) xi^p, xi = k / n_layers; p = 1 uniform, p >
     *  1 thinner layers at the inner surface [-]. */
    double radial_grading = 1.;
    /** gmsh `.msh` file, resolved against the prm file's folder. */
    std::string file_name;
    /** Wall-clock limit of one gmsh run of a `.geo` file [s] (Gmsh time
     *  limit); gmsh is stopped past it. */
    double gmsh_time_limit = 300.;
    /** Area an imported mesh must cover [m^2]; 0: not checked. */
    double expected_area = 0.;
    /** Uniform refinements applied after generation or import. */
    unsigned int global_refinements = 0;
    /** Source = file: boundary ids whose edges lie on circles, with the
     *  circle's centre [m] (Circular boundaries): refinement puts new
     *  vertices of those edges on the circle. */
    std::vector<std::pair<types::boundary_id, Point<2>>> circular_boundaries;
    /** Material id of generated meshes. */
    types::material_id material_id = 0;

    /**
     * Subsection `Mesh/Block heap` (Source = block heap): a container
     * (base plate and two side walls, material id 2; boundary ids 1 base,
     * 2 walls, 0 blocks) holding convex blocks (material id 1) cut from a
     * seeded Voronoi tessellation of a region above the base.
     */
    struct BlockHeap
    {
      double       container_width  = 0.5;   ///< inner width W [m]
      double       container_height = 0.7;   ///< inner wall height H [m]
      double       wall_thickness   = 0.02;  ///< base and walls [m]
      unsigned int n_blocks         = 61;    ///< number of blocks [-]
      double       mean_size        = 0.07;  ///< sqrt(mean cell area) [m]
      double       gap              = 0.005; ///< between blocks/walls [m]
      double       drop_height      = 0.02;  ///< region above the base [m]
      unsigned int seed             = 1;     ///< random seed [-]
    };
    BlockHeap block_heap;

    static void
    declare_parameters(ParameterHandler &prm);
    void
    parse_parameters(ParameterHandler &prm, const std::string &input_folder);

    /** The first @p dim coordinates of @p p [m]. */
    template <int dim>
    static Point<dim>
    in_dimension(const Point<3> &p)
    {
      Point<dim> q;
      for (unsigned int d = 0; d < dim; ++d)
        q[d] = p[d];
      return q;
    }
  };

  /** Properties of one material, subsection `Materials/Material <id>`. */
  struct MaterialProperties
  {
    double      density               = 2500.; ///< [kg/m^3]
    double      youngs_modulus        = 50e9;  ///< [Pa]
    double      poisson_ratio         = 0.25;  ///< [-]
    double      thermal_conductivity  = 3.;    ///< isotropic k [W/(m K)]
    double      specific_heat         = 800.;  ///< [J/(kg K)]
    double      thermal_expansion     = 1e-5;  ///< [1/K]
    double      reference_temperature = 0.;    ///< stress-free temperature [C]
    double      tensile_strength      = 10e6;  ///< [Pa]
    double      cohesion              = 20e6;  ///< [Pa]
    double      friction_angle        = 30.; ///< internal friction angle [deg]
    double      fracture_energy_I  = 100.;   ///< Mode I fracture energy [J/m^2]
    double      fracture_energy_II = 500.; ///< Mode II fracture energy [J/m^2]
    std::string heat_source = "0"; ///< volumetric source f(x,y,t) [W/m^3]
    /** Initial temperature T(x, y) of this material's cells [C]; empty:
     *  `Initial conditions/Temperature` (Parameters::initial_temperature_of).
     */
    std::string initial_temperature;

    /**
     * Anisotropic conduction (paper Eqs. 8-9): true where `Thermal
     * conductivity along` and `across` are given. The conductivity is then
     * the tensor K = k1 d d^T + k2 p p^T with d = (cos theta, sin theta)
     * and p = (-sin theta, cos theta), and `Thermal conductivity` is not
     * used; otherwise K = k I with k = thermal_conductivity.
     */
    bool   anisotropic_conductivity = false;
    double conductivity_along       = 3.; ///< k1, along d [W/(m K)]
    double conductivity_across      = 3.; ///< k2, along p [W/(m K)]
    /** Angle theta of d from the x axis, counterclockwise [deg]. */
    double conductivity_direction = 0.;

    /** Conductivity tensor K [W/(m K)]: k I when isotropic. In 3D the
     *  direction d lies in the x-y plane and K = k1 d d^T + k2 (I - d d^T):
     *  k2 across d in every direction, z included. */
    template <int dim = 2>
    Tensor<2, dim>
    conductivity_tensor() const
    {
      Tensor<2, dim> K;
      if (!anisotropic_conductivity)
        {
          for (unsigned int d = 0; d < dim; ++d)
            K[d][d] = thermal_conductivity;
          return K;
        }
      const double theta = conductivity_direction * numbers::PI / 180.;
      const double c = std::cos(theta), s = std::sin(theta);
      K[0][0] = conductivity_along * c * c + conductivity_across * s * s;
      K[1][1] = conductivity_along * s * s + conductivity_across * c * c;
      K[0][1] = K[1][0] = (conductivity_along - conductivity_across) * c * s;
      if constexpr (dim == 3)
        K[2][2] = conductivity_across;
      return K;
    }

    /** Largest principal conductivity [W/(m K)] (k when isotropic). */
    double
    max_conductivity() const
    {
      return anisotropic_conductivity ?
               std::max(conductivity_along, conductivity_across) :
               thermal_conductivity;
    }

    /** Normal conductivity n.K.n for a unit vector @p n [W/(m K)] (k when
     *  isotropic, exactly). */
    template <int dim>
    double
    normal_conductivity(const Tensor<1, dim> &n) const
    {
      if (!anisotropic_conductivity)
        return thermal_conductivity;
      return n * (conductivity_tensor<dim>() * n);
    }

    /** Thermal diffusivity k / (rho c) [m^2/s]; with anisotropy the
     *  largest principal value k_max / (rho c). */
    double
    diffusivity() const
    {
      return max_conductivity() / (density * specific_heat);
    }
  };

  /**
   * Subsection `Materials`: one subsection `Material <id>` per material id
   * 0 ... max_materials-1. A cell with material id m takes `Material m`.
   */
  struct MaterialParameters
  {
    static constexpr unsigned int                 max_materials = 8;
    std::array<MaterialProperties, max_materials> materials;
    /** Which `Material <id>` subsections the input defines (the prm file
     *  names the subsection, or --set sets one of its entries); all when
     *  the parameters do not come from a file. */
    std::bitset<max_materials> given = std::bitset<max_materials>().set();

    static void
    declare_parameters(ParameterHandler &prm);
    void
    parse_parameters(ParameterHandler &prm);
    /** Properties of material @p id; InputError if @p id is not allowed. */
    const MaterialProperties &
    operator[](const types::material_id id) const;
    /** InputError naming material @p id and @p where it is used (e.g.
     *  "cells of the mesh", "Discrete bodies/Body 2") if the input does not
     *  define its subsection (given): it would run on built-in defaults. */
    void
    require_given(const types::material_id id, const std::string &where) const;
  };

  /** One thermal boundary condition on a set of boundary ids. */
  struct ThermalBoundaryCondition
  {
    enum class Type
    {
      dirichlet,
      neumann,
      robin
    };
    /** `Thermal boundary conditions/Condition <n>`, for messages. */
    std::string                     name;
    std::vector<types::boundary_id> boundary_ids;
    Type                            type  = Type::dirichlet;
    std::string temperature               = "0"; ///< Dirichlet T(x,y,t) [C]
    std::string heat_flux                 = "0"; ///< inward q(x,y,t) [W/m^2]
    std::string heat_transfer_coefficient = "0"; ///< h(x,y,t) [W/(m^2 K)]
    std::string ambient_temperature       = "0"; ///< T_inf(x,y,t) [C]
  };

  /**
   * Subsection `Thermal boundary conditions`: up to max_conditions
   * subsections `Condition <n>`; boundary ids not named anywhere are
   * insulated (zero flux).
   */
  struct ThermalBoundaryParameters
  {
    static constexpr unsigned int         max_conditions = 8;
    std::vector<ThermalBoundaryCondition> conditions;

    static void
    declare_parameters(ParameterHandler &prm);
    void
    parse_parameters(ParameterHandler &prm);
  };

  /** Subsection `Initial conditions`. */
  struct InitialConditionParameters
  {
    std::string temperature = "0"; ///< T(x,y,0) [C]
    /** The initial temperature field is the stress-free state (discrete
     * layer), in place of the materials' Reference temperature. */
    bool stress_free = false;

    static void
    declare_parameters(ParameterHandler &prm);
    void
    parse_parameters(ParameterHandler &prm);
  };

  /** Subsection `Time stepping`. */
  struct TimeSteppingParameters
  {
    enum class Mode
    {
      transient,
      steady
    };
    Mode        mode = Mode::transient;
    std::string method;     ///< name from theta_scheme_registry()
    double      theta = 1.; ///< implicitness of the chosen method
    /** Backward Euler half steps that start a Crank-Nicolson run. */
    unsigned int rannacher_steps = 4;
    double       start_time      = 0.;  ///< [s]
    double       end_time        = 1.;  ///< [s]
    double       time_step       = 0.1; ///< [s]

    static void
    declare_parameters(ParameterHandler &prm);
    void
    parse_parameters(ParameterHandler &prm);
  };

  /** Subsection `Adaptive refinement` (Kelly estimator). */
  struct AdaptivityParameters
  {
    bool enable = false;
    /** "fixed fraction" (of the estimated error) or "fixed number" (of
     *  cells) marking. */
    std::string  strategy            = "fixed fraction";
    unsigned int interval            = 5;    ///< steps between adaptations
    double       refine_fraction     = 0.3;  ///< of cells or of the error
    double       coarsen_fraction    = 0.03; ///< of cells or of the error
    unsigned int max_level           = 4;    ///< above the initial mesh
    unsigned int initial_refinements = 2;    ///< adaptive, on the initial field
    unsigned int steady_cycles       = 6;    ///< solve-estimate-refine cycles

    static void
    declare_parameters(ParameterHandler &prm);
    void
    parse_parameters(ParameterHandler &prm);
  };

  /** Subsection `Heat solver`: discretisation and linear algebra. */
  struct HeatSolverParameters
  {
    unsigned int degree             = 1;     ///< polynomial degree
    double       relative_tolerance = 1e-10; ///< CG stop criterion
    unsigned int max_iterations     = 2000;
    std::string  preconditioner     = "AMG";

    static void
    declare_parameters(ParameterHandler &prm);
    void
    parse_parameters(ParameterHandler &prm);
  };

  /**
   * Subsection `Mechanics`: the continuum thermoelastic model (and the 2D
   * idealisation, which the discrete layer shares).
   */
  struct MechanicsParameters
  {
    /**
     * Out-of-plane assumption of the 2D model: the one enum of the
     * constitutive core (base/constitutive.h), shared by both layers.
     */
    using Idealisation = constitutive::Idealisation;
    /** Small-strain linear or finite-strain (Eq. 44 on F_e) kinematics. */
    enum class StrainMeasure
    {
      small,
      finite
    };
    /** Where the temperature that loads the body comes from. */
    enum class TemperatureSource
    {
      function,
      heat_solver,
      discrete_heat
    };
    /** One point whose displacement components are held at zero. */
    struct PinnedPoint
    {
      Point<3>     location;              ///< a mesh vertex [m]; z = 0 in 2D
      bool         fix_x         = false; ///< u_x = 0
      bool         fix_y         = false; ///< u_y = 0
      bool         fix_z         = false; ///< u_z = 0 (3D)
      unsigned int n_coordinates = 2;     ///< as written: x, y or x, y, z
      std::string  text;                  ///< as written, for messages
    };

    Idealisation      idealisation       = Idealisation::plane_stress;
    StrainMeasure     strain_measure     = StrainMeasure::small;
    TemperatureSource temperature_source = TemperatureSource::function;
    /** T(x, y, t) for Temperature source = function [C]. */
    std::string              temperature      = "0";
    unsigned int             degree           = 2;     ///< polynomial degree
    double                   newton_tolerance = 1e-10; ///< relative residual
    unsigned int             newton_max_iterations = 25;
    bool                     line_search           = true;
    double                   linear_tolerance      = 1e-12; ///< relative, CG
    unsigned int             linear_max_iterations = 5000;
    bool                     polar_frame           = false;
    Point<2>                 polar_centre; ///< [m]
    std::vector<PinnedPoint> pinned_points;

    /** Temperature source = heat solver, transient: the stress is also
     *  solved every ... [s] (0: only at the output times). */
    double coupling_interval = 0.;

    static void
    declare_parameters(ParameterHandler &prm);
    void
    parse_parameters(ParameterHandler &prm);
    /** InputError unless Idealisation and Pinned points suit a model of
     *  @p dimension (2 or 3). */
    void
    check_dimension(const unsigned int dimension) const;
  };

  /** One mechanical boundary condition on a set of boundary ids. */
  struct MechanicalBoundaryCondition
  {
    enum class Type
    {
      fixed,
      roller_x,
      roller_y,
      roller_z,
      displacement,
      traction,
      velocity
    };
    /** `Mechanical boundary conditions/Condition <n>`, for messages. */
    std::string                     name;
    std::vector<types::boundary_id> boundary_ids;
    Type                            type = Type::fixed;
    /** u_x, u_y (, u_z) as functions of x, y (, z), t for Type =
     *  displacement [m]. */
    std::array<std::string, 3> displacement = {{"0", "0", "0"}};
    /** Nominal traction t_x, t_y (, t_z) (x, y (, z), t) for Type =
     *  traction [Pa]. */
    std::array<std::string, 3> traction = {{"0", "0", "0"}};
    /** v_x, v_y (, v_z) as functions of x, y (, z), t for Type = velocity
     *  (discrete layer) [m/s]. */
    std::array<std::string, 3> velocity = {{"0", "0", "0"}};
  };

  /**
   * Subsection `Mechanical boundary conditions`: up to max_conditions
   * subsections `Condition <n>`; boundary ids named by no condition are
   * traction free.
   */
  struct MechanicalBoundaryParameters
  {
    static constexpr unsigned int            max_conditions = 8;
    std::vector<MechanicalBoundaryCondition> conditions;

    static void
    declare_parameters(ParameterHandler &prm);
    void
    parse_parameters(ParameterHandler &prm);
    /** InputError for z components (roller z, Displacement z, Traction z)
     *  in a model of @p dimension 2. */
    void
    check_dimension(const unsigned int dimension) const;
  };

  /** Subsection `Output`. */
  struct OutputParameters
  {
    std::string         directory;        ///< folder for all outputs
    std::vector<double> times;            ///< output times [s]
    double              interval  = 0.;   ///< output every ... [s], 0: off
    bool                write_vtu = true; ///< solution.pvd and vtu files
    /** Vtu format: VTK XML binary if true (the discrete layer: appended
     *  raw data, every array one zlib block; the continuum layer: deal.II's
     *  zlib-compressed base64), plain ascii text otherwise. */
    bool binary_vtu = true;
    /** Vtu precision = single: the discrete layer's vtu files hold point
     *  coordinates and real point and cell data as Float32 (rounded from
     *  the doubles); false: Float64, the doubles themselves. */
    bool single_precision_vtu = true;
    /** Discrete mechanics: write the deformed mesh at the end as
     *  <directory>/final_mesh.msh (gmsh 2.2, ASCII). */
    bool   write_final_mesh  = false;
    double progress_interval = 2.; ///< stderr progress [s wall]

    static void
    declare_parameters(ParameterHandler &prm);
    void
    parse_parameters(ParameterHandler &prm, const std::string &prm_stem);
  };

  /** Subsection `Monitors`: named probe points and sampled lines. */
  struct MonitorParameters
  {
    /** A named point x, y (, z) [m]; z = 0 in 2D. */
    struct Probe
    {
      std::string name;
      Point<3>    location;
    };
    /** A named line of n equally spaced points from start to end [m]. */
    struct Line
    {
      std::string  name;
      Point<3>     start, end;
      unsigned int n_points = 2;
      /** Given with z coordinates ("x0, y0, z0, x1, y1, z1, n"). */
      bool with_z = false;
    };
    std::vector<Probe> probes;
    std::vector<Line>  lines;
    /** Discrete layer: a point outside the mesh (in a gap between blocks)
     *  samples the nearest element instead of being an input error. */
    bool snap_to_nearest = false;

    static void
    declare_parameters(ParameterHandler &prm);
    void
    parse_parameters(ParameterHandler &prm);
  };

  /** Subsection `Checkpoint`: periodic checkpoints for --resume. */
  struct CheckpointParameters
  {
    unsigned int interval_steps   = 0;  ///< every n steps, 0: off
    double       interval_minutes = 0.; ///< every m minutes of wall time
    std::string  directory; ///< folder; <Output/Directory>/checkpoints
    unsigned int keep = 2;  ///< newest checkpoints kept

    static void
    declare_parameters(ParameterHandler &prm);
    void
    parse_parameters(ParameterHandler &prm);
  };

  /** Subsection `Guards`: checks in the time loop that stop a failing run. */
  struct GuardParameters
  {
    /** Kinetic energy above this times the energy put in stops the run;
     *  0: off. */
    double kinetic_energy_factor = 100.;
    /** Check the time step against the stable step of the current
     *  geometry (discrete layer). */
    bool stability_check = true;

    static void
    declare_parameters(ParameterHandler &prm);
    void
    parse_parameters(ParameterHandler &prm);
  };

  /**
   * The initial temperature of the cells of one material id: the
   * expression and the prm entry it came from (for messages).
   */
  struct InitialTemperatureEntry
  {
    std::string expression; ///< T(x, y) at the start time [C]
    std::string entry;      ///< e.g. "Materials/Material 2/Initial temperature"
  };

  struct Parameters;

  /**
   * A prm subsection owned by a part of tmfdem above base/, held by
   * Parameters (see register_parameter_section()).
   */
  class ParameterSection
  {
  public:
    virtual ~ParameterSection() = default;
    /** A copy (Parameters are copied with all their sections). */
    virtual std::unique_ptr<ParameterSection>
    clone() const = 0;
    /** Reads the section from @p prm (declared by its declare function). */
    virtual void
    parse(ParameterHandler &prm) = 0;
    /** After all sections are parsed: checks across sections, and what the
     *  section contributes to the shared ones (may throw InputError). */
    virtual void
    complete(Parameters &parameters) const = 0;
  };

  /**
   * Holds a T with `static void declare_parameters(ParameterHandler &)`
   * and `void parse_parameters(ParameterHandler &)`; if T has
   * `void complete(Parameters &) const`, it is called after all sections
   * are parsed.
   */
  template <typename T>
  class ParameterSectionOf : public ParameterSection
  {
  public:
    T value;

    std::unique_ptr<ParameterSection>
    clone() const override
    {
      return std::make_unique<ParameterSectionOf<T>>(*this);
    }
    void
    parse(ParameterHandler &prm) override
    {
      value.parse_parameters(prm);
    }
    void
    complete(Parameters &parameters) const override
    {
      complete_if_defined(value, parameters, 0);
    }

  private:
    template <typename U>
    static auto
    complete_if_defined(const U &u, Parameters &parameters, int)
      -> decltype(u.complete(parameters), void())
    {
      u.complete(parameters);
    }
    template <typename U>
    static void
    complete_if_defined(const U &, Parameters &, long)
    {}
  };

  /** One registered section: its type, how to declare it, a default. */
  struct ParameterSectionType
  {
    std::type_index type;
    std::string     name; ///< the prm subsection, for messages
    void (*declare)(ParameterHandler &prm);
    std::unique_ptr<ParameterSection> (*create)();
  };

  /** All registered sections, in registration order. */
  const std::vector<ParameterSectionType> &
  registered_parameter_sections();

  /** Adds a section type (use register_parameter_section()). */
  bool
  add_parameter_section(ParameterSectionType type);

  /**
   * Registers T as a prm subsection named @p name: declared with the
   * others (Parameters::declare_parameters, --print-parameters), parsed
   * with them, reached with Parameters::get<T>(). Call it from a
   * namespace-scope initialiser in the file that defines T.
   */
  template <typename T>
  bool
  register_parameter_section(const std::string &name)
  {
    return add_parameter_section(
      {std::type_index(typeid(T)),
       name,
       &T::declare_parameters,
       []() -> std::unique_ptr<ParameterSection> {
         return std::make_unique<ParameterSectionOf<T>>();
       }});
  }

  /**
   * The registered sections of one Parameters, by type: every registered
   * section with its defaults on construction, deep copies on copy.
   */
  class ParameterSections
  {
  public:
    ParameterSections();
    ParameterSections(const ParameterSections &other);
    ParameterSections &
    operator=(const ParameterSections &other);
    ParameterSections(ParameterSections &&) noexcept = default;
    ParameterSections &
    operator=(ParameterSections &&) noexcept = default;
    ~ParameterSections();

    /** The section of @p type; throws std::logic_error if unregistered or
     *  removed by keep_only(). */
    ParameterSection &
    find(const std::type_index &type) const;

    /** Removes every section whose prm name is not in @p names. */
    void
    keep_only(const std::vector<std::string> &names);

  private:
    std::map<std::type_index, std::unique_ptr<ParameterSection>> map;
  };

  /**
   * An initial temperature that a registered section sets for the cells of
   * some material ids (e.g. a discrete body's), in precedence above the
   * material's and the global entry.
   */
  struct InitialTemperatureOverride
  {
    std::vector<types::material_id> material_ids;
    InitialTemperatureEntry         temperature;
  };

  /** All parameters of a run. */
  struct Parameters
  {
    std::string                  model;    ///< name from the model registry
    std::string                  prm_file; ///< file the parameters came from
    MeshParameters               mesh;
    MaterialParameters           materials;
    ThermalBoundaryParameters    thermal_boundary;
    InitialConditionParameters   initial;
    TimeSteppingParameters       time;
    AdaptivityParameters         adaptivity;
    HeatSolverParameters         heat_solver;
    OutputParameters             output;
    MonitorParameters            monitors;
    MechanicsParameters          mechanics;
    MechanicalBoundaryParameters mechanical_boundary;
    CheckpointParameters         checkpoint;
    GuardParameters              guards;
    /** Digest of the input that decides the results (every entry except
     *  Checkpoint, Output/Directory, Output/Progress interval and Discrete
     *  mechanics/Threads), hex; checkpoints of another input are refused. */
    std::string input_digest;
    /** Continue from the newest checkpoint (command line --resume). */
    bool resume = false;
    /** The entries the input sets to other than their default, as
     *  "Section/Entry = value" (read_parameters()). */
    std::vector<std::string> changed_entries;
    /** Those of changed_entries in subsections the model does not read
     *  (set by create_simulation(), reported as a warning). */
    std::vector<std::string> unread_entries;
    /** The top-level subsections this model reads (restrict_to_sections());
     *  empty: not restricted, all. */
    std::vector<std::string> sections_read;
    /** Initial temperatures set by registered sections (discrete bodies),
     *  filled when they complete; first match wins. */
    std::vector<InitialTemperatureOverride> initial_temperature_overrides;

    /** The registered section T (e.g. DiscreteMechanicsParameters). */
    template <typename T>
    const T &
    get() const
    {
      return static_cast<const ParameterSectionOf<T> &>(
               sections.find(std::type_index(typeid(T))))
        .value;
    }
    /** The same, to change (tests, overrides). */
    template <typename T>
    T &
    get()
    {
      return static_cast<ParameterSectionOf<T> &>(
               sections.find(std::type_index(typeid(T))))
        .value;
    }

    static void
    declare_parameters(ParameterHandler &prm);
    void
    parse_parameters(ParameterHandler &prm);

    /**
     * Initial temperature of the cells of material @p id, by precedence
     * override > material > global: the first of
     * initial_temperature_overrides naming @p id (`Discrete bodies/Body
     * <n>/Initial temperature` of the body whose Material ids contain
     * @p id, if set); else `Materials/Material <id>/Initial temperature`, if
     * set; else `Initial conditions/Temperature`. Ids without a Materials
     * subsection take the global entry.
     */
    InitialTemperatureEntry
    initial_temperature_of(const types::material_id id) const;

    /** True if some body or material sets its own initial temperature. */
    bool
    has_local_initial_temperature() const;

    /** The names of all top-level subsections: the shared ones and the
     *  registered ones. */
    static std::vector<std::string>
    section_names();

    /**
     * Keeps only the subsections named in @p names, as a model receives
     * its input (create_simulation()): every other shared subsection goes
     * back to its defaults, every other registered one is removed (get<T>()
     * of it throws std::logic_error naming it), and an initial temperature
     * override goes with the subsection of its entry. A name that is
     * no subsection is a programming error (std::logic_error).
     */
    void
    restrict_to_sections(const std::vector<std::string> &names);

    /** The registered sections, each with its defaults until parsed. */
    ParameterSections sections;
  };

  /**
   * The one-step theta methods offered by `Time stepping/Method`, by name:
   * backward Euler (theta = 1) and Crank-Nicolson (theta = 1/2).
   */
  const std::vector<std::pair<std::string, double>> &
  theta_scheme_registry();

} // namespace tmfdem

#endif
