/**
 * @file
 * Recovery of a continuous (vertex) stress field from the constant stresses
 * of the discrete layer's triangles, for probes and lines (theory manual,
 * "Stress recovery at vertices"). Interior vertices: the value at the vertex
 * of a linear least-squares fit to the triangles' centroid stresses over the
 * vertex's patch. Boundary vertices: what is known there instead of a
 * one-sided extrapolation, namely the traction on the boundary edges
 * (sigma n = t: zero on free edges, the applied traction on loaded ones) and
 * the tangential stretch of the edges, which gives the remaining component
 * sigma_ss through the elastic law (Eq. 44) with the edge's temperature.
 */
#ifndef tmfdem_discrete_stress_recovery_h
#define tmfdem_discrete_stress_recovery_h

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
    };

    /**
     * Stress (xx, yy, xy) at every vertex of the original mesh [Pa],
     * 3 per vertex index, from @p model's element stresses (model.stress)
     * and the current and reference node positions. @p boundary has one
     * entry per element edge (3 n_elements; only boundary edges are read;
     * empty: every boundary edge unknown).
     *
     * Interior vertex, or boundary vertex with only unknown edges: the
     * value at the vertex of the least-squares plane through the centroid
     * stresses of its patch (widened by the neighbours' patches where it
     * has fewer than six triangles). Boundary vertex with edges of known
     * traction: each such edge gives the full tensor at its midpoint
     * (sigma_nn, sigma_ns from the Cauchy traction, sigma_ss from the
     * edge's stretch and Eq. 44 solved for the normal stretch); on a smooth
     * boundary the vertex takes the mean of the edges' (nn, ns, ss)
     * components in the frame of the mean normal, while at a corner (known
     * edges whose normals differ by more than 30 degrees) the tractions alone
     * give sigma by least squares. Edges with one known component then project
     * the value onto sigma n . e_i = t_i.
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
     * @p knowledge. Exposed for the unit tests.
     */
    Stress2
    boundary_edge_stress(const double                 x0,
                         const double                 y0,
                         const double                 x1,
                         const double                 y1,
                         const double                 reference_length,
                         const double                 tx,
                         const double                 ty,
                         const BoundaryEdgeKnowledge &knowledge);
  } // namespace discrete
} // namespace tmfdem

#endif
