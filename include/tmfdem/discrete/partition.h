/**
 * @file
 * The discrete layer on several MPI processes: which triangles each rank
 * owns, the ghost exchange of every explicit step, the exchange of
 * candidates by bounding boxes before a contact search, and the full
 * synchronisation before whatever reads the whole state (heat, energy,
 * outputs, checkpoints).
 *
 * The data layout is that of deal.II's parallel::shared::Triangulation:
 * every rank holds the whole exploded mesh (DiscreteModel), owns a part of
 * it and advances only that part; triangles keep their rank for the whole
 * run (Lagrangian). A rank owns a contiguous range of whole chunks of the
 * node update (ExplicitSolver::chunk_size triangles each), so that every
 * per-chunk sum (works, reactions, guards) is computed by one rank in the
 * serial order and the reductions are exact: results on any number of
 * ranks are bitwise those of one rank (doc/theory.md, "MPI"). The
 * triangles are numbered along a Hilbert curve when the model is built
 * (mesh/cell_order.h), so a range is a compact region and the halo grows
 * with its perimeter.
 *
 * Per step a rank needs, besides its own nodes, the nodes of the triangles
 * joined to its triangles (joints) and of the contact partners of its
 * triangles (the pair list of the last search): the ghosts. Owners send
 * them after every node update (point-to-point, pre-sized buffers); the
 * plan is rebuilt after every contact search from the rank's pair list
 * (the pairs with a triangle of its own).
 *
 * A contact search needs no full synchronisation: the joints' status goes
 * to every rank, so every rank knows the same active triangles, but only
 * what changed (a rank sends, of the joints of its first triangles, those
 * whose status differs from what it last sent, 4 B each; an intact body
 * sends only the counts), so the search's exchanges grow with what breaks
 * and what lies near another rank, not with the mesh. Then each rank
 * receives, from the ranks whose region (the hull of their active
 * triangles' search boxes) meets its own, only the triangles whose search
 * box meets its region (exchange_search_candidates()), makes the pairs of
 * its own first triangles and sends those whose second triangle is another
 * rank's to that rank (exchange_pairs()): each rank keeps the pairs with a
 * triangle of its own, in the order of one rank's list. The ghosts new to
 * the plan then come from their owners (exchange_new_ghosts()). The whole
 * pair list goes to every rank only before outputs and checkpoints and for
 * the contact heat (gather_pairs()).
 */
#ifndef tmfdem_discrete_partition_h
#define tmfdem_discrete_partition_h

#include <cstdint>
#include <mpi.h>
#include <tmfdem/discrete/contact.h>
#include <tmfdem/discrete/discrete_model.h>
#include <tmfdem/discrete/joints.h>
#include <vector>

namespace tmfdem
{
  namespace discrete
  {
    /** Ownership of the triangles and the exchanges between ranks. */
    class ElementPartition
    {
    public:
      /**
       * Splits the @p model's triangles over the ranks of @p communicator:
       * rank r owns whole chunks of @p chunk_size triangles, the chunks
       * [r C / P, (r + 1) C / P) of C chunks on P ranks. One rank owns all.
       */
      void
      setup(MPI_Comm             communicator,
            const DiscreteModel &model,
            const unsigned int   chunk_size);

      /** The ranks' communicator. */
      MPI_Comm
      get_communicator() const
      {
        return communicator;
      }
      /** More than one rank. */
      bool
      distributed() const
      {
        return n_ranks > 1;
      }
      unsigned int
      rank() const
      {
        return this_rank;
      }
      unsigned int
      n_processes() const
      {
        return n_ranks;
      }
      /** First owned triangle. */
      unsigned int
      begin() const
      {
        return element_begin[this_rank];
      }
      /** One past the last owned triangle. */
      unsigned int
      end() const
      {
        return element_begin[this_rank + 1];
      }
      bool
      owns(const unsigned int e) const
      {
        return e >= begin() && e < end();
      }
      /** First joint of this rank (joints belong to the owner of their
       *  first triangle). */
      unsigned int
      first_joint() const
      {
        return joint_begin[this_rank];
      }
      /** One past the last joint of this rank. */
      unsigned int
      end_joint() const
      {
        return joint_begin[this_rank + 1];
      }
      /** The joints this rank computes: its own (first triangle here)
       *  and those whose second triangle is here. */
      const JointSubset &
      joints() const
      {
        return joint_subset;
      }
      /** Triangles per chunk: every rank owns whole chunks, so a sum per
       *  chunk is computed by one rank (sum()). */
      unsigned int
      chunk_size() const
      {
        return chunk_elements;
      }
      /** The rank that owns triangle @p e. */
      unsigned int
      owner(const unsigned int e) const;
      /** Triangles of rank r: [first_element(r), first_element(r + 1)). */
      unsigned int
      first_element(const unsigned int r) const
      {
        return element_begin[r];
      }

      /**
       * The ghost plan: for every other rank the owned triangles it needs
       * (joined to or in a contact pair with one of its triangles) and the
       * triangles this rank needs from it, from the joints of @p model and
       * the contact pairs @p pairs.
       */
      void
      build_ghost_plan(const DiscreteModel            &model,
                       const std::vector<ContactPair> &pairs);

      /** Sends the positions and velocities of the owned nodes others need
       *  and receives those of the ghosts (every explicit step). */
      void
      exchange_ghosts(DiscreteModel &model);

      /**
       * The same plan for one value per node (@p values: 3 per triangle,
       * node 3e+k, e.g. the temperatures): sends the values of the owned
       * nodes others need and receives those of the ghosts.
       */
      void
      exchange_ghost_node_values(double *values);

      /**
       * Gives every rank the values of all triangles: @p values holds
       * @p width values per triangle (triangle e at width e); each rank's
       * block of its own triangles goes to every rank (MPI_Allgatherv).
       */
      void
      gather_element_values(double *values, const unsigned int width);

      /**
       * After build_ghost_plan() following a search by bounding boxes
       * (exchange_search_candidates()): sends and receives the positions
       * and velocities of the ghosts that were not in the previous plan
       * (the ghosts of the previous plan are current: exchange_ghosts()
       * after every node update). The partner of a pair made by a lower
       * rank came to it with the search, but the higher rank computes the
       * pair's forces too and needs the lower rank's triangle: so every
       * ghost is current before the first force computation of the plan.
       */
      void
      exchange_new_ghosts(DiscreteModel &model);

      /**
       * Gives every rank the whole state: positions, velocities and
       * stresses of all nodes and triangles, and the state of all joints
       * (a joint belongs to the owner of its first triangle; both owners
       * computed it the same way). With @p geometry_only, only the node
       * positions and velocities and the joints' status.
       */
      void
      synchronise(DiscreteModel &model, const bool geometry_only = false);

      /**
       * What a contact search needs, in two steps: the status of every
       * joint, on every rank as its owner has it ... A rank sends only the
       * joints of its first triangles [first_joint(), end_joint()) whose
       * status differs from the one it last sent (here or in
       * synchronise(); at setup() every rank holds the same model), as one
       * 32-bit word each (index and status; MPI_Allgather of the counts,
       * then MPI_Allgatherv of the words where any rank has one), and every
       * rank writes them into @p model. Every other joint a rank holds is
       * then what its owner holds too: sent before and unchanged since, or
       * computed by this rank as well (joints()), the same way. After
       * --resume every rank holds the checkpoint's statuses; the joints
       * that changed between setup() and the checkpoint then go once more
       * with the next exchange, which changes nothing.
       */
      void
      synchronise_joint_status(DiscreteModel &model);
      /**
       * ... then, once every rank knows the same active @p elements (sorted;
       * ContactSystem::update_active_elements()), the triangles the search
       * of this rank needs, by bounding boxes. A pair (a, b), a < b, is made
       * by the owner of a, and only when the search boxes of a and b
       * overlap (search_box(), contact.h: the bounding box enlarged by half
       * the @p buffer [m]). Each rank takes the hull of the search boxes of
       * its own active triangles, its region; the regions (4 doubles) and
       * the largest box side go to every rank (MPI_Allgather). A rank then
       * sends to each lower rank whose region meets its own the positions
       * and velocities (and index) of its own active triangles whose search
       * box meets that rank's region (point-to-point; who sends to whom
       * follows from the regions every rank knows): a box that overlaps
       * the box of a triangle of the region meets the region, so a lower
       * rank receives every partner its pairs can have; the rest stay
       * where they are. Receivers write them into @p model.
       *
       * On return @p candidates holds, sorted, this rank's own active
       * triangles and those received: what its search bins. @p extent is
       * that of the active triangles of all ranks (exact: minima and
       * maxima), so the linked-cell grid is the one one rank makes and the
       * pairs of this rank's first triangles are bitwise those one rank
       * makes.
       */
      void
      exchange_search_candidates(DiscreteModel                   &model,
                                 const std::vector<unsigned int> &elements,
                                 const double                     buffer,
                                 std::vector<unsigned int>       &candidates,
                                 SearchExtent                    &extent);

      /**
       * After a contact search: on entry @p pairs holds the pairs this
       * rank made (first triangle its own, sorted, with the friction
       * history it kept); on return the pairs with a triangle of this rank,
       * sorted: first those made by lower ranks whose second triangle is
       * here, received in rank order, then its own. A pair (a, b), a < b,
       * lies on the owners of a and b only; the owner of a sends it
       * (point-to-point: two 32-bit ids, 8 B, and, where it slides, its
       * index and six slips) to the owner of b, which computes its forces
       * too. Each rank's list is thus the subsequence of the list one rank
       * makes that holds its triangles: every triangle of the rank sees its
       * pairs in the order of np 1 (forces and friction sums bitwise).
       * With @p by_regions (the search followed exchange_search_candidates())
       * only ranks whose regions meet exchange messages; else every lower
       * rank sends one to every higher rank.
       */
      void
      exchange_pairs(std::vector<ContactPair> &pairs, const bool by_regions);

      /**
       * The whole pair list on every rank (rare: outputs, checkpoints,
       * contact heat): on entry @p pairs holds the pairs this rank made
       * (first triangle its own, sorted) and @p values, if given, @p width
       * doubles per pair of them; on return the pairs of all ranks in rank
       * order, which is the sorted list one rank makes, with the friction
       * history each owner kept, and the values of all pairs in the same
       * order. Only the pairs with a slip or a value (any bit set) send
       * them, with their index: 8 B for a pair that is not touching.
       */
      void
      gather_pairs(std::vector<ContactPair> &pairs,
                   std::vector<double>      *values = nullptr,
                   const unsigned int        width  = 0);

      /** Sums @p values over the ranks, in place. Exact where at most one
       *  rank holds a non-zero entry (the per-chunk sums). */
      void
      sum(std::vector<double> &values) const;

      /** The largest @p value over the ranks (exact). */
      double
      max(const double value) const;

      /** Bytes sent by this rank in ghost exchanges, all steps so far. */
      std::uint64_t
      ghost_bytes_sent() const
      {
        return ghost_bytes;
      }
      /** Bytes this rank contributed to synchronisations so far, the
       *  exchanges of a contact search included (joints' status, regions,
       *  candidates, new ghosts, cross-rank pairs) and the gathers of the
       *  whole pair list. */
      std::uint64_t
      synchronisation_bytes_sent() const
      {
        return sync_bytes;
      }
      /** Full synchronisations so far. */
      unsigned long
      n_synchronisations() const
      {
        return synchronisations;
      }
      /** Wall time this rank spent in exchanges, reductions and
       *  synchronisations so far (waits for other ranks included) [s]. */
      double
      communication_time() const
      {
        return communication_seconds;
      }
      /** Ghost triangles of this rank in the current plan. */
      unsigned int
      n_ghosts() const;

    private:
      MPI_Comm     communicator = MPI_COMM_SELF;
      unsigned int this_rank = 0, n_ranks = 1;
      /** Triangles per chunk (setup()). */
      unsigned int chunk_elements = 1;
      /** First triangle of every rank, and n_elements at the end. */
      std::vector<unsigned int> element_begin;
      /** First joint of every rank (joints are numbered by their first
       *  triangle), and n_joints at the end. */
      std::vector<unsigned int> joint_begin;
      JointSubset               joint_subset;

      /** One neighbouring rank of the ghost plan. */
      struct Neighbour
      {
        unsigned int              rank = 0;
        std::vector<unsigned int> send_elements, receive_elements;
        std::vector<double>       send_buffer, receive_buffer;
      };
      std::vector<Neighbour> neighbours;
      /** The neighbours of the previous plan (exchange_new_ghosts()). */
      std::vector<Neighbour>   previous_neighbours;
      std::vector<MPI_Request> requests;

      std::uint64_t  ghost_bytes           = 0;
      std::uint64_t  sync_bytes            = 0;
      unsigned long  synchronisations      = 0;
      mutable double communication_seconds = 0.;
      /** The other ranks whose region met this rank's in the last
       *  exchange_search_candidates(), ascending (exchange_pairs()). */
      std::vector<unsigned int> region_partners;
      /** The status of this rank's joints [first_joint(), end_joint())
       *  as every rank holds it: as set up, or as last sent by
       *  synchronise() or synchronise_joint_status(). */
      std::vector<JointStatus> sent_status;
      /** Scratch of synchronise(). */
      std::vector<double> scratch;
      /** Entries per rank of a gathered array, and where each rank's block
       *  starts (block_layout()). */
      std::vector<int> counts, displacements;

      /** One exchange of the ghost plan: @p width values per triangle,
       *  written by @p pack(e, buffer) (returns the buffer advanced) for the
       *  owned triangles others need and read by @p unpack(e, buffer) for
       *  the ghosts (point-to-point, message tag @p tag). */
      template <typename Pack, typename Unpack>
      void
      exchange_with_neighbours(const unsigned int width,
                               const int          tag,
                               const Pack        &pack,
                               const Unpack      &unpack);
      /** Sets displacements from counts; returns the total count. */
      std::size_t
      block_layout();
      /** MPI_Allgatherv in place: every rank's block of @p buffer (laid
       *  out by block_layout(), this rank's block filled) to every rank;
       *  counts the bytes this rank sends. */
      template <typename T>
      void
      allgather_blocks(std::vector<T> &buffer, MPI_Datatype type);
    };
  } // namespace discrete
} // namespace tmfdem

#endif
