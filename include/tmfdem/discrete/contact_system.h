/**
 * @file
 * Contact of the discrete layer as one unit: which elements take part
 * (those with a free edge and their intact neighbours), the broad-phase
 * pair search (LinkedCellSearch, contact.h) rebuilt when the accumulated
 * travel passes half the buffer, the contact law (a policy,
 * contact_law.h), the forces of every pair and their index per element
 * for the fused node update.
 */
#ifndef tmfdem_discrete_contact_system_h
#define tmfdem_discrete_contact_system_h

#include <tmfdem/base/threads.h>
#include <tmfdem/discrete/contact.h>
#include <tmfdem/discrete/contact_law.h>
#include <tmfdem/discrete/discrete_model.h>
#include <tmfdem/discrete/partition.h>
#include <vector>

namespace tmfdem
{
  class CheckpointWriter;
  class CheckpointReader;
  struct DiscreteMechanicsParameters;

  namespace discrete
  {
    /** What the contact of a run is made of (Discrete mechanics). */
    struct ContactSettings
    {
      bool                  enabled = true; ///< Discrete mechanics/Contact
      ContactLaw            law     = ContactLaw::penalty_coulomb;
      PenaltyCoulombContact penalty_coulomb; ///< its constants
      /** Search buffer: pairs are searched with boxes this much larger and
       *  searched again when a node may have travelled half of it [m]. */
      double buffer = 0.;
      /** The faces of a broken joint touch with at most the joint's
       *  compressive stiffness (face_penalty_factor(); `Contact of broken
       *  joint faces`); false: with the contact penalty like any pair. */
      bool match_broken_joints = true;
    };

    /**
     * Adds to @p f (@p width nodal force components of one element) the
     * forces of the element's pairs: entries [@p start[e], @p start[e + 1])
     * of @p entries, each 2 pair + side, whose forces are the @p width
     * components of that side in @p pair_force (2 @p width per pair), in
     * pair order (deterministic). Both contact systems. With @p active,
     * the pairs p with active[p] == 0 are skipped: their forces are +0, and
     * a sum that starts from +0 is never -0, so adding +0 changes nothing
     * (the result is bitwise that of adding them).
     */
    template <unsigned int width>
    inline void
    add_element_pair_forces(const std::vector<unsigned int> &start,
                            const std::vector<unsigned int> &entries,
                            const std::vector<double>       &pair_force,
                            const unsigned int               e,
                            double                          *f,
                            const unsigned char             *active = nullptr)
    {
      for (unsigned int p = start[e]; p < start[e + 1]; ++p)
        {
          const unsigned int entry = entries[p];
          if (active != nullptr && active[entry / 2] == 0)
            continue;
          const double *pf =
            &pair_force[2 * width * (entry / 2) + width * (entry % 2)];
          for (unsigned int i = 0; i < width; ++i)
            f[i] += pf[i];
        }
    }

    /** The sum of @p pair_friction over the pairs whose first element is
     *  in [@p begin, @p end) (@p first_start: where each element's pairs
     *  begin in the sorted list), in pair order. Both contact systems. */
    inline double
    sum_pair_friction(const std::vector<unsigned int> &first_start,
                      const std::vector<double>       &pair_friction,
                      const std::size_t                begin,
                      const std::size_t                end)
    {
      double sum = 0.;
      if (first_start.empty())
        return sum;
      for (unsigned int p = first_start[begin]; p < first_start[end]; ++p)
        sum += pair_friction[p];
      return sum;
    }

    /**
     * The contact settings of `Discrete mechanics` @p dm (both dimensions):
     * the penalties p_n, p_t from the stiffest material's Young's modulus
     * @p youngs_modulus [Pa], the friction law, the target's share and the
     * broken faces' penalty, and the buffer (`Contact buffer`, or a quarter
     * of @p smallest_size [m]).
     */
    ContactSettings
    make_contact_settings(const DiscreteMechanicsParameters &dm,
                          const double                       youngs_modulus,
                          const double                       smallest_size);

    /**
     * The search bookkeeping both contact systems share: the travel of the
     * fastest node since the last search and since the last overlap check,
     * and whether a search is due.
     */
    class ContactTravel
    {
    public:
      /** No travel; a search is due. */
      void
      reset(const double search_buffer)
      {
        buffer                     = search_buffer;
        travel_since_search        = 0.;
        travel_since_overlap_check = 0.;
        search_is_needed           = true;
      }
      /** After a step whose fastest node moved @p distance [m]: a search is
       *  due when the travel since the last one passes half the buffer. */
      void
      add_travel(const double distance)
      {
        travel_since_search += distance;
        travel_since_overlap_check += distance;
        if (2. * travel_since_search > buffer)
          search_is_needed = true;
      }
      /** Whether the overlap guard is due: the fastest node has travelled
       *  half the buffer since its last check, as for a search. Searches
       *  that joints breaking ask for come far more often and need no
       *  check. */
      bool
      overlap_check_due() const
      {
        return 2. * travel_since_overlap_check > buffer;
      }
      void
      overlap_checked()
      {
        travel_since_overlap_check = 0.;
      }
      /** Asks for a search before the next force computation (joints
       *  broke, nodes jumped). */
      void
      request_search()
      {
        search_is_needed = true;
      }
      bool
      search_needed() const
      {
        return search_is_needed;
      }
      /** A search was made now. */
      void
      searched()
      {
        travel_since_search = 0.;
        search_is_needed    = false;
      }
      /** Writes the travel since the search and the flag (checkpoints). */
      void
      save(CheckpointWriter &out) const;
      void
      load(CheckpointReader &in);

    private:
      double buffer                     = 0.; ///< [m]
      double travel_since_search        = 0.; ///< [m]
      double travel_since_overlap_check = 0.; ///< [m]
      bool   search_is_needed           = true;
    };

    /**
     * Potential contact between the triangles of a DiscreteModel: the pair
     * list, the pair forces of the last step and the friction history they
     * carry. The pair list is sorted and does not depend on the thread
     * count; forces are summed per element in pair order.
     */
    class ContactSystem : public ContactTravel
    {
    public:
      /**
       * Takes the settings; no pairs yet. @p rigid_group per element is the
       * index of its body if that body is fixed or driven (its elements
       * never push each other), or no_body.
       */
      void
      setup(const ContactSettings            &settings,
            const std::vector<unsigned char> &rigid_group);

      const ContactSettings &
      settings() const
      {
        return contact;
      }
      bool
      enabled() const
      {
        return contact.enabled;
      }
      /** The law's stiffness bound per node for the stable step [N/m per m];
       *  0 without contact. */
      double
      node_stiffness_bound() const;

      /**
       * The factor on the normal contact penalty @p penalty [Pa] of the
       * pair (@p a, @p b) [-]: for the two faces of a broken joint, the one
       * that gives their overlap the energy the joint stored in
       * compression, so that the contact takes over a compressed joint at
       * its break without a jump in energy or force (doc/theory.md 5.5). A
       * joint of normal stiffness k_n [Pa/m] stores k_n / 2 int o^2 ds for
       * an overlap o(s) linear along its edge; the potential contact of the
       * same overlap stores 3 p / 2 (1 / H_a + 1 / H_b) int o^2 ds (H the
       * triangles' altitudes onto the edge, in the reference
       * configuration), so the factor is k_n / (3 p (1 / H_a + 1 / H_b)).
       * 1 for any other pair.
       */
      static double
      face_penalty_factor(const DiscreteModel &model,
                          const unsigned int   a,
                          const unsigned int   b,
                          const double         penalty);

      /**
       * The elements that take part in the next search: those with a free
       * edge (no intact joint) and their intact neighbours, in index order,
       * from the joints' status in @p model. search() uses them; on several
       * ranks every rank finds the same (partition.h).
       */
      void
      update_active_elements(const DiscreteModel &model);
      const std::vector<unsigned int> &
      get_active_elements() const
      {
        return active_elements;
      }

      /**
       * Rebuilds the pair list from the current geometry of @p model: the
       * active elements of update_active_elements() (call it first), pairs
       * of those whose boxes come within the buffer and that are not
       * joined by an intact joint. Pairs within one rigid group stay in the
       * list (contact heat flows between them) but carry no force. Friction
       * history of pairs that persist is kept. On several ranks each rank
       * makes the pairs of its own first triangles and keeps the pairs with
       * a triangle of its own: the owner of the first triangle sends a pair
       * to the owner of the second (ElementPartition::exchange_pairs()).
       * With
       * @p candidates (sorted) and @p extent, a rank bins only those (its
       * own active triangles and the others' near its region, from
       * ElementPartition::exchange_search_candidates()) on the grid of the
       * extent of all active triangles: the same pairs.
       */
      void
      search(const DiscreteModel             &model,
             tbb::task_arena                 &arena,
             ElementPartition                &partition,
             const std::vector<unsigned int> *candidates = nullptr,
             const SearchExtent              *extent     = nullptr);

      /** Forces of the pairs with a triangle of this rank (@p partition)
       *  at the current state, with the law of the settings, over the step
       *  @p dt [s] (friction history and the friction dissipated by each
       *  pair: friction_of_elements()). */
      void
      compute_forces(const DiscreteModel    &model,
                     const double            dt,
                     tbb::task_arena        &arena,
                     const ElementPartition &partition);

      /** Adds the contact forces of all pairs of element @p e to its six
       *  nodal components @p f [N/m] (pair order: deterministic). */
      void
      add_forces(const unsigned int e, double *f) const
      {
        add_element_pair_forces<6>(element_pair_start,
                                   element_pair_entries,
                                   pair_force,
                                   e,
                                   f);
      }

      /** Energy dissipated by friction in the last step by the pairs
       *  whose first triangle is in [@p begin, @p end), summed in pair
       *  order [J/m]. */
      double
      friction_of_elements(const std::size_t begin, const std::size_t end) const
      {
        return sum_pair_friction(first_pair_start, pair_friction, begin, end);
      }

      /** The candidate pairs of the last search, sorted by (first, second):
       *  the mechanical contacts. On several ranks those with a triangle of
       *  this rank (the subsequence of the list of one rank), or, after
       *  synchronise_pairs() until the next search, all. */
      const std::vector<ContactPair> &
      pairs() const
      {
        return pair_list;
      }
      /** All candidate pairs of the last search, sorted: the candidates of
       *  contact heat, which runs on every rank with the whole state. On
       *  one rank pairs(); on several the list of gather_all_pairs(), whose
       *  address stays the same. */
      const std::vector<ContactPair> &
      all_pairs(const ElementPartition &partition) const;
      /** On several ranks: brings all_pairs() up to date (one gather per
       *  search, ElementPartition::gather_pairs()); a no-op on one rank. */
      void
      gather_all_pairs(ElementPartition &partition);
      bool
      has_pairs() const
      {
        return !pair_list.empty();
      }
      /** Pairs that carry contact forces (not within a rigid group), of
       *  all ranks (collective on several ranks). */
      unsigned int
      n_mechanical_pairs(const ElementPartition &partition) const;

      /**
       * The energy stored in the normal contact of the current pairs [J/m]:
       * p int_S (phi_c + phi_t) dA summed over the pairs that carry force,
       * each with its penalty (face_penalty_factor()), each pair counted by
       * the owner of its first triangle and summed over the ranks. The
       * normal force is minus its gradient (add_target_potential_forces());
       * the relaxation predictor books its change over a jump.
       */
      double
      stored_energy(const DiscreteModel    &model,
                    const ElementPartition &partition) const;
      /** The pair of largest overlap (largest_overlap()). */
      struct Overlap
      {
        /** Overlap area / the smaller triangle's area [-]; 0 if none. */
        double       fraction = 0.;
        double       area     = 0.;         ///< [m^2 per m]
        unsigned int first = 0, second = 0; ///< the two triangles
      };
      /**
       * The force-carrying pair of the current pair list (this rank's
       * pairs) whose triangles overlap most, relative to the smaller
       * triangle's area (triangle_overlap.h), in the current geometry of
       * @p model. Pairs within one rigid group, and pairs of one piece
       * (connected by intact joints: crushing, not failed contact), are
       * skipped. Not collective.
       */
      Overlap
      largest_overlap(const DiscreteModel &model) const;

      unsigned long
      n_searches() const
      {
        return searches;
      }

      /** On several ranks: the whole pair list on every rank, every pair's
       *  friction history and forces taken from the owner of its first
       *  triangle (before outputs and checkpoints, rare); pairs() holds all
       *  pairs until the next search. A no-op on one rank. */
      void
      synchronise_pairs(ElementPartition &partition);

      /** Writes the search state and the pairs with their friction
       *  history to a checkpoint. */
      void
      save(CheckpointWriter &out) const;
      /** Restores what save() wrote, for a model of @p n_elements. */
      void
      load(CheckpointReader &in, const unsigned int n_elements);

    private:
      /** Re-indexes the pairs per element after the pair list changed. */
      void
      index_pairs(const unsigned int n_elements);
      template <typename Law>
      void
      compute_forces_with(const Law              &law,
                          const DiscreteModel    &model,
                          const double            dt,
                          tbb::task_arena        &arena,
                          const ElementPartition &partition);

      /** Flags the pairs within one rigid group (no force). */
      void
      flag_rigid_pairs();

      ContactSettings            contact;
      std::vector<unsigned char> rigid_group;   ///< per element
      std::vector<char>          pair_is_rigid; ///< per pair
      LinkedCellSearch           linked_cells;
      std::vector<ContactPair>   pair_list;
      std::vector<double>        pair_force;    ///< 12 per pair [N/m]
      std::vector<double>        pair_friction; ///< dissipation this step
      /** Pairs of element e: element_pair_entries[start[e] .. start[e+1]),
       *  each 2 pair + side. */
      std::vector<unsigned int> element_pair_start, element_pair_entries;
      /** Pairs whose first triangle is e: [first_pair_start[e],
       *  first_pair_start[e + 1]) of the (sorted) pair list. */
      std::vector<unsigned int> first_pair_start;
      std::vector<unsigned int> active_elements;
      /** Several ranks: the pairs with a triangle of this rank, made for
       *  the search numbered local_pairs_of_search - 1. */
      std::vector<unsigned int> local_pairs;
      unsigned long             local_pairs_of_search = 0;
      /** face_penalty_factor() of each pair, formed once per pair list
       *  (emptied by index_pairs()); empty without match_broken_joints. */
      std::vector<double> pair_penalty_factor;
      /** Several ranks: all pairs (all_pairs()), gathered for the search
       *  numbered all_pairs_of_search - 1. */
      std::vector<ContactPair> all_pair_list;
      unsigned long            all_pairs_of_search = 0;
      unsigned long            searches            = 0;
    };
  } // namespace discrete
} // namespace tmfdem

#endif
