#include <algorithm>
#include <cmath>
#include <cstdint>
#include <string>
#include <tmfdem/base/exceptions.h>
#include <tmfdem/discrete/tetrahedron_contact_system.h>
#include <tmfdem/io/checkpoint.h>

namespace tmfdem
{
  namespace discrete
  {
    namespace
    {
      /** The potential of a pair of normal contact energy @p E with the
       *  offset @p E0 [J]: (E - E0)^2 / E above the offset, 0 at or below
       *  it. */
      double
      offset_energy(const double E, const double E0)
      {
        return E > E0 ? (E - E0) * (E - E0) / E : 0.;
      }

      /** Its derivative with respect to E above the offset, 1 - (E0 /
       *  E)^2: the factor on the normal forces of E [-]. */
      double
      offset_force_factor(const double E, const double E0)
      {
        return 1. - (E0 / E) * (E0 / E);
      }
    } // namespace

    void
    TetrahedronContactSystem::setup(
      const ContactSettings            &settings,
      const std::vector<unsigned char> &rigid_groups)
    {
      contact     = settings;
      rigid_group = rigid_groups;
      pair_list.clear();
      pair_energy_offset.clear();
      handed_over = 0.;
      index_pairs(static_cast<unsigned int>(rigid_group.size()));
      reset(settings.buffer);
      searches = 0;
    }

    double
    TetrahedronContactSystem::node_stiffness_bound(
      const double (&x)[4][3]) const
    {
      if (!contact.enabled)
        return 0.;
      double g[4][3];
      scaled_gradients(x, g);
      // |g_f| = 2 A_f; 6 V = g_3 . (x_3 - x_0); H_f = 3 V / A_f
      double six_volume = 0., largest_area = 0.;
      for (unsigned int i = 0; i < 3; ++i)
        six_volume += g[3][i] * (x[3][i] - x[0][i]);
      for (unsigned int f = 0; f < 4; ++f)
        largest_area =
          std::max(largest_area,
                   0.5 * std::sqrt(g[f][0] * g[f][0] + g[f][1] * g[f][1] +
                                   g[f][2] * g[f][2]));
      if (!(six_volume > 0.))
        return 0.;
      const double smallest_altitude   = 0.5 * six_volume / largest_area;
      const PenaltyCoulombContact &law = contact.penalty_coulomb;
      return 4. * law.normal_penalty * largest_area / smallest_altitude +
             law.tangential_penalty * std::sqrt(largest_area);
    }

    double
    TetrahedronContactSystem::face_penalty_factor(const DiscreteModel &model,
                                                  const unsigned int   a,
                                                  const unsigned int   b,
                                                  const double         penalty)
    {
      const int j = model.joint_between(a, b);
      if (j < 0)
        return 1.;
      // E_joint = k_n / 2 int o^2 dA, E_contact = 2 p (1 / H_a + 1 / H_b)
      // int o^2 dA, H = 3 V / A the altitudes onto the face
      const double A = model.joint_area[j];
      const double inverse_altitudes =
        A / 3. * (1. / model.reference_area[a] + 1. / model.reference_area[b]);
      return std::min(1.,
                      model.joint_constants[j].normal_stiffness /
                        (4. * penalty * inverse_altitudes));
    }

    void
    TetrahedronContactSystem::update_active_elements(const DiscreteModel &model)
    {
      model.contact_candidate_elements(active);
    }

    void
    TetrahedronContactSystem::search(const DiscreteModel &model,
                                     tbb::task_arena     &arena)
    {
      continuity.update(model);
      const auto skip = [&](const unsigned int a, const unsigned int b) {
        return model.joined(a, b) || continuity.continuous(a, b);
      };
      // the pairs of the last search (sorted), to carry their offsets over
      std::vector<std::uint64_t> previous(pair_list.size());
      const auto                 key = [](const TetrahedronContactPair &pair) {
        return (static_cast<std::uint64_t>(pair.first) << 32) | pair.second;
      };
      for (std::size_t p = 0; p < pair_list.size(); ++p)
        previous[p] = key(pair_list[p]);
      const std::vector<double>        previous_offset = pair_energy_offset;
      const std::vector<double> *const coordinates[3]  = {&model.x,
                                                          &model.y,
                                                          &model.z};
      linked_cells
        .rebuild(coordinates, active, contact.buffer, skip, pair_list, arena);
      // the boxes are coarse for tetrahedra: drop the pairs that a plane
      // separates by more than the buffer (they cannot meet before the next
      // search, and the pairs between nearby tetrahedra of one intact body
      // are most of the boxes' candidates)
      std::vector<char> far(pair_list.size(), 0);
      for_each_chunk(
        arena,
        pair_list.size(),
        64,
        [&](const std::size_t begin, const std::size_t end, const std::size_t) {
          for (std::size_t p = begin; p < end; ++p)
            {
              double x[2][4][3];
              gather_positions(model, pair_list[p], x);
              far[p] = tetrahedra_apart_by_more_than(x, contact.buffer);
            }
        });
      std::size_t kept = 0;
      for (std::size_t p = 0; p < pair_list.size(); ++p)
        if (!far[p])
          pair_list[kept++] = pair_list[p];
      pair_list.resize(kept);
      index_pairs(model.n_elements);
      pair_penalty_factor.assign(pair_list.size(), 1.);
      if (contact.match_broken_joints)
        for (std::size_t p = 0; p < pair_list.size(); ++p)
          pair_penalty_factor[p] =
            face_penalty_factor(model,
                                pair_list[p].first,
                                pair_list[p].second,
                                contact.penalty_coulomb.normal_penalty);
      // energy offsets: kept for pairs found again; a new pair that is not
      // the two faces of a joint brings the energy it has now (0 unless a
      // crack has just parted two corners of one piece that overlapped); the
      // two faces of a joint broken since the last search bring theirs into
      // the contact (handed_over)
      enum : char
      {
        found_again,
        new_pair,
        new_joint_faces
      };
      pair_energy_offset.assign(pair_list.size(), 0.);
      std::vector<char> kind(pair_list.size(), found_again);
      std::size_t       old = 0;
      for (std::size_t p = 0; p < pair_list.size(); ++p)
        {
          const std::uint64_t k = key(pair_list[p]);
          while (old < previous.size() && previous[old] < k)
            ++old;
          if (old < previous.size() && previous[old] == k)
            pair_energy_offset[p] = previous_offset[old];
          else if (searches > 0 && !pair_is_rigid[p])
            kind[p] =
              model.joint_between(pair_list[p].first, pair_list[p].second) < 0 ?
                new_pair :
                new_joint_faces;
        }
      std::vector<double> energy_now(pair_list.size(), 0.);
      for_each_chunk(arena,
                     pair_list.size(),
                     64,
                     [&](const std::size_t begin,
                         const std::size_t end,
                         const std::size_t) {
                       for (std::size_t p = begin; p < end; ++p)
                         if (kind[p] != found_again)
                           {
                             double x[2][4][3];
                             gather_positions(model, pair_list[p], x);
                             energy_now[p] = pair_contact_energy_3d(
                               x,
                               contact.penalty_coulomb.normal_penalty *
                                 pair_penalty_factor[p]);
                           }
                     });
      for (std::size_t p = 0; p < pair_list.size(); ++p)
        if (kind[p] == new_pair)
          pair_energy_offset[p] = energy_now[p];
        else if (kind[p] == new_joint_faces)
          handed_over += energy_now[p];
      searched();
      ++searches;
    }

    void
    TetrahedronContactSystem::index_pairs(const unsigned int n_elements)
    {
      pair_is_rigid.resize(pair_list.size());
      for (std::size_t p = 0; p < pair_list.size(); ++p)
        {
          const unsigned char a = rigid_group[pair_list[p].first];
          // no force within one rigid group
          pair_is_rigid[p] =
            a != no_body && a == rigid_group[pair_list[p].second];
        }
      pair_force.assign(24 * pair_list.size(), 0.);
      pair_friction.assign(pair_list.size(), 0.);
      // a pair found again keeps its friction history: reset it at the
      // first compute_forces() that finds its boxes apart
      pair_active.assign(pair_list.size(), 1);
      element_pair_start.assign(n_elements + 1, 0);
      first_pair_start.assign(n_elements + 1, 0);
      for (std::size_t p = 0; p < pair_list.size(); ++p)
        {
          ++first_pair_start[pair_list[p].first + 1];
          if (pair_is_rigid[p])
            continue;
          ++element_pair_start[pair_list[p].first + 1];
          ++element_pair_start[pair_list[p].second + 1];
        }
      for (unsigned int e = 0; e < n_elements; ++e)
        {
          element_pair_start[e + 1] += element_pair_start[e];
          first_pair_start[e + 1] += first_pair_start[e];
        }
      element_pair_entries.resize(element_pair_start[n_elements]);
      std::vector<unsigned int> fill(element_pair_start.begin(),
                                     element_pair_start.end() - 1);
      for (unsigned int p = 0; p < pair_list.size(); ++p)
        if (!pair_is_rigid[p])
          {
            element_pair_entries[fill[pair_list[p].first]++]  = 2 * p;
            element_pair_entries[fill[pair_list[p].second]++] = 2 * p + 1;
          }
    }

    void
    TetrahedronContactSystem::gather_positions(const DiscreteModel &m,
                                               const unsigned int   e,
                                               double (&x)[4][3])
    {
      for (unsigned int k = 0; k < 4; ++k)
        {
          const unsigned int node = 4 * e + k;
          x[k][0]                 = m.x[node];
          x[k][1]                 = m.y[node];
          x[k][2]                 = m.z[node];
        }
    }

    void
    TetrahedronContactSystem::gather_velocities(const DiscreteModel &m,
                                                const unsigned int   e,
                                                double (&v)[4][3])
    {
      for (unsigned int k = 0; k < 4; ++k)
        {
          const unsigned int node = 4 * e + k;
          v[k][0]                 = m.vx[node];
          v[k][1]                 = m.vy[node];
          v[k][2]                 = m.vz[node];
        }
    }

    void
    TetrahedronContactSystem::gather_positions(
      const DiscreteModel          &m,
      const TetrahedronContactPair &pair,
      double (&x)[2][4][3])
    {
      gather_positions(m, pair.first, x[0]);
      gather_positions(m, pair.second, x[1]);
    }

    void
    TetrahedronContactSystem::compute_forces(const DiscreteModel &m,
                                             const double         dt,
                                             tbb::task_arena     &arena)
    {
      if (pair_list.empty())
        return;
      for_each_chunk(
        arena,
        pair_list.size(),
        64,
        [&](const std::size_t begin, const std::size_t end, const std::size_t) {
          PenaltyCoulombContact law = contact.penalty_coulomb;
          for (std::size_t p = begin; p < end; ++p)
            {
              if (pair_is_rigid[p]) // its forces stay the +0 of index_pairs()
                continue;
              TetrahedronContactPair &pair  = pair_list[p];
              double                 *force = &pair_force[24 * p];
              double                  x[2][4][3], v[2][4][3];
              gather_positions(m, pair, x);
              if (!tetrahedron_boxes_overlap(x))
                {
                  // apart: no force, no dissipation, the friction history
                  // reset, the energy offset 0 (E = 0), as the full path
                  // below gives; done once, then skipped while apart
                  if (pair_active[p] != 0)
                    {
                      std::fill(force, force + 24, 0.);
                      pair_friction[p] = 0.;
                      pair.friction    = TetrahedronPairFriction();
                      pair_active[p]   = 0;
                    }
                  if (pair_energy_offset[p] != 0.)
                    pair_energy_offset[p] = 0.;
                  continue;
                }
              pair_active[p] = 1;
              std::fill(force, force + 24, 0.);
              pair_friction[p] = 0.;
              // the faces of a broken joint: its compressive stiffness
              law.normal_penalty =
                contact.penalty_coulomb.normal_penalty * pair_penalty_factor[p];
              // touching or apart (most pairs whose boxes meet): no force
              // and the friction reset below, the velocities not needed
              TetrahedronCoordinates coordinates[2];
              const bool overlap = tetrahedra_overlap(x, coordinates);
              if (pair_energy_offset[p] > 0.)
                {
                  // potential (E - E_0)^2 / E above the offset, 0 below it
                  // (the offset follows E down): the normal forces of E
                  // times 1 - (E_0 / E)^2, which starts from 0
                  const double energy =
                    pair_contact_energy_3d(x, law.normal_penalty);
                  if (energy <= pair_energy_offset[p])
                    {
                      pair_energy_offset[p] = energy;
                      pair.friction         = TetrahedronPairFriction();
                      continue;
                    }
                  law.normal_penalty *=
                    offset_force_factor(energy, pair_energy_offset[p]);
                }
              if (!overlap)
                {
                  pair.friction = TetrahedronPairFriction();
                  continue;
                }
              gather_velocities(m, pair.first, v[0]);
              gather_velocities(m, pair.second, v[1]);
              pair_friction[p] = add_overlapping_pair_forces_3d(x,
                                                                coordinates,
                                                                v,
                                                                law,
                                                                dt,
                                                                pair.friction,
                                                                force);
            }
        });
    }

    TetrahedronContactSystem::Overlap
    TetrahedronContactSystem::largest_overlap(const DiscreteModel &m) const
    {
      Overlap largest;
      if (pair_list.empty())
        return largest;
      std::vector<unsigned int> piece;
      m.intact_pieces(piece);
      for (std::size_t p = 0; p < pair_list.size(); ++p)
        {
          const unsigned int a = pair_list[p].first, b = pair_list[p].second;
          if (pair_is_rigid[p] ||
              (rigid_group[a] != no_body && rigid_group[b] != no_body) ||
              piece[a] == piece[b])
            continue;
          double x[2][4][3];
          gather_positions(m, pair_list[p], x);
          TetrahedronCoordinates target;
          if (!target.set(x[1]))
            continue;
          const double volume = overlap_volume_3d(x[0], target);
          const double fraction =
            volume / std::min(m.reference_area[a], m.reference_area[b]);
          if (fraction > largest.fraction)
            largest = Overlap{fraction, volume, a, b};
        }
      return largest;
    }

    unsigned int
    TetrahedronContactSystem::n_mechanical_pairs() const
    {
      return static_cast<unsigned int>(
        std::count(pair_is_rigid.begin(), pair_is_rigid.end(), 0));
    }

    double
    TetrahedronContactSystem::stored_energy(const DiscreteModel &m,
                                            tbb::task_arena     &arena) const
    {
      constexpr std::size_t chunk = 64;
      std::vector<double>   chunk_energy((pair_list.size() + chunk - 1) / chunk,
                                       0.);
      for_each_chunk(
        arena,
        pair_list.size(),
        chunk,
        [&](const std::size_t begin,
            const std::size_t end,
            const std::size_t c) {
          double energy = 0.;
          for (std::size_t p = begin; p < end; ++p)
            {
              if (pair_is_rigid[p])
                continue;
              double x[2][4][3];
              gather_positions(m, pair_list[p], x);
              energy += offset_energy(
                pair_contact_energy_3d(x,
                                       contact.penalty_coulomb.normal_penalty *
                                         pair_penalty_factor[p]),
                pair_energy_offset[p]);
            }
          chunk_energy[c] = energy;
        });
      double energy = 0.;
      for (const double e : chunk_energy)
        energy += e;
      return energy;
    }

    void
    TetrahedronContactSystem::save(CheckpointWriter &out) const
    {
      ContactTravel::save(out);
      out.put<std::uint64_t>(searches);
      out.put(pair_list);
      out.put(pair_penalty_factor);
      out.put(pair_energy_offset);
      out.put(handed_over);
    }

    void
    TetrahedronContactSystem::load(CheckpointReader  &in,
                                   const unsigned int n_elements)
    {
      ContactTravel::load(in);
      std::uint64_t count = 0;
      in.get(count);
      searches = count;
      in.get(pair_list);
      in.get(pair_penalty_factor);
      in.get(pair_energy_offset);
      in.get(handed_over);
      for (const auto &p : pair_list)
        if (p.first >= n_elements || p.second >= n_elements)
          throw InputError("the checkpoint '" + in.name() +
                           "' is corrupt (contact pair of tetrahedron " +
                           std::to_string(std::max(p.first, p.second)) + ").");
      if (pair_penalty_factor.size() != pair_list.size() ||
          pair_energy_offset.size() != pair_list.size())
        throw InputError("the checkpoint '" + in.name() +
                         "' is corrupt (contact pairs and their penalties "
                         "or energy offsets differ in number).");
      index_pairs(n_elements);
    }
  } // namespace discrete
} // namespace tmfdem
