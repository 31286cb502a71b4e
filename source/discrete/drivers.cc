#include <cctype>
#include <cmath>
#include <tmfdem/base/exceptions.h>
#include <tmfdem/base/function_expression.h>
#include <tmfdem/discrete/drivers.h>

namespace tmfdem
{
  namespace discrete
  {
    void
    Drivers::setup_bodies(const Parameters &parameters, DiscreteModel &model)
    {
      const auto &bodies = parameters.get<DiscreteBodyParameters>().bodies;
      body_motion.clear();
      body_velocity.clear();
      for (const auto &b : bodies)
        {
          body_motion.push_back(b.motion);
          body_velocity.push_back(
            make_expression_function(b.velocity_x, b.name + "/Velocity x"));
          body_velocity.push_back(
            make_expression_function(b.velocity_y, b.name + "/Velocity y"));
        }
      body_velocity_now.assign(bodies.size(), {{0., 0.}});
      body_reaction.assign(bodies.size(), {{0., 0.}});
      model.body_number.clear();
      for (const auto &b : bodies)
        model.body_number.push_back(b.number);
      std::vector<unsigned char> body_of_material(256, no_body);
      for (unsigned int b = 0; b < bodies.size(); ++b)
        for (const auto id : bodies[b].material_ids)
          body_of_material[id] = b;
      std::vector<bool> body_has_cells(bodies.size(), false);
      node_body.assign(model.n_nodes, no_body);
      for (unsigned int e = 0; e < model.n_elements; ++e)
        {
          model.body[e] = body_of_material[model.material[e]];
          if (model.body[e] != no_body)
            body_has_cells[model.body[e]] = true;
          for (unsigned int k = 0; k < 3; ++k)
            node_body[3 * e + k] = model.body[e];
        }
      for (unsigned int b = 0; b < bodies.size(); ++b)
        if (!body_has_cells[b])
          throw InputError(bodies[b].name +
                           "/Material ids: no cell of the mesh has these "
                           "material ids.");
      // initial velocities
      for (unsigned int b = 0; b < bodies.size(); ++b)
        {
          auto vx0 =
            make_expression_function(bodies[b].initial_velocity_x,
                                     bodies[b].name + "/Initial velocity x");
          auto vy0 =
            make_expression_function(bodies[b].initial_velocity_y,
                                     bodies[b].name + "/Initial velocity y");
          for (unsigned int n = 0; n < model.n_nodes; ++n)
            if (node_body[n] == b &&
                bodies[b].motion == DiscreteBody::Motion::free)
              {
                const Point<2> p(model.x_ref[n], model.y_ref[n]);
                model.vx[n] = vx0->value(p);
                model.vy[n] = vy0->value(p);
              }
        }
      gravity = {{parameters.get<DiscreteMechanicsParameters>().gravity[0],
                  parameters.get<DiscreteMechanicsParameters>().gravity[1]}};
      gravity_ramp_time =
        parameters.get<DiscreteMechanicsParameters>().gravity_ramp_time;
    }

    void
    Drivers::setup_boundary_conditions(const Parameters         &parameters,
                                       const DiscreteModel      &model,
                                       const ImposedMotionClock &clock)
    {
      conditions.clear();
      node_conditions.clear();
      node_condition_slot.assign(model.n_nodes, -1);
      using Type = MechanicalBoundaryCondition::Type;
      std::vector<int> condition_of_id(256, -1);
      for (const auto &c : parameters.mechanical_boundary.conditions)
        {
          ConditionFunctions f;
          f.type              = c.type;
          const char *axis[2] = {" x", " y"};
          for (unsigned int d = 0; d < 2; ++d)
            {
              const std::string expression =
                c.type == Type::displacement ? c.displacement[d] :
                c.type == Type::traction     ? c.traction[d] :
                                               c.velocity[d];
              const std::string entry =
                c.name +
                (c.type == Type::displacement ? "/Displacement" :
                 c.type == Type::traction     ? "/Traction" :
                                                "/Velocity") +
                axis[d];
              f.value[d] = make_expression_function(expression, entry);
              // a function that names t is evaluated every step
              for (std::size_t i = 0; i < expression.size(); ++i)
                if (expression[i] == 't' &&
                    (i == 0 || !std::isalnum(expression[i - 1])) &&
                    (i + 1 == expression.size() ||
                     !std::isalnum(expression[i + 1])))
                  f.time_dependent[d] = true;
            }
          model.check_boundary_ids(c.name + "/Boundary ids", c.boundary_ids);
          for (const auto id : c.boundary_ids)
            if (id < condition_of_id.size())
              condition_of_id[id] = conditions.size();
          conditions.push_back(std::move(f));
        }
      // nodes on boundary edges with a condition (free bodies only; fixed
      // and driven bodies move as their body says)
      for (unsigned int e = 0; e < model.n_elements; ++e)
        for (unsigned int k = 0; k < 3; ++k)
          {
            const types::boundary_id id = model.edge_boundary[3 * e + k];
            if (id == numbers::internal_face_boundary_id ||
                id >= condition_of_id.size() || condition_of_id[id] < 0)
              continue;
            const unsigned int c       = condition_of_id[id];
            const unsigned int ends[2] = {3 * e + k, 3 * e + (k + 1) % 3};
            const double       length =
              std::hypot(model.x_ref[ends[1]] - model.x_ref[ends[0]],
                         model.y_ref[ends[1]] - model.y_ref[ends[0]]);
            for (const unsigned int node : ends)
              {
                if (!node_is_free(node))
                  continue;
                if (node_condition_slot[node] < 0)
                  {
                    NodeCondition nc;
                    nc.node          = node;
                    nc.condition     = c;
                    nc.prescribed[0] = false;
                    nc.prescribed[1] = false;
                    nc.velocity[0] = nc.velocity[1] = 0.;
                    nc.force[0] = nc.force[1] = 0.;
                    nc.traction_length        = 0.;
                    nc.traction_condition     = -1;
                    node_condition_slot[node] = node_conditions.size();
                    node_conditions.push_back(nc);
                  }
                NodeCondition &nc = node_conditions[node_condition_slot[node]];
                const Type     type = conditions[c].type;
                if (type == Type::traction)
                  {
                    nc.traction_length += 0.5 * length;
                    nc.traction_condition = c;
                  }
                else
                  {
                    // a kinematic condition wins over a traction at corners
                    nc.condition     = c;
                    nc.prescribed[0] = type != Type::roller_y;
                    nc.prescribed[1] = type != Type::roller_x;
                  }
              }
          }
      boundary_conditions_change = false;
      for (const ConditionFunctions &f : conditions)
        boundary_conditions_change |= f.type == Type::displacement ||
                                      f.time_dependent[0] ||
                                      f.time_dependent[1];
      condition_reaction.assign(conditions.size(), {{0., 0.}});
      evaluate_boundary_conditions(model, clock);
    }

    void
    Drivers::evaluate_boundary_conditions(const DiscreteModel      &model,
                                          const ImposedMotionClock &clock)
    {
      using Type = MechanicalBoundaryCondition::Type;
      for (ConditionFunctions &f : conditions)
        for (unsigned int d = 0; d < 2; ++d)
          f.value[d]->set_time(f.type == Type::displacement ?
                                 clock.displacement_time :
                               f.type == Type::velocity ? clock.velocity_time :
                                                          clock.traction_time);
      for (NodeCondition &nc : node_conditions)
        {
          const unsigned int  n = nc.node;
          const Point<2>      p(model.x_ref[n], model.y_ref[n]);
          ConditionFunctions &f = conditions[nc.condition];
          for (unsigned int d = 0; d < 2; ++d)
            {
              if (nc.prescribed[d])
                {
                  if (f.type == Type::velocity)
                    nc.velocity[d] =
                      clock.velocity_scale * f.value[d]->value(p);
                  else if (f.type == Type::displacement)
                    {
                      // reach X + u(t + dt) at the end of the step
                      const double target =
                        (d == 0 ? model.x_ref[n] : model.y_ref[n]) +
                        f.value[d]->value(p);
                      const double now = d == 0 ? model.x[n] : model.y[n];
                      nc.velocity[d] =
                        clock.time_step > 0. ?
                          (target - now) /
                            (clock.steps_to_target * clock.time_step) :
                          0.;
                    }
                  else
                    nc.velocity[d] = 0.;
                }
            }
        }
      // tractions: conditions of traction type, per node share of length
      for (NodeCondition &nc : node_conditions)
        if (nc.traction_length > 0.)
          {
            const unsigned int  n = nc.node;
            const Point<2>      p(model.x_ref[n], model.y_ref[n]);
            ConditionFunctions &f = conditions[nc.traction_condition];
            nc.force[0]           = f.value[0]->value(p) * nc.traction_length;
            nc.force[1]           = f.value[1]->value(p) * nc.traction_length;
          }
    }

    void
    Drivers::evaluate_body_velocities(const ImposedMotionClock &clock)
    {
      // driven bodies move with one velocity: the functions are evaluated
      // at the origin
      const Point<2> origin(0., 0.);
      for (unsigned int b = 0; b < body_motion.size(); ++b)
        if (body_motion[b] == DiscreteBody::Motion::velocity)
          {
            body_velocity[2 * b]->set_time(clock.velocity_time);
            body_velocity[2 * b + 1]->set_time(clock.velocity_time);
            body_velocity_now[b] = {
              {clock.velocity_scale * body_velocity[2 * b]->value(origin),
               clock.velocity_scale * body_velocity[2 * b + 1]->value(origin)}};
          }
    }

    bool
    Drivers::imposes_motion() const
    {
      using Type   = MechanicalBoundaryCondition::Type;
      bool imposed = false;
      for (const auto &c : conditions)
        imposed |= c.type == Type::velocity || c.type == Type::displacement;
      for (const auto motion : body_motion)
        imposed |= motion == DiscreteBody::Motion::velocity;
      return imposed;
    }

    std::vector<unsigned char>
    Drivers::rigid_groups(const DiscreteModel &model) const
    {
      std::vector<unsigned char> group(model.n_elements, no_body);
      for (unsigned int e = 0; e < model.n_elements; ++e)
        if (model.body[e] != no_body &&
            body_motion[model.body[e]] != DiscreteBody::Motion::free)
          group[e] = model.body[e];
      return group;
    }

    void
    Drivers::clear_reactions()
    {
      for (auto &r : body_reaction)
        r = {{0., 0.}};
      condition_reaction.assign(conditions.size(), {{0., 0.}});
    }
  } // namespace discrete
} // namespace tmfdem
