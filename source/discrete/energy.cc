#include <algorithm>
#include <cmath>
#include <tmfdem/discrete/energy.h>

namespace tmfdem
{
  namespace discrete
  {
    double
    EnergyBalance::scale() const
    {
      return std::max({std::abs(initial_kinetic + initial_strain),
                       std::abs(external_work),
                       std::abs(kinetic),
                       std::abs(strain),
                       std::abs(joint_work),
                       std::abs(contact_work),
                       std::abs(viscous_dissipation),
                       std::abs(relaxation_work),
                       1e-9}); // [J/m]: below this nothing happened
    }

    void
    measure_stored_energy(const DiscreteModel              &model,
                          const std::vector<LameConstants> &element_lame,
                          const std::vector<double>        &element_anisotropy,
                          EnergyBalance                    &balance)
    {
      double kinetic = 0., strain = 0., stored = 0.;
      for (unsigned int n = 0; n < model.n_nodes; ++n)
        kinetic += 0.5 * model.mass[n] *
                   (model.vx[n] * model.vx[n] + model.vy[n] * model.vy[n]);
      for (unsigned int e = 0; e < model.n_elements; ++e)
        {
          strain += element_strain_energy(model,
                                          e,
                                          deformation_gradient(model, e),
                                          model.thermal_stretch[e],
                                          element_lame[e],
                                          element_anisotropy.empty() ?
                                            nullptr :
                                            &element_anisotropy[6 * e]);
        }
      for (unsigned int j = 0; j < model.n_joints; ++j)
        if (model.joint_status[j] == JointStatus::intact &&
            model.joint_damage[2 * j] == 0. &&
            model.joint_damage[2 * j + 1] == 0.)
          {
            const unsigned int *n  = &model.joint_nodes[4 * j];
            const double        ex = model.x[n[1]] - model.x[n[0]];
            const double        ey = model.y[n[1]] - model.y[n[0]];
            const double        L  = std::hypot(ex, ey);
            const double        tx = ex / L, ty = ey / L;
            const double        d0x = model.x[n[2]] - model.x[n[0]];
            const double        d0y = model.y[n[2]] - model.y[n[0]];
            const double        d1x = model.x[n[3]] - model.x[n[1]];
            const double        d1y = model.y[n[3]] - model.y[n[1]];
            // the two Gauss points of the force computation (joints.cc),
            // and the closed part of a joint closed at one end exactly
            const double o_start       = d0x * ty - d0y * tx;
            const double o_end         = d1x * ty - d1y * tx;
            const bool   partly_closed = (o_start < 0.) != (o_end < 0.);
            for (const double u : {0.21132486540518713, 0.78867513459481287})
              {
                const double          dx = (1. - u) * d0x + u * d1x;
                const double          dy = (1. - u) * d0y + u * d1y;
                const double          o  = dx * ty - dy * tx;
                const JointConstants &k  = model.joint_constants[j];
                stored +=
                  0.5 * L *
                  (stored_joint_energy(o, dx * tx + dy * ty, k) -
                   (partly_closed && o < 0. ? 0.5 * k.normal_stiffness * o * o :
                                              0.));
              }
            if (partly_closed)
              stored +=
                joint_closed_part(o_start, o_end, L, model.joint_constants[j])
                  .energy;
          }
      balance.kinetic      = kinetic;
      balance.strain       = strain;
      balance.joint_stored = stored;
    }
  } // namespace discrete
} // namespace tmfdem
