/**
 * @file
 * Contact between tetrahedra as one unit (the 3D counterpart of
 * contact_system.h): the tetrahedra that take part (those with a free face
 * and their intact neighbours), the linked-cell broad phase
 * (LinkedCellSearchT<3>, contact.h) rebuilt when the accumulated travel
 * passes half the buffer or joints break, the pair forces of
 * add_pair_forces_3d() (tetrahedron_contact.h) on the solver's threads,
 * their sum per tetrahedron in pair order, the stored energy and the
 * stiffness bound the stable step needs.
 */
#ifndef tmfdem_discrete_tetrahedron_contact_system_h
#define tmfdem_discrete_tetrahedron_contact_system_h

#include <tmfdem/base/threads.h>
#include <tmfdem/discrete/contact_system.h>
#include <tmfdem/discrete/discrete_model.h>
#include <tmfdem/discrete/tetrahedron_contact.h>
#include <tmfdem/discrete/vertex_continuity.h>
#include <vector>

namespace tmfdem
{
  class CheckpointWriter;
  class CheckpointReader;

  namespace discrete
  {
    /** Two tetrahedra that may touch: their indices (first < second) and
     *  the friction history of each face of each as the contactor in the
     *  other. */
    struct TetrahedronContactPair
    {
      unsigned int            first = 0, second = 0;
      TetrahedronPairFriction friction{};
    };

    /**
     * Potential contact between the tetrahedra of a DiscreteModel (dim = 3,
     * one MPI process): the pair list, the pair forces of the last step and
     * the friction history they carry. The pair list is sorted by (first,
     * second) and does not depend on the thread count; the forces are
     * summed per tetrahedron in pair order, so the results do not either.
     */
    class TetrahedronContactSystem : public ContactTravel
    {
    public:
      /**
       * Takes the settings (ContactSettings: enabled, the penalties and
       * friction of the law, the buffer, the faces of broken joints); no
       * pairs yet. @p rigid_group per tetrahedron is the index of its body
       * if that body is fixed or driven (its tetrahedra never push each
       * other), or no_body.
       */
      void
      setup(const ContactSettings            &settings,
            const std::vector<unsigned char> &rigid_group);

      bool
      enabled() const
      {
        return contact.enabled;
      }
      const ContactSettings &
      settings() const
      {
        return contact;
      }

      /**
       * Bound of the contact stiffness a node of a tetrahedron with nodes
       * @p x (x[k][i]) can feel [N/m], for the stable step: a face of area A
       * pressed into a target of altitude H stores 2 p_n A o^2 / H for a
       * uniform overlap o in each of the two pair directions, a stiffness
       * 4 p_n A / H that one node may carry alone; the stick spring adds
       * p_t A / sqrt(A). With A the largest face of the tetrahedron and H
       * its smallest altitude: 4 p_n A_max / H_min + p_t sqrt(A_max). 0
       * without contact.
       */
      double
      node_stiffness_bound(const double (&x)[4][3]) const;

      /**
       * The factor on the normal penalty @p penalty [Pa] of the pair
       * (@p a, @p b) [-]: for the two faces of a broken joint the one that
       * gives their overlap the energy the joint stored in compression, so
       * that the contact takes over a compressed joint at its break without
       * a jump in energy (doc/theory.md 5.13). A joint of normal stiffness
       * k_n [Pa/m] stores k_n / 2 int o^2 dA for an overlap o(x) linear over
       * its face; the potential contact of the same overlap stores
       * 2 p (1 / H_a + 1 / H_b) int o^2 dA (H = 3 V / A the tetrahedra's
       * altitudes onto the face, in the reference configuration), so the
       * factor is k_n / (4 p (1 / H_a + 1 / H_b)), at most 1. 1 for any
       * other pair.
       */
      static double
      face_penalty_factor(const DiscreteModel &model,
                          const unsigned int   a,
                          const unsigned int   b,
                          const double         penalty);

      /** The tetrahedra of the next search: those with a free face and
       *  their intact neighbours (DiscreteModel::
       *  contact_candidate_elements()); call after joints broke. */
      void
      update_active_elements(const DiscreteModel &model);

      /**
       * Rebuilds the pair list from the current geometry of @p model: pairs
       * of active tetrahedra whose boxes come within the buffer, that no
       * intact joint joins, and that are not one piece of material around
       * the vertices or the edge they share (VertexContinuity). Pairs within
       * one rigid group carry no force. Friction history and energy offset
       * of pairs found again are kept. A pair new to the list after the
       * first search that is not the two faces of a broken joint takes the
       * normal contact energy it has now as its offset: the overlap that two
       * corners of one intact piece had through the joints' compliance is
       * not pushed out when a crack makes them two (doc/theory.md 5.13).
       */
      void
      search(const DiscreteModel &model, tbb::task_arena &arena);

      /**
       * The forces of every pair at the current state of @p model over the
       * step @p dt [s] (friction history, and the friction dissipated per
       * pair). A pair with an energy offset E_0 > 0 has the potential
       * (E - E_0)^2 / E of its normal contact energy E above the offset and
       * 0 below it: the normal forces of E times 1 - (E_0 / E)^2, none while
       * E <= E_0, and E_0 follows E down (the offset shrinks as the corners
       * separate and is gone once they do).
       */
      void
      compute_forces(const DiscreteModel &model,
                     const double         dt,
                     tbb::task_arena     &arena);

      /** Whether tetrahedron @p e has a pair that carries force. */
      bool
      has_pairs(const unsigned int e) const
      {
        return element_pair_start[e + 1] > element_pair_start[e];
      }

      /** Whether a pair of tetrahedron @p e may have carried force in the
       *  last compute_forces() (the others' forces are +0: the node update
       *  may take the contact-free path for it). */
      bool
      has_active_pairs(const unsigned int e) const
      {
        for (unsigned int p = element_pair_start[e];
             p < element_pair_start[e + 1];
             ++p)
          if (pair_active[element_pair_entries[p] / 2] != 0)
            return true;
        return false;
      }

      /** Adds the contact forces of all pairs of tetrahedron @p e to its
       *  twelve nodal components @p f [N] (pair order: deterministic). */
      void
      add_forces(const unsigned int e, double *f) const
      {
        add_element_pair_forces<12>(element_pair_start,
                                    element_pair_entries,
                                    pair_force,
                                    e,
                                    f,
                                    pair_active.data());
      }

      /** Energy dissipated by friction in the last step by the pairs whose
       *  first tetrahedron is in [@p begin, @p end), in pair order [J]. */
      double
      friction_of_elements(const std::size_t begin, const std::size_t end) const
      {
        return sum_pair_friction(first_pair_start, pair_friction, begin, end);
      }

      const std::vector<unsigned int> &
      active_elements() const
      {
        return active;
      }
      /** The pairs of the last search, sorted by (first, second). */
      const std::vector<TetrahedronContactPair> &
      pairs() const
      {
        return pair_list;
      }
      /** Pairs that carry contact forces (not within a rigid group). */
      unsigned int
      n_mechanical_pairs() const;
      unsigned long
      n_searches() const
      {
        return searches;
      }

      /**
       * The energy stored in the normal contact of the current pairs [J]:
       * E_t + E_c (pair_contact_energy_3d()), or (E - E_0)^2 / E above a
       * pair's energy offset E_0 and 0 below it, summed over the pairs that
       * carry force, each with its penalty (face_penalty_factor()), per chunk
       * of first tetrahedra in chunk order.
       */
      double
      stored_energy(const DiscreteModel &model, tbb::task_arena &arena) const;

      /**
       * The normal contact energy the two faces of joints broken in
       * compression brought into the contact, summed over the searches that
       * found them first (each with its penalty, face_penalty_factor()) [J].
       * The joints' share of the joint work becomes the contact's: without
       * it the contact work equals the stored energy plus the friction
       * dissipated; with it, that less this.
       */
      double
      handed_over_energy() const
      {
        return handed_over;
      }

      /** The pair of largest overlap (largest_overlap()). */
      struct Overlap
      {
        /** Overlap volume / the smaller tetrahedron's volume [-]; 0 if
         *  none. */
        double       fraction = 0.;
        double       volume   = 0.;         ///< [m^3]
        unsigned int first = 0, second = 0; ///< the two tetrahedra
      };
      /**
       * The force-carrying pair whose tetrahedra overlap most, relative to
       * the smaller one's volume (overlap_volume_3d()), in the current
       * geometry of @p model. Pairs within one rigid group, pairs of two
       * fixed or driven bodies, and pairs of one piece (connected by intact
       * joints: crushing, not failed contact) are skipped.
       */
      Overlap
      largest_overlap(const DiscreteModel &model) const;
      /** Writes the search state and the pairs with their friction history
       *  to a checkpoint. */
      void
      save(CheckpointWriter &out) const;
      /** Restores what save() wrote, for a model of @p n_elements. */
      void
      load(CheckpointReader &in, const unsigned int n_elements);

    private:
      /** Re-indexes the pairs per tetrahedron and flags the rigid ones
       *  after the pair list changed. */
      void
      index_pairs(const unsigned int n_elements);
      /** Gathers the nodes (and velocities) of tetrahedron @p e. */
      /** The nodes of tetrahedron @p e into @p x [m]. */
      static void
      gather_positions(const DiscreteModel &model,
                       const unsigned int   e,
                       double (&x)[4][3]);

      /** The nodes of both tetrahedra of @p pair into @p x[0], @p x[1]
       *  [m]. */
      static void
      gather_positions(const DiscreteModel          &model,
                       const TetrahedronContactPair &pair,
                       double (&x)[2][4][3]);

      /** The node velocities of tetrahedron @p e into @p v [m/s]. */
      static void
      gather_velocities(const DiscreteModel &model,
                        const unsigned int   e,
                        double (&v)[4][3]);

      ContactSettings            contact;
      std::vector<unsigned char> rigid_group; ///< per tetrahedron
      LinkedCellSearchT<3, TetrahedronContactPair> linked_cells;
      std::vector<TetrahedronContactPair>          pair_list;
      /** Pairs that carry no force (within one rigid group). */
      std::vector<char> pair_is_rigid;
      /** face_penalty_factor() of each pair [-]. */
      std::vector<double> pair_penalty_factor;
      /** Normal contact energy of each pair that its potential leaves out
       *  (search()) [J]. */
      std::vector<double> pair_energy_offset;
      /** handed_over_energy() [J]. */
      double handed_over = 0.;
      /** The pieces of material around each vertex, as of the last
       *  search. */
      VertexContinuity    continuity;
      std::vector<double> pair_force; ///< 24 per pair [N]
      /** 0 where a pair's forces, dissipation and friction history are
       *  known to be zero (its tetrahedra's boxes were apart at the last
       *  compute_forces() and it was reset then): compute_forces() and
       *  add_forces() skip it until the boxes meet. */
      std::vector<unsigned char> pair_active;
      std::vector<double>        pair_friction; ///< dissipation this step [J]
      /** Pairs of tetrahedron e: element_pair_entries[start[e] ..
       *  start[e+1]), each 2 pair + side (force-carrying pairs only). */
      std::vector<unsigned int> element_pair_start, element_pair_entries;
      /** Pairs whose first tetrahedron is e: [first_pair_start[e],
       *  first_pair_start[e + 1]) of the sorted pair list. */
      std::vector<unsigned int> first_pair_start;
      std::vector<unsigned int> active;
      unsigned long             searches = 0;
    };
  } // namespace discrete
} // namespace tmfdem

#endif
