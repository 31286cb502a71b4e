#include <algorithm>
#include <string>
#include <tmfdem/base/exceptions.h>
#include <tmfdem/discrete/contact_system.h>
#include <tmfdem/discrete/discrete_parameters.h>
#include <tmfdem/discrete/triangle_overlap.h>
#include <tmfdem/io/checkpoint.h>

namespace tmfdem
{
  namespace discrete
  {
    ContactSettings
    make_contact_settings(const DiscreteMechanicsParameters &dm,
                          const double                       youngs_modulus,
                          const double                       smallest_size)
    {
      ContactSettings settings;
      settings.enabled           = dm.contact;
      settings.law               = ContactLaw::penalty_coulomb;
      PenaltyCoulombContact &law = settings.penalty_coulomb;
      law.normal_penalty         = dm.contact_penalty_factor * youngs_modulus;
      law.tangential_penalty =
        dm.contact_tangential_penalty_factor * youngs_modulus;
      law.friction            = dm.friction_coefficient;
      law.memory_slip         = dm.friction_memory_slip;
      law.rate_effect         = dm.friction_rate_effect;
      law.reference_slip_rate = dm.friction_reference_slip_rate;
      law.potential_gradient_on_target =
        dm.contact_potential_gradient_on_target;
      settings.match_broken_joints = dm.contact_broken_faces_at_joint_stiffness;
      settings.buffer =
        dm.contact_buffer > 0. ? dm.contact_buffer : 0.25 * smallest_size;
      return settings;
    }

    void
    ContactTravel::save(CheckpointWriter &out) const
    {
      out.put(travel_since_search);
      out.put<std::uint8_t>(search_is_needed);
    }

    void
    ContactTravel::load(CheckpointReader &in)
    {
      in.get(travel_since_search);
      std::uint8_t flag = 0;
      in.get(flag);
      search_is_needed = flag != 0;
    }

    void
    ContactSystem::setup(const ContactSettings            &settings,
                         const std::vector<unsigned char> &rigid_groups)
    {
      contact     = settings;
      rigid_group = rigid_groups;
      pair_list.clear();
      index_pairs(0);
      reset(settings.buffer);
      searches = 0;
    }

    double
    ContactSystem::node_stiffness_bound() const
    {
      if (!contact.enabled)
        return 0.;
      switch (contact.law)
        {
          case ContactLaw::penalty_coulomb:
            return contact.penalty_coulomb.node_stiffness_bound();
        }
      return 0.;
    }

    double
    ContactSystem::face_penalty_factor(const DiscreteModel &model,
                                       const unsigned int   a,
                                       const unsigned int   b,
                                       const double         penalty)
    {
      const int j = model.joint_between(a, b);
      if (j < 0)
        return 1.;
      // E_joint = k_n / 2 int o^2 ds, E_contact = 3 p / 2
      // (1 / H_a + 1 / H_b) int o^2 ds, H = 2 A / L the altitudes
      const double L = model.joint_length[j];
      const double inverse_altitudes =
        0.5 * L * (1. / model.reference_area[a] + 1. / model.reference_area[b]);
      return std::min(1.,
                      model.joint_constants[j].normal_stiffness /
                        (3. * penalty * inverse_altitudes));
    }

    void
    ContactSystem::update_active_elements(const DiscreteModel &model)
    {
      model.contact_candidate_elements(active_elements);
    }

    void
    ContactSystem::search(const DiscreteModel             &model,
                          tbb::task_arena                 &arena,
                          ElementPartition                &partition,
                          const std::vector<unsigned int> *candidates,
                          const SearchExtent              *extent)
    {
      const auto skip = [&](const unsigned int a, const unsigned int b) {
        return model.joined(a, b);
      };
      Assert((candidates == nullptr) == (extent == nullptr),
             ExcInternalError());
      linked_cells.rebuild(model.x,
                           model.y,
                           candidates != nullptr ? *candidates :
                                                   active_elements,
                           contact.buffer,
                           skip,
                           pair_list,
                           arena,
                           partition.begin(),
                           partition.end(),
                           extent);
      // each rank keeps the pairs with a triangle of its own (partition.h)
      partition.exchange_pairs(pair_list, candidates != nullptr);
      index_pairs(model.n_elements);
      flag_rigid_pairs();
      searched();
      ++searches;
      local_pairs_of_search = 0;
      all_pairs_of_search   = 0;
    }

    const std::vector<ContactPair> &
    ContactSystem::all_pairs(const ElementPartition &partition) const
    {
      return partition.distributed() ? all_pair_list : pair_list;
    }

    void
    ContactSystem::gather_all_pairs(ElementPartition &partition)
    {
      if (!partition.distributed() || all_pairs_of_search == searches + 1)
        return;
      all_pair_list.clear();
      for (const ContactPair &p : pair_list)
        if (partition.owns(p.first))
          all_pair_list.push_back(p);
      partition.gather_pairs(all_pair_list);
      all_pairs_of_search = searches + 1;
    }

    void
    ContactSystem::flag_rigid_pairs()
    {
      pair_is_rigid.resize(pair_list.size());
      for (std::size_t p = 0; p < pair_list.size(); ++p)
        {
          const unsigned char a = rigid_group[pair_list[p].first];
          pair_is_rigid[p] =
            a != no_body && a == rigid_group[pair_list[p].second];
        }
    }

    ContactSystem::Overlap
    ContactSystem::largest_overlap(const DiscreteModel &model) const
    {
      Overlap largest;
      if (pair_list.empty())
        return largest;
      // the pieces (triangles connected by intact joints): two triangles of
      // one piece that overlap are crushed, not in failed contact (the
      // guards on inverted elements and the stable step report that)
      std::vector<unsigned int> piece;
      model.intact_pieces(piece);
      OverlapPolygon polygon;
      for (std::size_t p = 0; p < pair_list.size(); ++p)
        {
          const unsigned int a = pair_list[p].first, b = pair_list[p].second;
          // no force within one rigid group, none between two bodies that
          // do not move (fixed or driven)
          if (pair_is_rigid[p] ||
              (rigid_group[a] != no_body && rigid_group[b] != no_body) ||
              piece[a] == piece[b])
            continue;
          if (!triangle_overlap(&model.x[3 * a],
                                &model.y[3 * a],
                                &model.x[3 * b],
                                &model.y[3 * b],
                                polygon))
            continue;
          const double fraction =
            polygon.area /
            std::min(model.reference_area[a], model.reference_area[b]);
          if (fraction > largest.fraction)
            largest = Overlap{fraction, polygon.area, a, b};
        }
      return largest;
    }

    unsigned int
    ContactSystem::n_mechanical_pairs(const ElementPartition &partition) const
    {
      // each pair counted by the owner of its first triangle
      unsigned int n = 0;
      for (std::size_t p = 0; p < pair_list.size(); ++p)
        if (!pair_is_rigid[p] && partition.owns(pair_list[p].first))
          ++n;
      std::vector<double> count(1, n);
      partition.sum(count); // exact: integers
      return static_cast<unsigned int>(count[0]);
    }

    double
    ContactSystem::stored_energy(const DiscreteModel    &model,
                                 const ElementPartition &partition) const
    {
      // per chunk of triangles (of the pairs' first triangles), each chunk
      // on one rank, added in chunk order: the same on any number of ranks
      const unsigned int  chunk = partition.chunk_size();
      std::vector<double> chunk_energy((model.n_elements + chunk - 1) / chunk,
                                       0.);
      const double        penalty = contact.penalty_coulomb.normal_penalty;
      std::vector<double> scratch(6);
      for (std::size_t p = 0; p < pair_list.size(); ++p)
        {
          const ContactPair &pair = pair_list[p];
          if (pair_is_rigid[p] || !partition.owns(pair.first))
            continue;
          const double pair_penalty =
            penalty *
            (contact.match_broken_joints ?
               face_penalty_factor(model, pair.first, pair.second, penalty) :
               1.);
          const double *ax = &model.x[3 * pair.first];
          const double *ay = &model.y[3 * pair.first];
          const double *bx = &model.x[3 * pair.second];
          const double *by = &model.y[3 * pair.second];
          chunk_energy[pair.first / chunk] +=
            add_target_potential_forces(ax,
                                        ay,
                                        bx,
                                        by,
                                        pair_penalty,
                                        scratch.data()) +
            add_target_potential_forces(bx,
                                        by,
                                        ax,
                                        ay,
                                        pair_penalty,
                                        scratch.data());
        }
      partition.sum(chunk_energy);
      double energy = 0.;
      for (const double e : chunk_energy)
        energy += e;
      return energy;
    }

    void
    ContactSystem::index_pairs(const unsigned int n_elements)
    {
      pair_penalty_factor.clear();
      pair_force.assign(12 * pair_list.size(), 0.);
      pair_friction.assign(pair_list.size(), 0.);
      element_pair_start.assign(n_elements + 1, 0);
      for (const auto &p : pair_list)
        {
          ++element_pair_start[p.first + 1];
          ++element_pair_start[p.second + 1];
        }
      for (unsigned int e = 0; e < n_elements; ++e)
        element_pair_start[e + 1] += element_pair_start[e];
      // pairs are sorted by their first triangle: where each one's begin
      first_pair_start.assign(n_elements + 1, 0);
      for (const auto &p : pair_list)
        ++first_pair_start[p.first + 1];
      for (unsigned int e = 0; e < n_elements; ++e)
        first_pair_start[e + 1] += first_pair_start[e];
      element_pair_entries.resize(2 * pair_list.size());
      std::vector<unsigned int> fill(element_pair_start.begin(),
                                     element_pair_start.end() - 1);
      for (unsigned int p = 0; p < pair_list.size(); ++p)
        {
          element_pair_entries[fill[pair_list[p].first]++]  = 2 * p;
          element_pair_entries[fill[pair_list[p].second]++] = 2 * p + 1;
        }
    }

    void
    ContactSystem::compute_forces(const DiscreteModel    &model,
                                  const double            dt,
                                  tbb::task_arena        &arena,
                                  const ElementPartition &partition)
    {
      if (pair_list.empty())
        return;
      switch (contact.law)
        {
          case ContactLaw::penalty_coulomb:
            compute_forces_with(contact.penalty_coulomb,
                                model,
                                dt,
                                arena,
                                partition);
            return;
        }
    }

    template <typename Law>
    void
    ContactSystem::compute_forces_with(const Law              &law,
                                       const DiscreteModel    &m,
                                       const double            dt,
                                       tbb::task_arena        &arena,
                                       const ElementPartition &partition)
    {
      // the faces of broken joints: their factors, once per pair list
      if (contact.match_broken_joints &&
          pair_penalty_factor.size() != pair_list.size())
        {
          pair_penalty_factor.resize(pair_list.size());
          for (std::size_t p = 0; p < pair_list.size(); ++p)
            pair_penalty_factor[p] = face_penalty_factor(m,
                                                         pair_list[p].first,
                                                         pair_list[p].second,
                                                         law.normal_penalty);
        }
      // on several ranks: the pairs with a triangle of this rank (the
      // others' friction entries stay 0)
      const bool distributed = partition.distributed();
      if (distributed && local_pairs_of_search != searches + 1)
        {
          local_pairs.clear();
          for (unsigned int p = 0; p < pair_list.size(); ++p)
            if (partition.owns(pair_list[p].first) ||
                partition.owns(pair_list[p].second))
              local_pairs.push_back(p);
          local_pairs_of_search = searches + 1;
        }
      for_each_chunk(
        arena,
        distributed ? local_pairs.size() : pair_list.size(),
        256,
        [&](const std::size_t begin, const std::size_t end, const std::size_t) {
          Law scaled_law;
          for (std::size_t i = begin; i < end; ++i)
            {
              const std::size_t p     = distributed ? local_pairs[i] : i;
              ContactPair      &pair  = pair_list[p];
              double           *force = &pair_force[12 * p];
              for (unsigned int i = 0; i < 12; ++i)
                force[i] = 0.;
              double dissipated = 0.;
              if (pair_is_rigid[p])
                {
                  pair_friction[p] = 0.;
                  continue;
                }
              // the faces of a broken joint: its compressive stiffness
              const double face_factor =
                pair_penalty_factor.empty() ? 1. : pair_penalty_factor[p];
              const Law &pair_law =
                face_factor == 1. ?
                  law :
                  (scaled_law = law.with_normal_penalty_scaled(face_factor));
              // each element is once the contactor, once the target
              for (unsigned int direction = 0; direction < 2; ++direction)
                {
                  const unsigned int c =
                    direction == 0 ? pair.first : pair.second;
                  const unsigned int t =
                    direction == 0 ? pair.second : pair.first;
                  double       *fc = force + 6 * direction;
                  double       *ft = force + 6 * (1 - direction);
                  const double *tx = &m.x[3 * t], *ty = &m.y[3 * t];
                  bool          entered = false;
                  for (unsigned int edge = 0; edge < 3; ++edge)
                    {
                      EdgeFriction &history =
                        pair.friction[3 * direction + edge];
                      const unsigned int a = 3 * c + edge,
                                         b = 3 * c + (edge + 1) % 3;
                      EdgePotentialIntegrals I;
                      if (!edge_potential_integrals(m.x[a],
                                                    m.y[a],
                                                    m.x[b],
                                                    m.y[b],
                                                    tx,
                                                    ty,
                                                    I))
                        {
                          history = EdgeFriction(); // the edge left the target
                          continue;
                        }
                      entered = true;
                      dissipated += pair_law.edge_forces(m.x.data(),
                                                         m.y.data(),
                                                         m.vx.data(),
                                                         m.vy.data(),
                                                         a,
                                                         b,
                                                         edge,
                                                         (edge + 1) % 3,
                                                         3 * t,
                                                         I,
                                                         dt,
                                                         history,
                                                         fc,
                                                         ft);
                    }
                  // the target's share of the normal force: where an edge
                  // of the contactor entered it, or where it lies inside
                  // the contactor (its node 0 left of all three edges)
                  const double *cx = &m.x[3 * c], *cy = &m.y[3 * c];
                  bool          overlap = entered;
                  if (!overlap)
                    {
                      overlap = true;
                      for (unsigned int k = 0; k < 3; ++k)
                        {
                          const unsigned int k1 = (k + 1) % 3;
                          if ((cx[k1] - cx[k]) * (ty[0] - cy[k]) -
                                (cy[k1] - cy[k]) * (tx[0] - cx[k]) <
                              0.)
                            overlap = false;
                        }
                    }
                  if (overlap)
                    pair_law.target_forces(cx, cy, tx, ty, ft);
                }
              pair_friction[p] = dissipated;
            }
        });
    }

    void
    ContactSystem::synchronise_pairs(ElementPartition &partition)
    {
      if (!partition.distributed())
        return;
      // the pairs each rank made, with their friction history and forces
      // (both owners of a pair computed the same), to every rank in rank
      // order: the sorted list of one rank
      constexpr unsigned int   width = 12;
      std::vector<ContactPair> all;
      std::vector<double>      forces;
      for (std::size_t p = 0; p < pair_list.size(); ++p)
        if (partition.owns(pair_list[p].first))
          {
            all.push_back(pair_list[p]);
            forces.insert(forces.end(),
                          pair_force.begin() + width * p,
                          pair_force.begin() + width * (p + 1));
          }
      partition.gather_pairs(all, &forces, width);
      pair_list.swap(all);
      index_pairs(static_cast<unsigned int>(element_pair_start.size() - 1));
      pair_force.swap(forces);
      flag_rigid_pairs();
      local_pairs_of_search = 0;
    }

    void
    ContactSystem::save(CheckpointWriter &out) const
    {
      ContactTravel::save(out);
      out.put<std::uint64_t>(searches);
      out.put(pair_list);
    }

    void
    ContactSystem::load(CheckpointReader &in, const unsigned int n_elements)
    {
      ContactTravel::load(in);
      std::uint64_t count = 0;
      in.get(count);
      searches              = count;
      local_pairs_of_search = 0;
      all_pairs_of_search   = 0;
      in.get(pair_list);
      for (const auto &p : pair_list)
        if (p.first >= n_elements || p.second >= n_elements)
          throw InputError("the checkpoint '" + in.name() +
                           "' is corrupt (contact pair of element " +
                           std::to_string(std::max(p.first, p.second)) + ").");
      index_pairs(n_elements);
      flag_rigid_pairs();
    }
  } // namespace discrete
} // namespace tmfdem
