/**
 * @file
 * Contact heat transfer between two triangles of the discrete layer (paper
 * Sec. 3.4, Eqs. 28-36, with the driving term of
 * `shared/design/physics-notes.md`, section "Heat"; theory manual "Contact
 * heat over the overlap").
 *
 * For a contact pair (contactor c, target t) the kernel
 *  1. clips c by the three half-planes of t (Sutherland-Hodgman) to get the
 *     overlap polygon S (at most 6 vertices), its area, its centroid G and
 *     its contact length L_c, the chord of the interpenetration (see
 *     OverlapPolygon);
 *  2. evaluates the area coordinates of G in both triangles (Eqs. 34-35);
 *  3. transfers Q = h_c L_c (T_t(G) - T_c(G)) [W/m, per unit thickness]
 *     from t to c and distributes +Q to c's nodes and -Q to t's nodes with
 *     those area coordinates (Eq. 36). The six nodal heats sum to exactly
 *     0.0 in floating point, in any order of summation (see
 *     split_heat_exactly()).
 *
 * The paper's own driving term (Eqs. 29-33: element temperature gradients
 * averaged over the overlap, times h_c) is offered as the named alternative
 * paper_literal_contact_heat(), selected by `Discrete heat/Contact heat
 * model = paper literal` (ContactHeatModel); it transfers nothing between
 * two isothermal bodies at different temperatures and so fails the simplest
 * contact benchmark.
 *
 * Everything here is header-only, inline and allocation-free.
 */
#ifndef tmfdem_discrete_contact_heat_h
#define tmfdem_discrete_contact_heat_h

#include <algorithm>
#include <array>
#include <cmath>
#include <string>
#include <tmfdem/discrete/triangle_overlap.h>
#include <utility>

namespace tmfdem
{
  namespace discrete
  {
    /**
     * Driving term of the contact heat, `Discrete heat/Contact heat model`.
     * Parsed once from the prm name (contact_heat_model_registry()); the
     * heat loop switches on the enum.
     */
    enum class ContactHeatModel : unsigned char
    {
      /** Q = h_c L_c (T_t(G) - T_c(G)), contact_heat_from_overlap() (the
       * default) */
      temperature_difference,
      /** the paper's Eqs. 29-33, paper_literal_contact_heat() */
      paper_literal
    };

    /** The prm names of the contact heat models, in the order of the
     * `Contact heat model` selection (the first is the default). */
    inline const std::array<std::pair<const char *, ContactHeatModel>, 2> &
    contact_heat_model_registry()
    {
      static const std::array<std::pair<const char *, ContactHeatModel>, 2>
        registry{
          {{"temperature difference", ContactHeatModel::temperature_difference},
           {"paper literal", ContactHeatModel::paper_literal}}};
      return registry;
    }

    /** The prm name of @p model (for summary.json and messages). */
    inline std::string
    contact_heat_model_name(const ContactHeatModel model)
    {
      for (const auto &[name, entry] : contact_heat_model_registry())
        if (entry == model)
          return name;
      return "unknown";
    }

    // the overlap polygon of two triangles: triangle_overlap.h

    /**
     * Area coordinates [-] of the point (@p px, @p py) [m] in the triangle
     * with counter-clockwise nodes (@p x, @p y) [m] (paper Eq. 35:
     * N_A = S_BCG / S_ABC, ...). Round-off negatives (the point lies in the
     * triangle, e.g. the centroid of an overlap) are clamped to 0 and the
     * coordinates renormalised to sum to 1 (Eq. 34). The triangle must have
     * positive area.
     */
    inline std::array<double, 3>
    area_coordinates(const double *x,
                     const double *y,
                     const double  px,
                     const double  py)
    {
      std::array<double, 3> coordinates;
      for (unsigned int k = 0; k < 3; ++k)
        {
          const unsigned int k1 = (k + 1) % 3, k2 = (k + 2) % 3;
          coordinates[k] =
            std::max(twice_signed_area(x[k1], y[k1], x[k2], y[k2], px, py), 0.);
        }
      const double sum = coordinates[0] + coordinates[1] + coordinates[2];
      for (double &c : coordinates)
        c /= sum;
      return coordinates;
    }

    /**
     * Temperature [K] interpolated with the @p n_nodes barycentric (area or
     * volume) coordinates @p N [-] from the nodal temperatures @p T [K],
     * written as T_0 + sum_k N_k (T_k - T_0) so that an isothermal simplex
     * returns its temperature exactly.
     */
    template <std::size_t n_nodes>
    inline double
    interpolate_temperature(const double                      *T,
                            const std::array<double, n_nodes> &N)
    {
      double value = T[0];
      for (std::size_t k = 1; k < n_nodes; ++k)
        value += N[k] * (T[k] - T[0]);
      return value;
    }

    /**
     * Heat exchanged by one contact pair of simplices with @p n_nodes nodes
     * each (3: triangles, heats per unit thickness [W/m]; 4: tetrahedra,
     * heats [W]) and its linearisation. Nodal heats are positive into the
     * node. With T = (T_c0, ..., T_t0, ...) and w = (N_c, -N_t), the nodal
     * heats are q = -(h_c L_c) w w^T T (h_c A_c in 3D), so the conductance
     * matrix K = h_c L_c w w^T (symmetric positive semi-definite, rows
     * summing to zero) enters an implicit scheme's matrix with a plus sign:
     * C dT/dt + (... + K) T = ...
     */
    template <std::size_t n_nodes>
    struct ContactHeatTransferT
    {
      /** Pair conductance h_c L_c [W/(m K)] (2D) or h_c A_c [W/K] (3D); 0
       * without overlap. */
      double conductance = 0.;

      /** Contactor's and target's temperatures at G [K]. */
      double contactor_temperature = 0., target_temperature = 0.;

      /** Q = conductance (T_t(G) - T_c(G)): heat flowing from the target
       * into the contactor [W/m] (2D) or [W] (3D). */
      double heat_flow = 0.;

      /** Barycentric coordinates of G in the contactor and in the target
       * [-]. */
      std::array<double, n_nodes> contactor_shape{}, target_shape{};

      /** Nodal heats into the contactor's and the target's nodes [W/m] or
       * [W]; all of them sum to exactly 0.0. */
      std::array<double, n_nodes> contactor_nodal_heat{}, target_nodal_heat{};

      /** Paper literal model only (zero otherwise): dQ/dT_j of the heat
       * flow into the contactor, Q = sum_j flow_weights[j] T_j, j over the
       * contactor's nodes then the target's. Its Jacobian (not a
       * conductance: neither symmetric nor definite) bounds the explicit
       * step, see DiscreteHeat::stable_time_step(). */
      std::array<double, 2 * n_nodes> flow_weights{};

      /**
       * d(nodal heat i)/d(nodal temperature j), i and j running over the
       * contactor's nodes then the target's: -K, with K = conductance w
       * w^T, w = (N_c, -N_t).
       */
      std::array<std::array<double, 2 * n_nodes>, 2 * n_nodes>
      heat_jacobian() const
      {
        std::array<double, 2 * n_nodes> w;
        for (std::size_t k = 0; k < n_nodes; ++k)
          {
            w[k]           = contactor_shape[k];
            w[n_nodes + k] = -target_shape[k];
          }
        std::array<std::array<double, 2 * n_nodes>, 2 * n_nodes> jacobian;
        for (std::size_t i = 0; i < 2 * n_nodes; ++i)
          for (std::size_t j = 0; j < 2 * n_nodes; ++j)
            jacobian[i][j] = -conductance * (w[i] * w[j]);
        return jacobian;
      }
    };

    /** The contact heat of a pair of triangles (per unit thickness). */
    using ContactHeatTransfer = ContactHeatTransferT<3>;

    /**
     * Splits the pair's heat @p heat_flow into +Q N_c to the contactor's
     * nodes and -Q N_t to the target's nodes (Eq. 36) so that the 2
     * @p n_nodes nodal heats sum to exactly 0.0 in any order of summation:
     * every share is rounded to a multiple of the power of two
     * u = 2^(e - 50), |Q| < 2^e, and the last target share is the exact
     * remainder. All partial sums are then multiples of u below 2^53 u and
     * are computed without rounding. Each share is off Q N by at most
     * 2^-50 |Q| (about 1e-15 relative).
     */
    template <std::size_t n_nodes>
    inline void
    split_heat_exactly(const double                       heat_flow,
                       const std::array<double, n_nodes> &contactor_shape,
                       const std::array<double, n_nodes> &target_shape,
                       std::array<double, n_nodes>       &contactor_nodal_heat,
                       std::array<double, n_nodes>       &target_nodal_heat)
    {
      int exponent = 0;
      std::frexp(heat_flow, &exponent);
      if (heat_flow == 0. || !std::isfinite(heat_flow) || exponent < -960)
        {
          // nothing to transfer (or non-finite input: let it propagate)
          const double q = std::isfinite(heat_flow) ? 0. : heat_flow;
          contactor_nodal_heat.fill(q);
          target_nodal_heat.fill(-q);
          return;
        }
      const double quantum          = std::ldexp(1., exponent - 50);
      auto         round_to_quantum = [quantum](const double value) {
        return std::nearbyint(value / quantum) * quantum;
      };
      double sum = 0.;
      for (std::size_t k = 0; k < n_nodes; ++k)
        {
          contactor_nodal_heat[k] =
            round_to_quantum(heat_flow * contactor_shape[k]);
          sum += contactor_nodal_heat[k];
        }
      for (std::size_t k = 0; k + 1 < n_nodes; ++k)
        {
          target_nodal_heat[k] = -round_to_quantum(heat_flow * target_shape[k]);
          sum += target_nodal_heat[k];
        }
      target_nodal_heat[n_nodes - 1] = -sum;
    }

    /**
     * The default model's heat of a pair whose shapes and temperatures at G
     * are in @p transfer: its @p conductance [W/(m K)] in 2D, [W/K] in 3D,
     * Q = conductance (T_t(G) - T_c(G)) and its exact split to the nodes.
     */
    template <std::size_t n_nodes>
    inline void
    temperature_difference_heat(const double                   conductance,
                                ContactHeatTransferT<n_nodes> &transfer)
    {
      transfer.conductance = conductance;
      transfer.heat_flow   = conductance * (transfer.target_temperature -
                                          transfer.contactor_temperature);
      split_heat_exactly(transfer.heat_flow,
                         transfer.contactor_shape,
                         transfer.target_shape,
                         transfer.contactor_nodal_heat,
                         transfer.target_nodal_heat);
    }

    /**
     * Contact heat of a pair whose overlap (@p overlap, from
     * triangle_overlap(), contactor first) is known: contactor nodes
     * (@p cx, @p cy) [m] at temperatures @p Tc [K], target nodes
     * (@p tx, @p ty) [m] at @p Tt [K], contact conductance @p h_c
     * [W/(m^2 K)]. Fills @p transfer with Q = h_c L_c (T_t(G) - T_c(G))
     * [W/m], its distribution to the six nodes and the linearisation data.
     * An empty overlap gives a zero transfer.
     */
    inline void
    contact_heat_from_overlap(const OverlapPolygon &overlap,
                              const double         *cx,
                              const double         *cy,
                              const double         *Tc,
                              const double         *tx,
                              const double         *ty,
                              const double         *Tt,
                              const double          h_c,
                              ContactHeatTransfer  &transfer)
    {
      transfer = ContactHeatTransfer();
      if (overlap.n_vertices == 0 || !(overlap.area > 0.))
        return;
      transfer.contactor_shape =
        area_coordinates(cx, cy, overlap.centroid_x, overlap.centroid_y);
      transfer.target_shape =
        area_coordinates(tx, ty, overlap.centroid_x, overlap.centroid_y);
      transfer.contactor_temperature =
        interpolate_temperature(Tc, transfer.contactor_shape);
      transfer.target_temperature =
        interpolate_temperature(Tt, transfer.target_shape);
      temperature_difference_heat(h_c * overlap.contact_length, transfer);
    }

    /**
     * Contact heat between contactor (@p cx, @p cy) [m] at nodal
     * temperatures @p Tc [K] and target (@p tx, @p ty) [m] at @p Tt [K],
     * both counter-clockwise, with contact conductance @p h_c [W/(m^2 K)]:
     * the driving term of physics-notes.md,
     *   Q = h_c L_c (T_t(G) - T_c(G)) [W/m],
     * distributed with the area coordinates of the overlap's centroid G
     * (Eqs. 34-36). Fills @p overlap and @p transfer; returns false (zero
     * transfer) if the triangles do not overlap with positive area.
     */
    inline bool
    contact_heat(const double        *cx,
                 const double        *cy,
                 const double        *Tc,
                 const double        *tx,
                 const double        *ty,
                 const double        *Tt,
                 const double         h_c,
                 OverlapPolygon      &overlap,
                 ContactHeatTransfer &transfer)
    {
      const bool overlapping = triangle_overlap(cx, cy, tx, ty, overlap);
      contact_heat_from_overlap(overlap, cx, cy, Tc, tx, ty, Tt, h_c, transfer);
      return overlapping;
    }

    /**
     * Temperature gradient [K/m] of the P1 field @p T [K] on the triangle
     * (@p x, @p y) [m] (constant over the triangle, so also its average over
     * any overlap, paper Eqs. 30-31).
     */
    inline std::array<double, 2>
    temperature_gradient(const double *x, const double *y, const double *T)
    {
      const double twice_area =
        twice_signed_area(x[0], y[0], x[1], y[1], x[2], y[2]);
      // differences, so that an isothermal triangle has exactly zero gradient
      const double dT1 = T[1] - T[0], dT2 = T[2] - T[0];
      return {{(dT1 * (y[2] - y[0]) - dT2 * (y[1] - y[0])) / twice_area,
               (dT2 * (x[1] - x[0]) - dT1 * (x[2] - x[0])) / twice_area}};
    }

    /**
     * NAMED ALTERNATIVE, NOT THE DEFAULT (`Contact heat model = paper
     * literal`): the paper's driving term (Eqs. 29-33), for users
     * reproducing the paper. Our reading of it, as printed:
     *  - Eq. 29 with k_ij = 1: the "flux" of each element is q = -grad T
     *    [K/m], its P1 temperature gradient (with the conductivity, Eq. 33
     *    would be in W^2/(m^2 K), not a heat; with k_ij = 1 it is a heat
     *    per unit thickness [W/m]);
     *  - Eqs. 30-31: averaged over the overlap, a P1 gradient is the element
     *    gradient itself;
     *  - Eq. 32: "the outward normal vectors" of the contactor and the
     *    target are n_c = unit vector from the contactor's centroid to the
     *    target's and n_t = -n_c; the net flow from c to t superposes what c
     *    sends towards t, q_c . n_c, and, with the opposite sign, what t
     *    sends towards c, q_t . n_t:
     *      q = q_c . n_c - q_t . n_t = -(grad T_c + grad T_t) . n_c;
     *  - Eq. 33: p = h_c A q over the overlap area A, i.e. the heat flow
     *    into the contactor
     *      Q = h_c A (grad T_c + grad T_t) . n_c   [W/m],
     *    distributed like contact_heat() (Eq. 36, area coordinates of the
     *    overlap's centroid G).
     * Q is odd under swapping contactor and target (n_c changes sign), so
     * the result does not depend on which triangle of a pair the contact
     * search calls the contactor. (Reading Eq. 32 as a plain sum
     * q_c . n_c + q_t . n_t instead gives a Q that is even under the swap:
     * the direction of the flow would follow the element numbering.)
     *
     * Why it is not the default: Q depends only on temperature GRADIENTS.
     * Two isothermal bodies at T1 != T2 pressed together have zero
     * gradients and exchange nothing, forever; the simplest contact
     * benchmark (two small isothermal bodies equilibrating as exp(-t/tau))
     * fails, and so does the steady series-resistance benchmark (no
     * temperature jump q / h_c across the contact can drive a flux). Its
     * size also scales with the overlap AREA, i.e. with the
     * penalty-dependent interpenetration, not with the contact length, and
     * not with the conductivities of the two bodies.
     * The default form Q = h_c L_c (T_t(G) - T_c(G)) is driven by the
     * temperature jump.
     *
     * Fills @p overlap and @p transfer (conductance 0: not a
     * conductance-type law; flow_weights: dQ/dT); returns false (zero
     * transfer) if the triangles do not overlap with positive area.
     */
    inline bool
    paper_literal_contact_heat(const double        *cx,
                               const double        *cy,
                               const double        *Tc,
                               const double        *tx,
                               const double        *ty,
                               const double        *Tt,
                               const double         h_c,
                               OverlapPolygon      &overlap,
                               ContactHeatTransfer &transfer)
    {
      transfer = ContactHeatTransfer();
      if (!triangle_overlap(cx, cy, tx, ty, overlap))
        return false;
      const std::array<double, 2> gradient_c = temperature_gradient(cx, cy, Tc);
      const std::array<double, 2> gradient_t = temperature_gradient(tx, ty, Tt);
      double       nx   = (tx[0] + tx[1] + tx[2] - cx[0] - cx[1] - cx[2]) / 3.;
      double       ny   = (ty[0] + ty[1] + ty[2] - cy[0] - cy[1] - cy[2]) / 3.;
      const double norm = std::hypot(nx, ny);
      if (norm > 0.)
        {
          nx /= norm;
          ny /= norm;
        }
      transfer.contactor_shape =
        area_coordinates(cx, cy, overlap.centroid_x, overlap.centroid_y);
      transfer.target_shape =
        area_coordinates(tx, ty, overlap.centroid_x, overlap.centroid_y);
      transfer.contactor_temperature =
        interpolate_temperature(Tc, transfer.contactor_shape);
      transfer.target_temperature =
        interpolate_temperature(Tt, transfer.target_shape);
      transfer.conductance = 0.; // not a conductance-type law
      const double factor  = h_c * overlap.area;
      transfer.heat_flow   = factor * ((gradient_c[0] + gradient_t[0]) * nx +
                                     (gradient_c[1] + gradient_t[1]) * ny);
      // dQ/dT_j = h_c A grad N_j . n, grad N_j = (y_k - y_l, x_l - x_k)/2A
      const double *xs[2] = {cx, tx}, *ys[2] = {cy, ty};
      for (unsigned int side = 0; side < 2; ++side)
        {
          const double *x = xs[side], *y = ys[side];
          const double  twice_area =
            twice_signed_area(x[0], y[0], x[1], y[1], x[2], y[2]);
          for (unsigned int j = 0; j < 3; ++j)
            {
              const unsigned int k = (j + 1) % 3, l = (j + 2) % 3;
              transfer.flow_weights[3 * side + j] =
                factor * ((y[k] - y[l]) * nx + (x[l] - x[k]) * ny) / twice_area;
            }
        }
      split_heat_exactly(transfer.heat_flow,
                         transfer.contactor_shape,
                         transfer.target_shape,
                         transfer.contactor_nodal_heat,
                         transfer.target_nodal_heat);
      return true;
    }

    /**
     * Contact heat of a pair with the driving term @p model (see
     * ContactHeatModel): contact_heat() or paper_literal_contact_heat(),
     * same arguments and results.
     */
    inline bool
    contact_heat(const ContactHeatModel model,
                 const double          *cx,
                 const double          *cy,
                 const double          *Tc,
                 const double          *tx,
                 const double          *ty,
                 const double          *Tt,
                 const double           h_c,
                 OverlapPolygon        &overlap,
                 ContactHeatTransfer   &transfer)
    {
      switch (model)
        {
          case ContactHeatModel::paper_literal:
            return paper_literal_contact_heat(cx,
                                              cy,
                                              Tc,
                                              tx,
                                              ty,
                                              Tt,
                                              h_c,
                                              overlap,
                                              transfer);
          case ContactHeatModel::temperature_difference:
          default:
            return contact_heat(cx, cy, Tc, tx, ty, Tt, h_c, overlap, transfer);
        }
    }
  } // namespace discrete
} // namespace tmfdem

#endif
