#include <algorithm>
#include <cmath>
#include <tmfdem/discrete/joint_compliance.h>

namespace tmfdem
{
  namespace discrete
  {
    CompensatedElement
    compensate_joint_compliance(const std::array<double, 3> &x,
                                const std::array<double, 3> &y,
                                const LameConstants         &lame,
                                const std::array<double, 3> &normal_penalty,
                                const std::array<double, 3> &tangential_penalty,
                                const double                 max_share)
    {
      CompensatedElement result;
      result.lame       = lame;
      const double area = 0.5 * std::abs((x[1] - x[0]) * (y[2] - y[0]) -
                                         (x[2] - x[0]) * (y[1] - y[0]));
      if (!(area > 0.))
        return result;
      // the joints' bulk (1/K) and shear (1/mu) compliances
      double bulk = 0., shear = 0.; // [1/Pa]
      for (unsigned int k = 0; k < 3; ++k)
        {
          const double pn = normal_penalty[k], pt = tangential_penalty[k];
          if (!(pn > 0.) || !(pt > 0.))
            continue;
          const unsigned int b = (k + 1) % 3;
          const double       L2 =
            (x[b] - x[k]) * (x[b] - x[k]) + (y[b] - y[k]) * (y[b] - y[k]);
          const double w = L2 / (2. * area);
          result.weight += w;
          bulk += w / pn;
          shear += w * (1. / pn + 1. / pt) / 2.;
        }
      if (result.weight == 0.)
        return result;
      const double K = lame.lambda + lame.mu, mu = lame.mu;
      // shares of the target compliance 1/K and 1/mu taken by the joints
      double share_bulk = bulk * K, share_shear = shear * mu;
      result.share = std::max(share_bulk, share_shear);
      if (result.share > max_share)
        {
          result.capped = true;
          share_bulk    = std::min(share_bulk, max_share);
          share_shear   = std::min(share_shear, max_share);
        }
      const double K_e = K / (1. - share_bulk), mu_e = mu / (1. - share_shear);
      result.lame.mu     = mu_e;
      result.lame.lambda = K_e - mu_e;
      return result;
    }
  } // namespace discrete
} // namespace tmfdem
