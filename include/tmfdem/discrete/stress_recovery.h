/**
 * @file
 * Recovery of a continuous stress field from the constant stresses of the
 * discrete layer's triangles, for probes and lines (theory manual 5.10,
 * "Stress recovery at vertices"). Every vertex of the original mesh gets a
 * quadratic polynomial, the least-squares fit to the centroid stresses of
 * its patch widened by one ring of neighbours (superconvergent patch
 * recovery, Zienkiewicz-Zhu). At boundary vertices its value at the vertex
 * is what is known there instead of an extrapolation, namely the traction
 * on the boundary edges (sigma n = t: zero on free edges, the applied
 * traction on loaded ones) and the tangential stretch of the edges, which
 * gives the remaining component sigma_ss through the elastic law (Eq. 44)
 * with the edge's temperature; the fit then gives the slopes and
 * curvatures only. A sample in a triangle takes the blend
 * sum_k lambda_k P_k(x) of its three vertices' polynomials, each evaluated
 * at the sample point.
 */
#ifndef tmfdem_discrete_stress_recovery_h
#define tmfdem_discrete_stress_recovery_h

#include <array>
#include <tmfdem/discrete/discrete_model.h>
#include <tmfdem/discrete/solid.h>
#include <vector>

namespace tmfdem
{
  namespace discrete
  {
    /** What the recovery knows on one boundary edge (element edge 3e+k). */
    struct BoundaryEdgeKnowledge
    {
      enum class Kind : unsigned char
      {
        /** Nothing (supported, driven, in contact): the patch fit. */
        unknown,
        /** Full traction known (free edge: zero; traction condition). */
        traction,
        /** One Cartesian traction component known (rollers: the free
         *  direction carries no traction). */
        component
      };
      Kind kind = Kind::unknown;
      /** Nominal traction (force per reference length) x, y [Pa] for
       *  Kind::traction; for Kind::component the value of the known
       *  component is traction[component]. */
      double       traction[2] = {0., 0.};
      unsigned int component   = 0; ///< 0: x, 1: y (Kind::component)
      /** Thermal stretch s of F_T = s I at the edge (its mean
       *  temperature) [-]. */
      double thermal_stretch = 1.;
      /** Lame constants of the edge's element [Pa]. */
      LameConstants lame;
      /** The element's anisotropic correction Delta C, Mandel (11, 22,
       *  33, 12, 13, 23) [Pa] (joint_compliance.h); zero: isotropic. */
      std::array<double, 6> anisotropy = {{0., 0., 0., 0., 0., 0.}};
    };

    /**
     * The recovered stress field of @p model at the time it is built: one
     * quadratic polynomial per vertex of the original mesh (reference
     * configuration), evaluated by value(). @p boundary has one entry per
     * element edge (3 n_elements; only boundary edges are read; empty:
     * every boundary edge unknown).
     *
     * Fit: per vertex v, the patch P = the triangles with a node on v,
     * widened by one ring (the triangles with a node on any vertex of P),
     * and by further rings while it has fewer than 14 triangles (at most
     * three more); the polynomial minimises
     * sum_{e in P} |p(x_e) - sigma_e|^2 (x_e the reference centroid,
     * |.| the Frobenius norm). Where the patch cannot determine a
     * quadratic well (fewer or nearly degenerate centroids: a Cholesky
     * pivot below 1e-3 of the largest diagonal entry) a linear one, else
     * the mean.
     *
     * Boundary vertex with edges of known traction: the value at the
     * vertex is prescribed, and the fit gives the other coefficients. Each
     * such edge gives the full tensor at its midpoint (sigma_nn, sigma_ns
     * from the Cauchy traction, sigma_ss from the edge's stretch and Eq. 44
     * solved for the normal stretch); on a smooth boundary the vertex takes
     * the mean of the edges' (nn, ns, ss) components in the frame of the
     * mean normal, while at a corner (known edges whose normals differ by
     * more than 30 degrees) the tractions alone prescribe the components
     * they determine (all three at a corner of two free edges). Edges with
     * one known component (rollers) prescribe that component of
     * sigma n; conflicting prescriptions are met in the least-squares
     * sense. Components nothing prescribes come from the fit.
     */
    class RecoveredStress
    {
    public:
      /** Polynomial terms per component: 1, x, y, x^2, x y, y^2. */
      static constexpr unsigned int n_terms = 6;

      RecoveredStress(const DiscreteModel                      &model,
                      const std::vector<BoundaryEdgeKnowledge> &boundary);

      /**
       * Stress (xx, yy, xy) [Pa] at the reference point
       * sum_k lambda[k] X_k of element @p element (X_k its nodes'
       * reference positions, lambda its barycentric coordinates):
       * sum_k lambda[k] P_{v_k}(x), v_k the element's vertices.
       */
      Stress2
      value(const unsigned int element, const double *lambda) const;

      /** Stress (xx, yy, xy) [Pa] at vertex @p vertex: P_v(x_v). */
      Stress2
      vertex_value(const unsigned int vertex) const;

      /** Number of vertices of the original mesh. */
      unsigned int
      n_vertices() const
      {
        return static_cast<unsigned int>(vertex_x.size());
      }

      /** Polynomial degree used at @p vertex (2, or 1 / 0 where the patch
       *  cannot determine more). */
      unsigned int
      degree(const unsigned int vertex) const
      {
        return vertex_degree[vertex];
      }

    private:
      const DiscreteModel *model;
      /** Reference position [m] and inverse length scale [1/m] (1 / sqrt
       *  of the patch's mean area) of each vertex: the polynomials are in
       *  ((x - x_v) / h_v, (y - y_v) / h_v). */
      std::vector<double> vertex_x, vertex_y, inverse_scale;
      /** 3 n_terms per vertex: component c (xx, yy, xy), term i at
       *  [3 n_terms v + n_terms c + i] [Pa]. */
      std::vector<double>        coefficients;
      std::vector<unsigned char> vertex_degree;
    };

    /**
     * Stress (xx, yy, xy) at every vertex of the original mesh [Pa],
     * 3 per vertex index: RecoveredStress::vertex_value() of every vertex.
     */
    std::vector<double>
    recover_vertex_stress(const DiscreteModel                      &model,
                          const std::vector<BoundaryEdgeKnowledge> &boundary);

    /**
     * Full stress tensor (xx, yy, xy) [Pa] at the midpoint of a boundary
     * edge from current ends (x0, y0), (x1, y1), reference length
     * @p reference_length [m], its Cauchy traction (tx, ty) [Pa] (on the
     * outward normal of the current edge, the edge running
     * counter-clockwise around the body) and the elastic law of
     * @p knowledge. With an anisotropic correction in @p knowledge the
     * reference direction of the edge matters: (@p reference_dx,
     * @p reference_dy) is the reference edge vector [m]. Exposed for the
     * unit tests.
     */
    Stress2
    boundary_edge_stress(const double                 x0,
                         const double                 y0,
                         const double                 x1,
                         const double                 y1,
                         const double                 reference_length,
                         const double                 tx,
                         const double                 ty,
                         const BoundaryEdgeKnowledge &knowledge,
                         const double                 reference_dx = 0.,
                         const double                 reference_dy = 0.);
  } // namespace discrete
} // namespace tmfdem

#endif
