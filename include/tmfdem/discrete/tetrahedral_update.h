/**
 * @file
 * The pieces of the 3D explicit step (TetrahedralSolver) written once for
 * one tetrahedron or face joint at a time and for the lanes of a vector
 * batch: a node component's works, a broken face joint's status and the
 * slots its forces go to; and the vector batches of the element loop and of
 * the face-joint loop (source/discrete/tetrahedral_update.cc), compiled
 * once per instruction set and chosen at run time as the 2D batches are
 * (vector_instructions.h). A batch does, lane by lane, the operations of
 * the one-at-a-time loop in the same order, so the results are bitwise
 * those of that loop.
 */
#ifndef tmfdem_discrete_tetrahedral_update_h
#define tmfdem_discrete_tetrahedral_update_h

#include <algorithm>
#include <cstddef>
#include <tmfdem/discrete/cohesive_law.h>
#include <tmfdem/discrete/discrete_model.h>
#include <tmfdem/discrete/solid.h>
#include <tmfdem/discrete/vector_instructions.h>

namespace tmfdem
{
  namespace discrete
  {
    /**
     * The slot of face @p f among the three faces of a tetrahedron that
     * hold its vertex @p k (face f holds every vertex but 3 - f): the
     * node's forces of that face's joint are
     * DiscreteModel::node_joint_force[9 node + 3 slot + i].
     */
    inline unsigned int
    face_slot(const unsigned int f, const unsigned int k)
    {
      return f < 3 - k ? f : f - 1;
    }

    /** The works of one component of a node's forces over a step [J], by
     *  origin (one node, or one per lane). */
    template <typename Number>
    struct TetrahedronNodeWorks
    {
      Number elastic, viscous, joint, reaction, damping;
    };

    /**
     * The works over the step's displacement @p travel = dt (v_old +
     * v_new) / 2 [m] of one component of a node's elastic, viscous, joint
     * and reaction forces @p f_elastic, @p f_viscous, @p f_joint,
     * @p f_reaction [N], and the dissipation c m / dt travel^2 [J] of the
     * mass damping @p c_m [1/s] on its mass @p mass [kg] over the step
     * @p dt [s].
     */
    template <typename Number>
    __attribute__((always_inline)) inline TetrahedronNodeWorks<Number>
    tetrahedron_node_works(const Number f_elastic,
                           const Number f_viscous,
                           const Number f_joint,
                           const Number f_reaction,
                           const Number travel,
                           const double c_m,
                           const Number mass,
                           const double dt)
    {
      TetrahedronNodeWorks<Number> w;
      w.elastic  = f_elastic * travel;
      w.viscous  = f_viscous * travel;
      w.joint    = f_joint * travel;
      w.reaction = f_reaction * travel;
      w.damping  = c_m * mass / dt * travel * travel;
      return w;
    }

    /** The step's displacement dt (v_old + v_new) / 2 [m] of a node
     *  component with velocities @p v_old, @p v_new [m/s] over @p dt [s]. */
    template <typename Number>
    __attribute__((always_inline)) inline Number
    half_step_travel(const double dt, const Number v_old, const Number v_new)
    {
      return 0.5 * dt * (v_old + v_new);
    }

    /**
     * Marks face joint @p j broken at @p time [s], its mode from the largest
     * normalised softening opening @p d_opening and slip @p d_slip of its
     * Gauss points [-] (FaceJointResponse): Mode I where the opening's
     * share d_o^2 / (d_o^2 + d_s^2) exceeds 0.9, Mode II below 0.1, mixed
     * between.
     */
    inline void
    mark_face_joint_broken(DiscreteModel    &m,
                           const std::size_t j,
                           const double      d_opening,
                           const double      d_slip,
                           const double      time)
    {
      const double d_o = d_opening, d_s = d_slip;
      const double ratio = d_o * d_o / std::max(1e-300, d_o * d_o + d_s * d_s);
      m.joint_status[j]  = ratio > 0.9 ? JointStatus::mode_I :
                           ratio < 0.1 ? JointStatus::mode_II :
                                         JointStatus::mixed;
      m.joint_break_time[j] = time;
    }

    /**
     * Writes the forces @p f [side][node][component] [N] of face joint
     * @p j to its nodes' slots of DiscreteModel::node_joint_force; side s's
     * face of its element is @p joint_face [2 j + s] (0-3).
     */
    inline void
    write_face_joint_forces(DiscreteModel       &m,
                            const std::size_t    j,
                            const unsigned char *joint_face,
                            const double (&f)[2][3][3])
    {
      const unsigned int *p = &m.joint_nodes[6 * j];
      for (unsigned int side = 0; side < 2; ++side)
        {
          const unsigned int face = joint_face[2 * j + side];
          for (unsigned int k = 0; k < 3; ++k)
            {
              const unsigned int node  = p[3 * side + k];
              const unsigned int local = node % 4;
              double            *slot =
                &m.node_joint_force[9 * node + 3 * face_slot(face, local)];
              for (unsigned int i = 0; i < 3; ++i)
                slot[i] = f[side][k][i];
            }
        }
    }

    /** What the element batches read besides the model. */
    struct TetrahedronBatchInput
    {
      /** Per element: Lame constants [Pa] and viscosity [Pa s]. */
      const LameConstants *lame;
      const double        *viscosity;
      /** Per element: the anisotropic correction (21 each), or nullptr. */
      const double *anisotropy = nullptr;
      /** The step [s]; v_new = a v_old + b / m f with @p damp_a [-] and
       *  @p damp_b [s]; the mass damping c [1/s]. */
      double dt, damp_a, damp_b, c_m;
      /** Gravity on every node, m g (with_gravity; its work is external
       *  work, in the reaction's slot) [m/s^2]. */
      bool   with_gravity = false;
      double gravity[3]   = {0., 0., 0.};
    };

    /**
     * A batch of the element loop: the tetrahedra e0 ... e0 + lanes - 1,
     * all of whose nodes are free (no imposed velocity), their forces, the
     * node update and the step's works, added to @p works (elastic,
     * viscous, joint, reaction, damping [J]) lane by lane, node by node,
     * component by component as the one-at-a-time loop adds them; the first
     * inverted element and the first node with a non-finite velocity go to
     * @p guard [0], [1] where those are still -1.
     */
    using TetrahedronBatchKernel = void (*)(DiscreteModel &,
                                            const std::size_t,
                                            const TetrahedronBatchInput &,
                                            double    *works,
                                            long long *guard);

    /**
     * A batch of the face-joint loop: the joints j0 ... j0 + lanes - 1, all
     * intact, their forces (face_joint_response(), damage updated) written
     * to their nodes' slots (write_face_joint_forces(), @p joint_face); a
     * joint that breaks is marked broken at @p time [s] and @p broke set.
     */
    using FaceJointBatchKernel = void (*)(DiscreteModel &,
                                          const std::size_t,
                                          const unsigned char *joint_face,
                                          const double         time,
                                          char                &broke);

    /** The element batch of @p instructions, or nullptr (none). */
    TetrahedronBatchKernel
    tetrahedron_batch_kernel(const VectorInstructions instructions);

    /** The face-joint batch of @p instructions and the softening law
     *  @p law, or nullptr (none). */
    FaceJointBatchKernel
    face_joint_batch_kernel(const VectorInstructions instructions,
                            const SofteningLaw       law);
  } // namespace discrete
} // namespace tmfdem

#endif
