#include <deal.II/base/mpi.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <iostream>
#include <iterator>
#include <tmfdem/discrete/partition.h>

namespace tmfdem
{
  namespace discrete
  {
    namespace
    {
      /** Adds the wall time of its life to a counter [s]. */
      class CommunicationTimer
      {
      public:
        explicit CommunicationTimer(double &total)
          : total(total)
          , start(std::chrono::steady_clock::now())
        {}
        ~CommunicationTimer()
        {
          total += std::chrono::duration<double>(
                     std::chrono::steady_clock::now() - start)
                     .count();
        }

      private:
        double                               &total;
        std::chrono::steady_clock::time_point start;
      };

      /** Doubles per triangle in the ghost exchange: x, y, vx, vy of its
       *  three nodes. */
      constexpr unsigned int ghost_width = 12;
      /** Doubles per triangle in synchronise(): x, y, vx, vy of its three
       *  nodes and its stress (xx, yy, xy) (geometry only: not the stress). */
      constexpr unsigned int element_width = 15;
      /** Doubles per joint in synchronise(): status, damage at both Gauss
       *  points and break time (geometry only: status). The joint forces
       *  are not state (DiscreteModel::node_joint_force). */
      constexpr unsigned int joint_width = 4;
      /** Bits of a joint's status in synchronise_joint_status()'s words
       *  (JointStatus: 0 to 3); the joint's index takes the others. */
      constexpr unsigned int joint_status_bits = 2;

      /** Joint @p j and its status @p s as one 32-bit word. */
      inline std::uint32_t
      pack_joint_status(const unsigned int j, const JointStatus s)
      {
        static_assert(static_cast<unsigned int>(JointStatus::mixed) <
                        (1u << joint_status_bits),
                      "every JointStatus fits in joint_status_bits");
        return (static_cast<std::uint32_t>(j) << joint_status_bits) |
               static_cast<std::uint32_t>(s);
      }

      /** Writes x, y, vx, vy of the three nodes of triangle @p e to @p b
       *  and returns the position after them. */
      inline double *
      pack_nodes(const DiscreteModel &m, const unsigned int e, double *b)
      {
        for (unsigned int node = 3 * e; node < 3 * e + 3; ++node)
          {
            *b++ = m.x[node];
            *b++ = m.y[node];
            *b++ = m.vx[node];
            *b++ = m.vy[node];
          }
        return b;
      }

      /** Reads what pack_nodes() wrote into triangle @p e's nodes. */
      inline const double *
      unpack_nodes(DiscreteModel &m, const unsigned int e, const double *b)
      {
        for (unsigned int node = 3 * e; node < 3 * e + 3; ++node)
          {
            m.x[node]  = *b++;
            m.y[node]  = *b++;
            m.vx[node] = *b++;
            m.vy[node] = *b++;
          }
        return b;
      }

      /** Receives the next message with @p tag from rank @p source into
       *  @p buffer, sized to the message (its length unknown beforehand). */
      template <typename T>
      void
      receive_message(const MPI_Comm     communicator,
                      const int          source,
                      const int          tag,
                      const MPI_Datatype type,
                      std::vector<T>    &buffer)
      {
        MPI_Status status;
        AssertThrowMPI(MPI_Probe(source, tag, communicator, &status));
        int count = 0;
        AssertThrowMPI(MPI_Get_count(&status, type, &count));
        buffer.resize(count);
        AssertThrowMPI(MPI_Recv(buffer.data(),
                                count,
                                type,
                                source,
                                tag,
                                communicator,
                                MPI_STATUS_IGNORE));
      }
    } // namespace

    void
    ElementPartition::setup(MPI_Comm             comm,
                            const DiscreteModel &model,
                            const unsigned int   chunk_size)
    {
      communicator   = comm;
      chunk_elements = chunk_size;
      this_rank      = Utilities::MPI::this_mpi_process(comm);
      n_ranks        = Utilities::MPI::n_mpi_processes(comm);
      const std::size_t n_chunks =
        (model.n_elements + chunk_size - 1) / chunk_size;
      if (n_ranks > n_chunks && this_rank == 0)
        std::cerr << "[tmfdem] note: the discrete mesh has " << model.n_elements
                  << " triangles; each rank advances "
                  << "whole chunks of " << chunk_size << ", so " << n_chunks
                  << " of the " << n_ranks
                  << " MPI ranks do the work and the others wait (fewer "
                     "ranks, or a finer mesh, use them)\n";
      element_begin.assign(n_ranks + 1, model.n_elements);
      for (unsigned int r = 0; r < n_ranks; ++r)
        element_begin[r] = static_cast<unsigned int>(
          std::min<std::size_t>(model.n_elements,
                                (r * n_chunks / n_ranks) * chunk_size));
      // joints are made in the order of their first triangle
      // (DiscreteModel::build), so each rank's joints are a range too
      joint_begin.assign(n_ranks + 1, model.n_joints);
      unsigned int j = 0;
      for (unsigned int r = 0; r < n_ranks; ++r)
        {
          while (j < model.n_joints &&
                 model.joint_elements[2 * j] < element_begin[r])
            ++j;
          joint_begin[r] = j;
        }
      for (unsigned int k = 0; k + 1 < model.n_joints; ++k)
        Assert(model.joint_elements[2 * k] <= model.joint_elements[2 * k + 2],
               ExcInternalError());
      // every rank built the same model: the status of my joints is what
      // every rank holds (synchronise_joint_status() sends what changes)
      AssertThrow(model.n_joints <=
                    (std::uint64_t(1) << (32 - joint_status_bits)),
                  ExcMessage("more than 2^30 joints: the exchange of the "
                             "joints' status numbers them in 30 bits."));
      sent_status.assign(model.joint_status.begin() + joint_begin[this_rank],
                         model.joint_status.begin() +
                           joint_begin[this_rank + 1]);
      // this rank's joints, and the earlier ranks' joints to its triangles
      joint_subset.begin = joint_begin[this_rank];
      joint_subset.end   = joint_begin[this_rank + 1];
      joint_subset.others.clear();
      for (unsigned int k = 0; k < joint_subset.begin; ++k)
        if (owns(model.joint_elements[2 * k + 1]))
          joint_subset.others.push_back(k);
      neighbours.clear();
      previous_neighbours.clear();
      requests.clear();
    }

    unsigned int
    ElementPartition::owner(const unsigned int e) const
    {
      return static_cast<unsigned int>(
        std::upper_bound(element_begin.begin(), element_begin.end() - 1, e) -
        element_begin.begin() - 1);
    }

    unsigned int
    ElementPartition::n_ghosts() const
    {
      unsigned int n = 0;
      for (const auto &neighbour : neighbours)
        n += neighbour.receive_elements.size();
      return n;
    }

    void
    ElementPartition::build_ghost_plan(const DiscreteModel            &model,
                                       const std::vector<ContactPair> &pairs)
    {
      if (!distributed())
        return;
      // per other rank: what it needs of mine, what I need of it
      std::vector<std::vector<unsigned int>> send(n_ranks), receive(n_ranks);
      const auto couple = [&](const unsigned int a, const unsigned int b) {
        const unsigned int ra = owner(a), rb = owner(b);
        if (ra == rb)
          return;
        if (ra == this_rank)
          {
            send[rb].push_back(a);
            receive[rb].push_back(b);
          }
        else if (rb == this_rank)
          {
            send[ra].push_back(b);
            receive[ra].push_back(a);
          }
      };
      for (unsigned int j = 0; j < model.n_joints; ++j)
        if (model.joint_status[j] == JointStatus::intact)
          couple(model.joint_elements[2 * j], model.joint_elements[2 * j + 1]);
      for (const ContactPair &p : pairs)
        couple(p.first, p.second);
      previous_neighbours = std::move(neighbours);
      neighbours.clear();
      for (unsigned int r = 0; r < n_ranks; ++r)
        {
          if (send[r].empty() && receive[r].empty())
            continue;
          Neighbour n;
          n.rank = r;
          for (auto *list : {&send[r], &receive[r]})
            {
              std::sort(list->begin(), list->end());
              list->erase(std::unique(list->begin(), list->end()), list->end());
            }
          n.send_elements    = std::move(send[r]);
          n.receive_elements = std::move(receive[r]);
          n.send_buffer.resize(ghost_width * n.send_elements.size());
          n.receive_buffer.resize(ghost_width * n.receive_elements.size());
          neighbours.push_back(std::move(n));
        }
      requests.resize(2 * neighbours.size());
    }

    template <typename Pack, typename Unpack>
    void
    ElementPartition::exchange_with_neighbours(const unsigned int width,
                                               const int          tag,
                                               const Pack        &pack,
                                               const Unpack      &unpack)
    {
      CommunicationTimer timer(communication_seconds);
      for (std::size_t i = 0; i < neighbours.size(); ++i)
        {
          Neighbour &n = neighbours[i];
          const int  receive_count =
            static_cast<int>(width * n.receive_elements.size());
          const int send_count =
            static_cast<int>(width * n.send_elements.size());
          AssertThrowMPI(MPI_Irecv(n.receive_buffer.data(),
                                   receive_count,
                                   MPI_DOUBLE,
                                   n.rank,
                                   tag,
                                   communicator,
                                   &requests[2 * i]));
          double *b = n.send_buffer.data();
          for (const unsigned int e : n.send_elements)
            b = pack(e, b);
          AssertThrowMPI(MPI_Isend(n.send_buffer.data(),
                                   send_count,
                                   MPI_DOUBLE,
                                   n.rank,
                                   tag,
                                   communicator,
                                   &requests[2 * i + 1]));
          ghost_bytes += sizeof(double) * send_count;
        }
      AssertThrowMPI(MPI_Waitall(static_cast<int>(requests.size()),
                                 requests.data(),
                                 MPI_STATUSES_IGNORE));
      for (const Neighbour &n : neighbours)
        {
          const double *b = n.receive_buffer.data();
          for (const unsigned int e : n.receive_elements)
            b = unpack(e, b);
        }
    }

    void
    ElementPartition::exchange_ghosts(DiscreteModel &m)
    {
      if (!distributed())
        return;
      exchange_with_neighbours(
        ghost_width,
        4711,
        [&](const unsigned int e, double *b) { return pack_nodes(m, e, b); },
        [&](const unsigned int e, const double *b) {
          return unpack_nodes(m, e, b);
        });
    }

    void
    ElementPartition::exchange_ghost_node_values(double *values)
    {
      if (!distributed())
        return;
      // the buffers hold ghost_width >= 3 values per triangle
      exchange_with_neighbours(
        3,
        4713,
        [&](const unsigned int e, double *b) {
          for (unsigned int k = 0; k < 3; ++k)
            *b++ = values[3 * e + k];
          return b;
        },
        [&](const unsigned int e, const double *b) {
          for (unsigned int k = 0; k < 3; ++k)
            values[3 * e + k] = *b++;
          return b;
        });
    }

    void
    ElementPartition::gather_element_values(double            *values,
                                            const unsigned int width)
    {
      if (!distributed())
        return;
      CommunicationTimer timer(communication_seconds);
      counts.assign(n_ranks, 0);
      for (unsigned int r = 0; r < n_ranks; ++r)
        counts[r] =
          static_cast<int>(width * (element_begin[r + 1] - element_begin[r]));
      block_layout();
      AssertThrowMPI(MPI_Allgatherv(MPI_IN_PLACE,
                                    0,
                                    MPI_DATATYPE_NULL,
                                    values,
                                    counts.data(),
                                    displacements.data(),
                                    MPI_DOUBLE,
                                    communicator));
      sync_bytes += sizeof(double) * counts[this_rank];
    }

    std::size_t
    ElementPartition::block_layout()
    {
      displacements.assign(n_ranks + 1, 0);
      for (unsigned int r = 0; r < n_ranks; ++r)
        displacements[r + 1] = displacements[r] + counts[r];
      return displacements[n_ranks];
    }

    template <typename T>
    void
    ElementPartition::allgather_blocks(std::vector<T> &buffer,
                                       MPI_Datatype    type)
    {
      AssertThrowMPI(MPI_Allgatherv(MPI_IN_PLACE,
                                    0,
                                    MPI_DATATYPE_NULL,
                                    buffer.data(),
                                    counts.data(),
                                    displacements.data(),
                                    type,
                                    communicator));
      sync_bytes += sizeof(T) * counts[this_rank];
    }

    void
    ElementPartition::synchronise(DiscreteModel &m, const bool geometry_only)
    {
      if (!distributed())
        return;
      CommunicationTimer timer(communication_seconds);
      // geometry: x, y, vx, vy of the nodes (new ghosts of the next plan
      // need their velocities too: friction) and the joints' status; else
      // all of element_width and joint_width
      const unsigned int per_element = geometry_only ? 12 : element_width;
      const unsigned int per_joint   = geometry_only ? 1 : joint_width;
      counts.assign(n_ranks, 0);
      for (unsigned int r = 0; r < n_ranks; ++r)
        counts[r] = static_cast<int>(
          per_element * (element_begin[r + 1] - element_begin[r]) +
          per_joint * (joint_begin[r + 1] - joint_begin[r]));
      scratch.resize(block_layout());
      // pack mine in place
      {
        double *b = scratch.data() + displacements[this_rank];
        for (unsigned int e = begin(); e < end(); ++e)
          {
            b = pack_nodes(m, e, b);
            if (!geometry_only)
              for (unsigned int c = 0; c < 3; ++c)
                *b++ = m.stress[3 * e + c];
          }
        for (unsigned int j = joint_begin[this_rank];
             j < joint_begin[this_rank + 1];
             ++j)
          {
            *b++ = static_cast<double>(m.joint_status[j]);
            // every rank gets it: what synchronise_joint_status() compares
            sent_status[j - joint_begin[this_rank]] = m.joint_status[j];
            if (geometry_only)
              continue;
            *b++ = m.joint_damage[2 * j];
            *b++ = m.joint_damage[2 * j + 1];
            *b++ = m.joint_break_time[j];
          }
      }
      allgather_blocks(scratch, MPI_DOUBLE);
      ++synchronisations;
      for (unsigned int r = 0; r < n_ranks; ++r)
        {
          if (r == this_rank)
            continue;
          const double *b = scratch.data() + displacements[r];
          for (unsigned int e = element_begin[r]; e < element_begin[r + 1]; ++e)
            {
              b = unpack_nodes(m, e, b);
              if (!geometry_only)
                for (unsigned int c = 0; c < 3; ++c)
                  m.stress[3 * e + c] = *b++;
            }
          for (unsigned int j = joint_begin[r]; j < joint_begin[r + 1]; ++j)
            {
              m.joint_status[j] =
                static_cast<JointStatus>(static_cast<int>(*b++));
              if (geometry_only)
                continue;
              m.joint_damage[2 * j]     = *b++;
              m.joint_damage[2 * j + 1] = *b++;
              m.joint_break_time[j]     = *b++;
            }
        }
    }

    void
    ElementPartition::synchronise_joint_status(DiscreteModel &m)
    {
      if (!distributed())
        return;
      CommunicationTimer timer(communication_seconds);
      // my joints whose status differs from what every rank holds (the
      // status I last sent), one 32-bit word each: index and status
      std::vector<std::uint32_t> changes;
      for (unsigned int j = first_joint(); j < end_joint(); ++j)
        {
          JointStatus &sent = sent_status[j - first_joint()];
          if (m.joint_status[j] != sent)
            {
              changes.push_back(pack_joint_status(j, m.joint_status[j]));
              sent = m.joint_status[j];
            }
        }
      const int n_changes = static_cast<int>(changes.size());
      counts.assign(n_ranks, 0);
      AssertThrowMPI(MPI_Allgather(&n_changes,
                                   1,
                                   MPI_INT,
                                   counts.data(),
                                   1,
                                   MPI_INT,
                                   communicator));
      sync_bytes += sizeof(n_changes);
      // every rank knows the total: none, no second message anywhere
      const std::size_t n_all = block_layout();
      if (n_all == 0)
        return;
      std::vector<std::uint32_t> all(n_all);
      std::copy(changes.begin(),
                changes.end(),
                all.begin() + displacements[this_rank]);
      allgather_blocks(all, MPI_UINT32_T);
      for (unsigned int r = 0; r < n_ranks; ++r)
        if (r != this_rank)
          for (int k = displacements[r]; k < displacements[r + 1]; ++k)
            {
              const unsigned int j = all[k] >> joint_status_bits;
              // a rank sends the joints of its first triangles only
              AssertThrow(j >= joint_begin[r] && j < joint_begin[r + 1],
                          ExcInternalError());
              m.joint_status[j] = static_cast<JointStatus>(
                all[k] & ((1u << joint_status_bits) - 1));
            }
    }

    void
    ElementPartition::exchange_search_candidates(
      DiscreteModel                   &m,
      const std::vector<unsigned int> &elements,
      const double                     buffer,
      std::vector<unsigned int>       &candidates,
      SearchExtent                    &extent)
    {
      Assert(distributed(), ExcInternalError());
      CommunicationTimer timer(communication_seconds);
      // the list is sorted and the same on every rank: my active triangles
      // are elements[mine_begin, mine_end)
      const std::size_t mine_begin =
        std::lower_bound(elements.begin(), elements.end(), begin()) -
        elements.begin();
      const std::size_t mine_end =
        std::lower_bound(elements.begin(), elements.end(), end()) -
        elements.begin();
      const std::size_t n_mine = mine_end - mine_begin;
      // the search boxes of my active triangles and their hull, my region
      std::vector<double> boxes(4 * n_mine);
      SearchExtent        region;
      for (std::size_t i = 0; i < n_mine; ++i)
        {
          const unsigned int e = elements[mine_begin + i];
          search_box(&m.x[3 * e], &m.y[3 * e], buffer, &boxes[4 * i]);
          region.add(&boxes[4 * i]);
        }
      // every rank's region and largest box side
      constexpr unsigned int width = 5;
      std::vector<double>    regions(width * n_ranks);
      {
        const double mine[width] = {region.lo[0],
                                    region.lo[1],
                                    region.hi[0],
                                    region.hi[1],
                                    region.largest};
        AssertThrowMPI(MPI_Allgather(mine,
                                     width,
                                     MPI_DOUBLE,
                                     regions.data(),
                                     width,
                                     MPI_DOUBLE,
                                     communicator));
        sync_bytes += sizeof(mine);
      }
      // the extent of all active triangles: minima and maxima are exact,
      // in any order
      extent            = SearchExtent();
      extent.n_elements = elements.size();
      for (unsigned int r = 0; r < n_ranks; ++r)
        {
          const double *R = &regions[width * r];
          extent.lo[0]    = std::min(extent.lo[0], R[0]);
          extent.lo[1]    = std::min(extent.lo[1], R[1]);
          extent.hi[0]    = std::max(extent.hi[0], R[2]);
          extent.hi[1]    = std::max(extent.hi[1], R[3]);
          extent.largest  = std::max(extent.largest, R[4]);
        }
      // pairs (a, b), a < b, are made by the owner of a: a rank sends to the
      // lower ranks whose region meets its own (an empty region, no active
      // triangle, meets none) and receives from the higher ones
      const double *my_region = &regions[width * this_rank];
      const auto    meets     = [&](const unsigned int r) {
        return boxes_overlap(&regions[width * r], my_region);
      };
      region_partners.clear();
      for (unsigned int r = 0; r < n_ranks; ++r)
        if (r != this_rank && meets(r))
          region_partners.push_back(r);
      constexpr int                    tag    = 4712;
      constexpr unsigned int           record = 1 + ghost_width; // index, nodes
      std::vector<std::vector<double>> send(this_rank);
      std::vector<MPI_Request>         send_requests;
      for (unsigned int r = 0; r < this_rank; ++r)
        if (meets(r))
          {
            const double *R = &regions[width * r];
            for (std::size_t i = 0; i < n_mine; ++i)
              if (boxes_overlap(&boxes[4 * i], R))
                {
                  const unsigned int e = elements[mine_begin + i];
                  send[r].resize(send[r].size() + record);
                  double *b = send[r].data() + send[r].size() - record;
                  *b++      = static_cast<double>(e);
                  pack_nodes(m, e, b);
                }
            send_requests.emplace_back();
            AssertThrowMPI(MPI_Isend(send[r].data(),
                                     static_cast<int>(send[r].size()),
                                     MPI_DOUBLE,
                                     r,
                                     tag,
                                     communicator,
                                     &send_requests.back()));
            sync_bytes += sizeof(double) * send[r].size();
          }
      // mine, then what the higher ranks send in rank order: sorted
      candidates.assign(elements.begin() + mine_begin,
                        elements.begin() + mine_end);
      std::vector<double> received;
      for (unsigned int r = this_rank + 1; r < n_ranks; ++r)
        if (meets(r))
          {
            receive_message(communicator, r, tag, MPI_DOUBLE, received);
            for (const double *b = received.data();
                 b < received.data() + received.size();)
              {
                const unsigned int e = static_cast<unsigned int>(*b++);
                AssertThrow(owner(e) == r && e < m.n_elements,
                            ExcInternalError());
                candidates.push_back(e);
                b = unpack_nodes(m, e, b);
              }
          }
      AssertThrowMPI(MPI_Waitall(static_cast<int>(send_requests.size()),
                                 send_requests.data(),
                                 MPI_STATUSES_IGNORE));
    }

    void
    ElementPartition::exchange_new_ghosts(DiscreteModel &m)
    {
      if (!distributed())
        return;
      CommunicationTimer timer(communication_seconds);
      const int          tag = 4713;
      // per neighbour: the triangles new to its send and receive lists
      // (both sides of a plan see the same lists, so they agree)
      std::vector<std::vector<unsigned int>> new_send(neighbours.size()),
        new_receive(neighbours.size());
      std::vector<std::vector<double>> send_data(neighbours.size()),
        receive_data(neighbours.size());
      std::vector<MPI_Request> new_requests;
      new_requests.reserve(2 * neighbours.size());
      for (std::size_t i = 0; i < neighbours.size(); ++i)
        {
          const Neighbour &n = neighbours[i];
          const auto       previous =
            std::find_if(previous_neighbours.begin(),
                         previous_neighbours.end(),
                         [&](const Neighbour &p) { return p.rank == n.rank; });
          static const std::vector<unsigned int> none;
          const auto &old_send    = previous == previous_neighbours.end() ?
                                      none :
                                      previous->send_elements;
          const auto &old_receive = previous == previous_neighbours.end() ?
                                      none :
                                      previous->receive_elements;
          std::set_difference(n.send_elements.begin(),
                              n.send_elements.end(),
                              old_send.begin(),
                              old_send.end(),
                              std::back_inserter(new_send[i]));
          std::set_difference(n.receive_elements.begin(),
                              n.receive_elements.end(),
                              old_receive.begin(),
                              old_receive.end(),
                              std::back_inserter(new_receive[i]));
          if (!new_receive[i].empty())
            {
              receive_data[i].resize(ghost_width * new_receive[i].size());
              new_requests.emplace_back();
              AssertThrowMPI(MPI_Irecv(receive_data[i].data(),
                                       static_cast<int>(receive_data[i].size()),
                                       MPI_DOUBLE,
                                       n.rank,
                                       tag,
                                       communicator,
                                       &new_requests.back()));
            }
          if (!new_send[i].empty())
            {
              send_data[i].resize(ghost_width * new_send[i].size());
              double *b = send_data[i].data();
              for (const unsigned int e : new_send[i])
                b = pack_nodes(m, e, b);
              new_requests.emplace_back();
              AssertThrowMPI(MPI_Isend(send_data[i].data(),
                                       static_cast<int>(send_data[i].size()),
                                       MPI_DOUBLE,
                                       n.rank,
                                       tag,
                                       communicator,
                                       &new_requests.back()));
              sync_bytes += sizeof(double) * send_data[i].size();
            }
        }
      AssertThrowMPI(MPI_Waitall(static_cast<int>(new_requests.size()),
                                 new_requests.data(),
                                 MPI_STATUSES_IGNORE));
      for (std::size_t i = 0; i < neighbours.size(); ++i)
        {
          const double *b = receive_data[i].data();
          for (const unsigned int e : new_receive[i])
            b = unpack_nodes(m, e, b);
        }
    }

    namespace
    {
      /** A pair's friction history is kept where any of its values has a
       *  bit set (-0 included). */
      inline bool
      sliding(const ContactPair &pair)
      {
        std::array<double, friction_history_values> values;
        std::memcpy(values.data(), pair.friction.data(), sizeof(values));
        bool any = false;
        for (const double s : values)
          any |= s != 0. || std::signbit(s);
        return any;
      }

      /** Appends @p n bytes of @p data to @p buffer. */
      inline void
      put_bytes(std::vector<unsigned char> &buffer,
                const void                 *data,
                const std::size_t           n)
      {
        const auto *bytes = static_cast<const unsigned char *>(data);
        buffer.insert(buffer.end(), bytes, bytes + n);
      }
    } // namespace

    void
    ElementPartition::exchange_pairs(std::vector<ContactPair> &pairs,
                                     const bool                by_regions)
    {
      if (!distributed())
        return;
      CommunicationTimer timer(communication_seconds);
      constexpr int      tag = 4714;
      // a pair (a, b), a < b, made here (a mine) goes to the owner of b
      // when that is another, higher, rank: per such rank the message
      // [n, (a, b) n times as 32-bit ids, (index, six edges' friction history)
      // per sliding pair], in bytes. The list is sorted by a, not by the owner
      // of b: one pass that fills every rank's message.
      std::vector<unsigned int> partners;
      if (by_regions)
        partners = region_partners;
      else
        for (unsigned int r = 0; r < n_ranks; ++r)
          if (r != this_rank)
            partners.push_back(r);
      const auto higher_begin =
        std::upper_bound(partners.begin(), partners.end(), this_rank);
      // per higher partner: ids, then the sliding records
      const std::size_t n_higher = partners.end() - higher_begin;
      std::vector<std::vector<std::uint32_t>> ids(n_higher);
      std::vector<std::vector<unsigned char>> records(n_higher);
      for (const ContactPair &pair : pairs)
        {
          const unsigned int r = owner(pair.second);
          if (r == this_rank)
            continue;
          const auto partner =
            std::lower_bound(higher_begin, partners.end(), r);
          // a higher rank whose region does not meet mine sent me no
          // candidate, so I made no pair with its triangles
          AssertThrow(partner != partners.end() && *partner == r,
                      ExcInternalError());
          const std::size_t   k = partner - higher_begin;
          const std::uint32_t index =
            static_cast<std::uint32_t>(ids[k].size() / 2);
          ids[k].push_back(pair.first);
          ids[k].push_back(pair.second);
          if (sliding(pair))
            {
              put_bytes(records[k], &index, sizeof(index));
              put_bytes(records[k],
                        pair.friction.data(),
                        sizeof(pair.friction));
            }
        }
      std::vector<std::vector<unsigned char>> send(n_higher);
      std::vector<MPI_Request>                send_requests(n_higher);
      for (std::size_t k = 0; k < n_higher; ++k)
        {
          const std::uint32_t n = static_cast<std::uint32_t>(ids[k].size() / 2);
          put_bytes(send[k], &n, sizeof(n));
          put_bytes(send[k], ids[k].data(), sizeof(std::uint32_t) * 2 * n);
          send[k].insert(send[k].end(), records[k].begin(), records[k].end());
          AssertThrowMPI(MPI_Isend(send[k].data(),
                                   static_cast<int>(send[k].size()),
                                   MPI_BYTE,
                                   *(higher_begin + k),
                                   tag,
                                   communicator,
                                   &send_requests[k]));
          sync_bytes += send[k].size();
        }
      // the pairs of the lower ranks with a second triangle here, in rank
      // order (their first triangles precede mine), then mine
      std::vector<ContactPair>   joined;
      std::vector<unsigned char> received;
      for (auto r = partners.begin(); r != higher_begin; ++r)
        {
          receive_message(communicator, *r, tag, MPI_BYTE, received);
          std::uint32_t n = 0;
          AssertThrow(received.size() >= sizeof(n), ExcInternalError());
          std::memcpy(&n, received.data(), sizeof(n));
          const std::size_t ids_end = sizeof(n) + sizeof(std::uint32_t) * 2 * n;
          constexpr std::size_t record =
            sizeof(std::uint32_t) + sizeof(ContactPair::friction);
          AssertThrow(received.size() >= ids_end &&
                        (received.size() - ids_end) % record == 0,
                      ExcInternalError());
          const std::size_t first = joined.size();
          joined.resize(first + n);
          for (std::size_t p = 0; p < n; ++p)
            {
              std::uint32_t id[2];
              std::memcpy(id,
                          received.data() + sizeof(n) + sizeof(id) * p,
                          sizeof(id));
              AssertThrow(owner(id[0]) == *r && owns(id[1]) && id[0] < id[1],
                          ExcInternalError());
              joined[first + p].first  = id[0];
              joined[first + p].second = id[1];
            }
          for (std::size_t b = ids_end; b < received.size(); b += record)
            {
              std::uint32_t index = 0;
              std::memcpy(&index, received.data() + b, sizeof(index));
              AssertThrow(index < n, ExcInternalError());
              std::memcpy(joined[first + index].friction.data(),
                          received.data() + b + sizeof(index),
                          sizeof(ContactPair::friction));
            }
        }
      joined.insert(joined.end(), pairs.begin(), pairs.end());
      pairs.swap(joined);
      AssertThrowMPI(MPI_Waitall(static_cast<int>(send_requests.size()),
                                 send_requests.data(),
                                 MPI_STATUSES_IGNORE));
    }

    void
    ElementPartition::gather_pairs(std::vector<ContactPair> &pairs,
                                   std::vector<double>      *values,
                                   const unsigned int        width)
    {
      if (!distributed())
        return;
      CommunicationTimer timer(communication_seconds);
      // most candidate pairs are not touching and have no friction history:
      // the pairs go as two 32-bit ids (8 B), and only the pairs with a
      // friction history (any bit set, -0 included) add their index and the
      // six edges' slip, strength and remembered rate
      std::vector<std::uint32_t> ids(2 * pairs.size());
      std::vector<double>        histories;
      for (std::size_t p = 0; p < pairs.size(); ++p)
        {
          ids[2 * p]     = pairs[p].first;
          ids[2 * p + 1] = pairs[p].second;
          if (sliding(pairs[p]))
            {
              histories.push_back(static_cast<double>(p));
              histories.resize(histories.size() + friction_history_values);
              std::memcpy(histories.data() + histories.size() -
                            friction_history_values,
                          pairs[p].friction.data(),
                          sizeof(pairs[p].friction));
            }
        }
      // one rank's block of a gathered array, by rank
      const auto gather = [this](const auto &mine, auto &all, MPI_Datatype t) {
        const int count = static_cast<int>(mine.size());
        counts.assign(n_ranks, 0);
        AssertThrowMPI(MPI_Allgather(&count,
                                     1,
                                     MPI_INT,
                                     counts.data(),
                                     1,
                                     MPI_INT,
                                     communicator));
        all.resize(block_layout());
        std::copy(mine.begin(),
                  mine.end(),
                  all.begin() + displacements[this_rank]);
        allgather_blocks(all, t);
        return displacements;
      };
      std::vector<std::uint32_t> all_ids;
      const std::vector<int> id_offsets = gather(ids, all_ids, MPI_UINT32_T);
      scratch.clear();
      const std::vector<int> history_offsets =
        gather(histories, scratch, MPI_DOUBLE);
      pairs.assign(all_ids.size() / 2, ContactPair());
      for (std::size_t p = 0; p < pairs.size(); ++p)
        {
          pairs[p].first  = all_ids[2 * p];
          pairs[p].second = all_ids[2 * p + 1];
        }
      constexpr unsigned int record = 1 + friction_history_values; // index
      for (unsigned int r = 0; r < n_ranks; ++r)
        for (int k = history_offsets[r]; k < history_offsets[r + 1];
             k += record)
          {
            ContactPair &pair =
              pairs[id_offsets[r] / 2 + static_cast<std::size_t>(scratch[k])];
            std::memcpy(pair.friction.data(),
                        &scratch[k + 1],
                        sizeof(pair.friction));
          }
      if (values != nullptr)
        {
          // the values likewise: most pairs carry none (not touching), so
          // only the pairs with any bit set go, as index and values
          Assert(values->size() == width * ids.size() / 2, ExcInternalError());
          std::vector<double> sparse;
          for (std::size_t p = 0; p < ids.size() / 2; ++p)
            {
              const double *v   = values->data() + width * p;
              bool          any = false;
              for (unsigned int i = 0; i < width; ++i)
                any |= v[i] != 0. || std::signbit(v[i]);
              if (any)
                {
                  sparse.push_back(static_cast<double>(p));
                  sparse.insert(sparse.end(), v, v + width);
                }
            }
          std::vector<double>    all;
          const std::vector<int> value_offsets =
            gather(sparse, all, MPI_DOUBLE);
          values->assign(width * pairs.size(), 0.);
          for (unsigned int r = 0; r < n_ranks; ++r)
            for (int k = value_offsets[r]; k < value_offsets[r + 1];
                 k += 1 + width)
              std::copy(all.begin() + k + 1,
                        all.begin() + k + 1 + width,
                        values->begin() +
                          width * (id_offsets[r] / 2 +
                                   static_cast<std::size_t>(all[k])));
        }
    }

    void
    ElementPartition::sum(std::vector<double> &values) const
    {
      if (!distributed() || values.empty())
        return;
      CommunicationTimer timer(communication_seconds);
      AssertThrowMPI(MPI_Allreduce(MPI_IN_PLACE,
                                   values.data(),
                                   static_cast<int>(values.size()),
                                   MPI_DOUBLE,
                                   MPI_SUM,
                                   communicator));
    }

    double
    ElementPartition::max(const double value) const
    {
      if (!distributed())
        return value;
      CommunicationTimer timer(communication_seconds);
      return Utilities::MPI::max(value, communicator);
    }
  } // namespace discrete
} // namespace tmfdem
