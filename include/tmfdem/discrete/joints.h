/**
 * @file
 * The cohesive joints of the discrete layer as a whole (the law of one
 * joint is cohesive_law.h): their constants from the materials (with
 * heterogeneous strengths), their forces at the current state, and the
 * measures the coupling needs (strength utilisation, damaged count).
 */
#ifndef tmfdem_discrete_joints_h
#define tmfdem_discrete_joints_h

#include <tmfdem/base/parameters.h>
#include <tmfdem/base/threads.h>
#include <tmfdem/discrete/cohesive_law.h>
#include <tmfdem/discrete/discrete_model.h>
#include <tmfdem/discrete/vector_instructions.h>
#include <vector>

namespace tmfdem
{
  namespace discrete
  {
    /** Which joints a rank computes: the range [begin, end) and the joints
     *  in @p others (sorted). One rank: all joints, others empty. */
    struct JointSubset
    {
      unsigned int              begin = 0, end = 0;
      std::vector<unsigned int> others;
    };

    /**
     * Joint constants of every joint of @p model from the materials on its
     * two sides (interfaces take the weaker strength and fracture energy,
     * the stiffer E for the penalties), with the strengths scaled by the
     * heterogeneity of Discrete mechanics (Weibull or normal factors drawn
     * from Random seed in the mesh's order of the joints, by
     * DiscreteModel::mesh_index: the same field whatever the numbering). Throws
     * InputError naming the joint if a fracture energy is below the work stored
     * before the peak.
     */
    void
    setup_joint_constants(const Parameters  &parameters,
                          const SofteningLaw law,
                          DiscreteModel     &model);

    /** What one chunk of the joint forces did. */
    struct JointChunkTally
    {
      bool         broke      = false; ///< a joint of the chunk broke
      unsigned int intact     = 0;     ///< intact joints computed
      unsigned int vectorised = 0;     ///< of those, in vector batches
    };

    /**
     * Forces of all intact joints at time @p time [s] into
     * the slots of their four nodes in model.node_joint_force [N/m]; joints
     * whose damage reaches 1 at both Gauss points break (status by mode,
     * break time @p time) and their slots are zeroed. Runs in @p arena over
     * fixed chunks; @p tally gets what each chunk did. Only the joints of @p
     * subset are computed (on several ranks those with a triangle of this rank,
     * partition.h). Batches of joints on the rising branch of the law go
     * through the vector kernel of @p instructions, bitwise the same
     * (vector_instructions.h). Returns whether one of them broke.
     */
    bool
    compute_joint_forces(const SofteningLaw            law,
                         DiscreteModel                &model,
                         const double                  time,
                         tbb::task_arena              &arena,
                         std::vector<JointChunkTally> &tally,
                         const JointSubset            &subset,
                         const VectorInstructions      instructions);

    /**
     * The strength utilisation of every joint into @p utilisation (one
     * value per joint) [-]: for an undamaged intact joint the largest over
     * its Gauss points of opening / peak opening and |slip| / peak slip (1
     * at the peak of the cohesive law, capped there); -1 for a damaged or
     * broken joint, whose state the damage measures instead.
     */
    void
    joint_utilisations(const DiscreteModel &model,
                       std::vector<double> &utilisation);

    /**
     * The damage of every joint's more damaged Gauss point into @p damage
     * (one value per joint, 1 for a broken joint) [-].
     */
    void
    joint_damages(const DiscreteModel &model, std::vector<double> &damage);

    /** Joints that are damaged or broken [-]. */
    unsigned int
    n_damaged_or_broken_joints(const DiscreteModel &model);
  } // namespace discrete
} // namespace tmfdem

#endif
