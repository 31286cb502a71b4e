/**
 * @file
 * The contact members of TetrahedralSolver: the settings from Discrete
 * mechanics and the forces of each step (TetrahedronContactSystem).
 */
#include <algorithm>
#include <cmath>
#include <iomanip>
#include <sstream>
#include <tmfdem/base/exceptions.h>
#include <tmfdem/base/threads.h>
#include <tmfdem/discrete/discrete_parameters.h>
#include <tmfdem/discrete/tetrahedral_solver.h>
#include <tmfdem/discrete/tetrahedron_contact_system.h>

namespace tmfdem
{
  namespace discrete
  {
    void
    TetrahedralSolver::setup_contact()
    {
      const auto &dm = parameters.get<DiscreteMechanicsParameters>();
      if (!dm.contact)
        {
          contact.reset();
          return;
        }
      // penalties from the stiffest material of the mesh
      double E_max = 0.;
      for (unsigned int e = 0; e < model.n_elements; ++e)
        E_max =
          std::max(E_max,
                   parameters.materials[model.material[e]].youngs_modulus);
      // buffer: a quarter of the smallest edge by default
      double min_h = 1e300;
      for (unsigned int e = 0; e < model.n_elements; ++e)
        for (unsigned int a = 0; a < 4; ++a)
          for (unsigned int b = a + 1; b < 4; ++b)
            {
              const unsigned int na = 4 * e + a, nb = 4 * e + b;
              min_h =
                std::min(min_h,
                         std::sqrt(
                           std::pow(model.x_ref[na] - model.x_ref[nb], 2) +
                           std::pow(model.y_ref[na] - model.y_ref[nb], 2) +
                           std::pow(model.z_ref[na] - model.z_ref[nb], 2)));
            }
      // fixed and driven bodies: their tetrahedra never push each other
      const auto &bodies = parameters.get<DiscreteBodyParameters>().bodies;
      std::vector<unsigned char> rigid_group(model.n_elements, no_body);
      for (unsigned int e = 0; e < model.n_elements; ++e)
        if (model.body[e] != no_body &&
            bodies[model.body[e]].motion != DiscreteBody::Motion::free)
          rigid_group[e] = model.body[e];
      contact = std::make_unique<TetrahedronContactSystem>();
      contact->setup(make_contact_settings(dm, E_max, min_h), rigid_group);
      contact->update_active_elements(model);
      element_in_contact.assign(model.n_elements, 0);
    }

    void
    TetrahedralSolver::compute_contact_forces(const double dt)
    {
      const DiscreteModel &m = model;
      // the travel of the last step: the fastest active node
      if (step_number > 0)
        {
          double max_speed = 0.;
          for (const unsigned int e : contact->active_elements())
            for (unsigned int node = 4 * e; node < 4 * e + 4; ++node)
              max_speed =
                std::max(max_speed,
                         m.vx[node] * m.vx[node] + m.vy[node] * m.vy[node] +
                           m.vz[node] * m.vz[node]);
          contact->add_travel(std::sqrt(max_speed) * dt);
        }
      tbb::task_arena &arena = arena_for(n_threads);
      if (contact->search_needed())
        {
          contact->search(model, arena);
          for (unsigned int e = 0; e < m.n_elements; ++e)
            element_in_contact[e] = contact->has_pairs(e) ? 1 : 0;
          if (contact->overlap_check_due())
            {
              check_contact_overlap(false);
              contact->overlap_checked();
            }
        }
      contact->compute_forces(model, dt, arena);
      // the tetrahedra whose pairs are all apart take the contact-free
      // path of the node update (their contact forces are +0)
      for (unsigned int e = 0; e < m.n_elements; ++e)
        element_in_contact[e] = contact->has_active_pairs(e) ? 1 : 0;
      const double dissipated = contact->friction_of_elements(0, m.n_elements);
      energies.friction += dissipated;
    }

    void
    TetrahedralSolver::check_contact_overlap(const bool initial)
    {
      if (initial)
        {
          contact->search(model, arena_for(n_threads));
          for (unsigned int e = 0; e < model.n_elements; ++e)
            element_in_contact[e] = contact->has_pairs(e) ? 1 : 0;
        }
      const TetrahedronContactSystem::Overlap worst =
        contact->largest_overlap(model);
      if (worst.fraction <=
          (initial ? max_initial_overlap : max_contact_overlap))
        return;
      const auto &bodies   = parameters.get<DiscreteBodyParameters>().bodies;
      const auto  describe = [&](const unsigned int e) {
        double centroid[3] = {0., 0., 0.};
        for (unsigned int k = 0; k < 4; ++k)
          {
            centroid[0] += 0.25 * model.x_ref[4 * e + k];
            centroid[1] += 0.25 * model.y_ref[4 * e + k];
            centroid[2] += 0.25 * model.z_ref[4 * e + k];
          }
        const unsigned char b = model.body[e];
        std::ostringstream  text;
        text << std::setprecision(6) << e << " ("
             << (b != no_body && b < bodies.size() ? bodies[b].name :
                                                      std::string("no body"))
             << ", material id " << static_cast<unsigned int>(model.material[e])
             << ", reference centroid (" << centroid[0] << ", " << centroid[1]
             << ", " << centroid[2] << ") m)";
        return text.str();
      };
      const std::string  a = describe(worst.first), b = describe(worst.second);
      std::ostringstream message;
      message << std::setprecision(6);
      if (initial)
        {
          message << "the tetrahedra " << a << " and " << b << " overlap by "
                  << worst.volume << " m^3 at Time stepping/Start time, "
                  << 100. * worst.fraction
                  << " % of the smaller one's volume (allowed at the start: "
                  << 100. * max_initial_overlap
                  << " %, a face pressed in by about 3 % of the altitude): "
                     "bodies, and disconnected pieces of one body, must not "
                     "overlap at the start (contact would push them apart "
                     "violently and invert elements). Move them apart in the "
                     "mesh (Mesh/File name, the .geo file) or leave a gap.";
          throw InputError(message.str());
        }
      const auto &dm = parameters.get<DiscreteMechanicsParameters>();
      message << "guard: contact failed: the tetrahedra " << a << " and " << b
              << " overlap by " << worst.volume << " m^3, "
              << 100. * worst.fraction
              << " % of the smaller one's volume (allowed: "
              << 100. * max_contact_overlap
              << " %, a face pressed in by about a sixth of the altitude): "
                 "the contact penalty is too soft for the impact, and the "
                 "bodies pass through each other. Raise Discrete "
                 "mechanics/Contact penalty factor (now "
              << dm.contact_penalty_factor
              << " x Young's modulus) or lower the impact velocity or load";
      guard_failure(message.str());
    }
  } // namespace discrete
} // namespace tmfdem
