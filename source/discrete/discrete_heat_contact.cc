/**
 * @file
 * Contact heat in the discrete layer's own heat (DiscreteHeat): which
 * triangles touch (from the mechanics' contact search, or a search of its
 * own), the transfer of every touching pair (contact_heat.h) and its heat
 * rates.
 */
#include <tmfdem/base/threads.h>
#include <tmfdem/discrete/contact.h>
#include <tmfdem/discrete/contact_heat.h>
#include <tmfdem/discrete/discrete_heat.h>
#include <tmfdem/discrete/discrete_parameters.h>

namespace tmfdem
{
  namespace discrete
  {
    void
    DiscreteHeat::compute_contact_transfers() const
    {
      // transfers in parallel; for_each_contact_transfer() hands them on in
      // pair order
      transfers.assign(contact_pairs.size(), ContactHeatTransfer());
      overlapping.assign(contact_pairs.size(), 0);
      const ContactHeatModel contact_model =
        parameters.get<DiscreteHeatParameters>().contact_heat_model;
      for_each_chunk(arena_for(n_threads),
                     contact_pairs.size(),
                     64,
                     [&](const std::size_t begin,
                         const std::size_t end,
                         const std::size_t) {
                       for (std::size_t p = begin; p < end; ++p)
                         {
                           const auto [c, t] = contact_pairs[p];
                           OverlapPolygon overlap;
                           overlapping[p] = contact_heat(contact_model,
                                                         &model.x[3 * c],
                                                         &model.y[3 * c],
                                                         T.begin() + 3 * c,
                                                         &model.x[3 * t],
                                                         &model.y[3 * t],
                                                         T.begin() + 3 * t,
                                                         contact_conductance,
                                                         overlap,
                                                         transfers[p]);
                         }
                     });
    }


    void
    DiscreteHeat::update_contact_pairs()
    {
      contact_pairs.clear();
      rows.clear_pattern(); // couplings change: rebuild the pattern
      if (contact_conductance <= 0.)
        return;
      // candidates: the mechanics' (one search for both), or our own
      std::vector<ContactPair>        own_candidates;
      const std::vector<ContactPair> &candidates =
        shared_candidates ? *shared_candidates : own_candidates;
      if (!shared_candidates)
        search_contact_candidates(own_candidates);
      std::vector<char> touching(candidates.size(), 0);
      for_each_chunk(
        arena_for(n_threads),
        candidates.size(),
        256,
        [&](const std::size_t begin, const std::size_t end, const std::size_t) {
          for (std::size_t p = begin; p < end; ++p)
            {
              const ContactPair &c = candidates[p];
              OverlapPolygon     overlap;
              touching[p] = triangle_overlap(&model.x[3 * c.first],
                                             &model.y[3 * c.first],
                                             &model.x[3 * c.second],
                                             &model.y[3 * c.second],
                                             overlap) &&
                            overlap.contact_length > 0.;
            }
        });
      // on several ranks the pairs with a triangle of this rank
      const auto here = [&](const unsigned int e) {
        return e >= first_element && e < end_element;
      };
      for (std::size_t p = 0; p < candidates.size(); ++p)
        if (touching[p] &&
            (here(candidates[p].first) || here(candidates[p].second)))
          contact_pairs.emplace_back(candidates[p].first, candidates[p].second);
    }

    std::vector<ContactPair>
    DiscreteHeat::contact_pair_list() const
    {
      std::vector<ContactPair> list(contact_pairs.size());
      for (std::size_t p = 0; p < contact_pairs.size(); ++p)
        {
          list[p].first  = contact_pairs[p].first;
          list[p].second = contact_pairs[p].second;
        }
      return list;
    }

    void
    DiscreteHeat::search_contact_candidates(
      std::vector<ContactPair> &candidates) const
    {
      // triangles with a free edge and their intact neighbours; boxes
      // that overlap (no buffer); pairs joined by an intact joint excluded
      std::vector<unsigned int> elements;
      model.contact_candidate_elements(elements);
      LinkedCellSearch search;
      search.rebuild(
        model.x,
        model.y,
        elements,
        0.,
        [&](const unsigned int a, const unsigned int b) {
          return model.joined(a, b);
        },
        candidates,
        arena_for(n_threads));
    }

    void
    DiscreteHeat::add_contact_heat(Vector<double>      &rate,
                                   std::vector<double> *partials) const
    {
      const unsigned int W = balance_width();
      for_each_contact_transfer([&](const unsigned int         c,
                                    const unsigned int         t,
                                    const ContactHeatTransfer &transfer) {
        // |Q| counted once, by the owner of the pair's first triangle
        if (partials != nullptr && c >= first_element && c < end_element)
          (*partials)[chunk_of(c) * W + 2] += std::abs(transfer.heat_flow);
        for (unsigned int k = 0; k < 3; ++k)
          {
            rate[3 * c + k] += transfer.contactor_nodal_heat[k];
            rate[3 * t + k] += transfer.target_nodal_heat[k];
          }
      });
    }

  } // namespace discrete
} // namespace tmfdem
