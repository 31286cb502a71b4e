/**
 * @file
 * One joint's forces in one explicit step, written once for the
 * joint-by-joint loop (Number = double) and for the vector batches (Number
 * = a GCC vector of doubles, one joint per lane; source/discrete/joints.cc):
 * the frame of the joint's mean edge from its four nodes, the cohesive
 * tractions at the two Gauss points (cohesive_law.h), the exact compression
 * of a joint closed at one end only (joint_closed_part()) and the forces on
 * the node pairs. Both instantiations perform the same operations in the
 * same order, so a joint in a batch gets bitwise the forces of the
 * joint-by-joint loop (joints.cc is compiled without FMA contraction).
 */
#ifndef tmfdem_discrete_joint_kernel_h
#define tmfdem_discrete_joint_kernel_h

#include <tmfdem/discrete/cohesive_law.h>
#include <tmfdem/discrete/vector_instructions.h>

namespace tmfdem
{
  namespace discrete
  {
    /** Gauss points of a joint, parameter u in [0, 1] along the edge. */
    constexpr double joint_gauss_points[2] = {0.21132486540518713,
                                              0.78867513459481287};

    /**
     * The frame of a joint at the current state: the gaps d0, d1 of its two
     * node pairs (B - A) [m], the length L of the mean edge [m], its
     * reciprocal [1/m] and the edge's unit tangent t and normal n (outward
     * of element A).
     */
    template <typename Number>
    struct JointFrameT
    {
      Number d0x, d0y, d1x, d1y;
      Number L, inverse_L, tx, ty, nx, ny;
    };

    /**
     * The frame of a joint with nodes a0, a1 (element A, along its edge)
     * and b0, b1 (element B, b0 facing a0) at @p x, @p y [m] (in the order
     * a0, a1, b0, b1; DiscreteModel::joint_nodes).
     */
    template <typename Number>
    __attribute__((always_inline)) inline JointFrameT<Number>
    joint_frame(const Number *x, const Number *y)
    {
      JointFrameT<Number> g;
      g.d0x           = x[2] - x[0];
      g.d0y           = y[2] - y[0];
      g.d1x           = x[3] - x[1];
      g.d1y           = y[3] - y[1];
      const Number ex = 0.5 * (x[1] + x[3] - x[0] - x[2]);
      const Number ey = 0.5 * (y[1] + y[3] - y[0] - y[2]);
      g.L             = lane_sqrt(ex * ex + ey * ey);
      g.inverse_L     = 1. / g.L;
      g.tx            = ex * g.inverse_L;
      g.ty            = ey * g.inverse_L;
      g.nx            = g.ty;
      g.ny            = -g.tx;
      return g;
    }

    /**
     * The constants of the joints of a batch, one per lane, under the
     * member names of JointConstants (what cohesive_traction() reads).
     */
    template <typename Number>
    struct JointConstantLanes
    {
      Number normal_stiffness, tangential_stiffness, tensile_strength, cohesion,
        friction_tangent, softening_width_I, softening_width_II,
        inverse_opening_peak, inverse_slip_peak_open;

      /** Lane l holds @p first [l] (the constants of consecutive
       *  joints). */
      explicit JointConstantLanes(const JointConstants *first)
      {
        for (unsigned int l = 0; l < sizeof(Number) / sizeof(double); ++l)
          {
            const JointConstants &k   = first[l];
            normal_stiffness[l]       = k.normal_stiffness;
            tangential_stiffness[l]   = k.tangential_stiffness;
            tensile_strength[l]       = k.tensile_strength;
            cohesion[l]               = k.cohesion;
            friction_tangent[l]       = k.friction_tangent;
            softening_width_I[l]      = k.softening_width_I;
            softening_width_II[l]     = k.softening_width_II;
            inverse_opening_peak[l]   = k.inverse_opening_peak;
            inverse_slip_peak_open[l] = k.inverse_slip_peak_open;
          }
      }
    };

    /**
     * What joint_response() computes for one joint (or one per lane). The
     * node forces [N/m] are
     *
     *   a0: a0 + frame,  b0: -a0 + frame,  a1: a1 - frame,  b1: -a1 - frame.
     */
    template <typename Number>
    struct JointResponse
    {
      /** The tractions' forces on a0 (start of the edge) and a1 (its end)
       *  [N/m], pulling A toward B; B's nodes take them with the opposite
       *  sign. */
      Number a0x, a0y, a1x, a1y;
      /** The force of the turning frame [N/m]: the tractions' work on the
       *  change of the normal and tangent with the nodes, along n; it
       *  balances the moment of the gaps (d x F), so that the joint exerts
       *  no net torque (joint_response()). */
      Number frame_x, frame_y;
      /** The larger of the Gauss points' normalised softening opening and
       *  slip (cohesive_traction()) [-]. */
      Number d_opening, d_slip;
      /** Past a peak at a Gauss point (bool, or a lane mask). */
      decltype(Number() > 1.) beyond_peak;
    };

    /**
     * The forces of a joint with frame @p g, constants @p k (JointConstants,
     * or JointConstantLanes for a batch) and the damage of its two Gauss
     * points @p damage (updated in place): the cohesive tractions at the
     * Gauss points, weighted L / 2, distributed to the node pairs by the
     * linear shape functions; a joint closed at one end and open at the
     * other takes its compression exactly over the closed part
     * (joint_closed_part()) instead of at the Gauss points. With
     * @p with_softening = false the rising branch only (cohesive_traction()).
     *
     * The forces are the tractions' generalised forces on the Gauss points'
     * opening o = d.n and slip s = d.t, whose normal and tangent turn with
     * the mean edge e (de/dx = +-1/2): do/de = -s n / L, ds/de = o n / L.
     * Those derivatives give the frame force (1/2) M n on a0 and b0 and
     * minus it on a1 and b1, M = sum_q w_q (T_s o - T_n s) / L =
     * (d0 x F0 + d1 x F1) / L. Without it a joint whose gap is not along
     * its traction (sheared, or open and damaged) exerts the torque
     * -(d0 x F0 + d1 x F1) on the body; with it, o and s being invariant
     * under rigid motions, the forces keep momentum and angular momentum.
     */
    template <SofteningLaw law,
              bool         with_softening = true,
              typename Number,
              typename Constants>
    __attribute__((always_inline)) inline void
    joint_response(const JointFrameT<Number> &g,
                   const Constants           &k,
                   Number                    *damage,
                   JointResponse<Number>     &f)
    {
      const Number zero{};
      f.a0x = f.a0y = f.a1x = f.a1y = zero;
      f.frame_x = f.frame_y = zero;
      f.d_opening = f.d_slip     = zero;
      f.beyond_peak              = decltype(f.beyond_peak){};
      const Number o_start       = g.d0x * g.nx + g.d0y * g.ny;
      const Number o_end         = g.d1x * g.nx + g.d1y * g.ny;
      const auto   partly_closed = (o_start < 0.) != (o_end < 0.);
      for (unsigned int q = 0; q < 2; ++q)
        {
          const double                 u  = joint_gauss_points[q];
          const Number                 dx = (1. - u) * g.d0x + u * g.d1x;
          const Number                 dy = (1. - u) * g.d0y + u * g.d1y;
          const Number                 o  = dx * g.nx + dy * g.ny;
          const Number                 s  = dx * g.tx + dy * g.ty;
          const JointTractionT<Number> tr =
            cohesive_traction<law, with_softening>(o, s, k, damage[q]);
          f.d_opening = lane_max(f.d_opening, tr.d_opening);
          f.d_slip    = lane_max(f.d_slip, tr.d_slip);
          f.beyond_peak |= tr.beyond_peak;
          // traction on A (pulls A toward B), weight L/2; the closed part
          // of a partly closed joint below
          const Number w      = 0.5 * g.L;
          const Number normal = (partly_closed & (o < 0.)) ? zero : tr.normal;
          const Number px     = w * (normal * g.nx + tr.shear * g.tx);
          const Number py     = w * (normal * g.ny + tr.shear * g.ty);
          f.a0x += (1. - u) * px;
          f.a0y += (1. - u) * py;
          f.a1x += u * px;
          f.a1y += u * py;
        }
      if (any_lane(partly_closed))
        {
          const ClosedPartT<Number> c =
            joint_closed_part(o_start, o_end, g.L, k);
          f.a0x = partly_closed ? f.a0x + c.force_start * g.nx : f.a0x;
          f.a0y = partly_closed ? f.a0y + c.force_start * g.ny : f.a0y;
          f.a1x = partly_closed ? f.a1x + c.force_end * g.nx : f.a1x;
          f.a1y = partly_closed ? f.a1y + c.force_end * g.ny : f.a1y;
        }
      // the turning frame: (1/2) (d0 x F0 + d1 x F1) / L along n
      const Number moment =
        g.d0x * f.a0y - g.d0y * f.a0x + g.d1x * f.a1y - g.d1y * f.a1x;
      const Number half_M = 0.5 * moment * g.inverse_L;
      f.frame_x           = half_M * g.nx;
      f.frame_y           = half_M * g.ny;
    }

    /**
     * Gauss points of a joint on a triangular face (tetrahedra, 3D): the
     * barycentric coordinates of the three-point rule, exact for
     * quadratics (the gap is linear over the face), each of weight 1/3 of
     * the area.
     */
    constexpr double face_joint_gauss_points[3][3] = {
      {2. / 3., 1. / 6., 1. / 6.},
      {1. / 6., 2. / 3., 1. / 6.},
      {1. / 6., 1. / 6., 2. / 3.}};

    /**
     * The frame of a joint on a triangular face at the current state: the
     * gaps of its three node pairs (B - A) [m], the edges e1 = m1 - m0,
     * e2 = m2 - m0 of the mean face m_k = (a_k + b_k) / 2 [m], its area
     * [m^2] and unit normal n = e1 x e2 / |e1 x e2| (outward of element A
     * when a0, a1, a2 run counter-clockwise seen from B).
     */
    template <typename Number>
    struct FaceJointFrameT
    {
      Number d[3][3]; ///< d[k][i]: component i of the gap of node pair k
      Number e1[3], e2[3];
      Number area, inverse_twice_area, n[3];
    };

    /**
     * The frame of a face joint with nodes a0, a1, a2 (element A) and b0,
     * b1, b2 (element B, b_k facing a_k) at @p x (x[i][node], nodes in the
     * order a0, a1, a2, b0, b1, b2) [m].
     */
    template <typename Number>
    __attribute__((always_inline)) inline FaceJointFrameT<Number>
    face_joint_frame(const Number *const (&x)[3])
    {
      FaceJointFrameT<Number> g;
      for (int i = 0; i < 3; ++i)
        {
          for (int k = 0; k < 3; ++k)
            g.d[k][i] = x[i][3 + k] - x[i][k];
          g.e1[i] = 0.5 * (x[i][1] + x[i][4] - x[i][0] - x[i][3]);
          g.e2[i] = 0.5 * (x[i][2] + x[i][5] - x[i][0] - x[i][3]);
        }
      const Number c[3] = {g.e1[1] * g.e2[2] - g.e1[2] * g.e2[1],
                           g.e1[2] * g.e2[0] - g.e1[0] * g.e2[2],
                           g.e1[0] * g.e2[1] - g.e1[1] * g.e2[0]};
      const Number twice_area =
        lane_sqrt(c[0] * c[0] + c[1] * c[1] + c[2] * c[2]);
      g.area               = 0.5 * twice_area;
      g.inverse_twice_area = 1. / twice_area;
      for (int i = 0; i < 3; ++i)
        g.n[i] = c[i] * g.inverse_twice_area;
      return g;
    }

    /**
     * What face_joint_response() computes for one face joint (or one per
     * lane). The node forces [N] are
     *
     *   a_k: a[k] + frame[k],   b_k: -a[k] + frame[k].
     */
    template <typename Number>
    struct FaceJointResponse
    {
      /** The tractions' forces on a_k [N], pulling A toward B; B's nodes
       *  take them with the opposite sign. */
      Number a[3][3];
      /** The forces of the turning frame on a_k and b_k alike [N] (sum
       *  zero; see face_joint_response()). */
      Number frame[3][3];
      /** The larger of the Gauss points' normalised softening opening and
       *  slip (cohesive_traction()) [-]. */
      Number d_opening, d_slip;
      /** Past a peak at a Gauss point (bool, or a lane mask). */
      decltype(Number() > 1.) beyond_peak;
    };

    /**
     * The forces of a joint on a triangular face with frame @p g, constants
     * @p k (JointConstants, or JointConstantLanes for a batch) and the
     * damage of its three Gauss points @p damage (updated in place): at
     * each Gauss point the gap d, its opening o = d.n and slip vector
     * s = d - o n; the cohesive law of the 2D joints on o and |s|
     * (cohesive_traction(): the same softening laws, mixed mode and
     * Mohr-Coulomb shear strength) gives the normal traction sigma and the
     * shear traction tau along s; the traction sigma n + tau s / |s|,
     * weighted area / 3, goes to the node pairs by the linear shape
     * functions.
     *
     * As in 2D the forces are the generalised forces of the tractions on o
     * and |s| with the normal turning with the mean face (its area held):
     * d|s| = s/|s| . (dd - o dn) and do = n . dd + d . dn give, besides
     * the traction, the work V . dn with V = sum_q w_q (sigma - tau o / |s|)
     * s. With dn = (I - n n)(de1 x e2 + e1 x de2) / |e1 x e2| and
     * de1 = (da1 + db1 - da0 - db0) / 2 (e2 alike) that is the force
     * -(e2 x V) / (2 |e1 x e2|) on a1 and b1, -(V x e1) / (2 |e1 x e2|) on
     * a2 and b2, and minus their sum on a0 and b0: o and |s| being
     * invariant under rigid motions, the joint keeps momentum and angular
     * momentum. A face closed over part of its area takes its compression
     * at the Gauss points.
     */
    template <SofteningLaw law,
              bool         with_softening = true,
              typename Number,
              typename Constants>
    __attribute__((always_inline)) inline void
    face_joint_response(const FaceJointFrameT<Number> &g,
                        const Constants               &k,
                        Number                        *damage,
                        FaceJointResponse<Number>     &f)
    {
      const Number zero{};
      for (int a = 0; a < 3; ++a)
        for (int i = 0; i < 3; ++i)
          f.a[a][i] = f.frame[a][i] = zero;
      f.d_opening = f.d_slip = zero;
      f.beyond_peak          = decltype(f.beyond_peak){};
      Number       V[3]      = {zero, zero, zero};
      const Number w         = g.area * (1. / 3.);
      for (int q = 0; q < 3; ++q)
        {
          const double *lambda = face_joint_gauss_points[q];
          Number        d[3];
          for (int i = 0; i < 3; ++i)
            d[i] = lambda[0] * g.d[0][i] + lambda[1] * g.d[1][i] +
                   lambda[2] * g.d[2][i];
          const Number o = d[0] * g.n[0] + d[1] * g.n[1] + d[2] * g.n[2];
          Number       s[3];
          for (int i = 0; i < 3; ++i)
            s[i] = d[i] - o * g.n[i];
          const Number abs_s =
            lane_sqrt(s[0] * s[0] + s[1] * s[1] + s[2] * s[2]);
          const JointTractionT<Number> tr =
            cohesive_traction<law, with_softening>(o, abs_s, k, damage[q]);
          f.d_opening = lane_max(f.d_opening, tr.d_opening);
          f.d_slip    = lane_max(f.d_slip, tr.d_slip);
          f.beyond_peak |= tr.beyond_peak;
          // tau / |s| (tau is 0 where |s| is)
          const auto   slipping = abs_s > 0.;
          const Number shear_per_slip =
            slipping ? tr.shear / (slipping ? abs_s : zero + 1.) : zero;
          const Number frame_factor = w * (tr.normal - shear_per_slip * o);
          for (int i = 0; i < 3; ++i)
            {
              const Number p = w * (tr.normal * g.n[i] + shear_per_slip * s[i]);
              for (int a = 0; a < 3; ++a)
                f.a[a][i] += lambda[a] * p;
              V[i] += frame_factor * s[i];
            }
        }
      // the turning frame: -(e2 x V) / (2 |c|) on a1, b1; -(V x e1) / (2 |c|)
      // on a2, b2; minus their sum on a0, b0
      const Number h     = -0.5 * g.inverse_twice_area;
      const Number f1[3] = {h * (g.e2[1] * V[2] - g.e2[2] * V[1]),
                            h * (g.e2[2] * V[0] - g.e2[0] * V[2]),
                            h * (g.e2[0] * V[1] - g.e2[1] * V[0])};
      const Number f2[3] = {h * (V[1] * g.e1[2] - V[2] * g.e1[1]),
                            h * (V[2] * g.e1[0] - V[0] * g.e1[2]),
                            h * (V[0] * g.e1[1] - V[1] * g.e1[0])};
      for (int i = 0; i < 3; ++i)
        {
          f.frame[1][i] = f1[i];
          f.frame[2][i] = f2[i];
          f.frame[0][i] = -(f1[i] + f2[i]);
        }
    }
  } // namespace discrete
} // namespace tmfdem

#endif
