/**
 * @file
 * The heat kernels of the discrete layer, once for triangles and
 * tetrahedra (paper Eqs. 18-20 and 25-27; theory manual, "Heat in the
 * discrete layer"): the P1 conductivity matrix of a simplex in its current
 * configuration, its consistent capacity matrix, and the conductance of
 * an intact joint between one node pair. Templates on the dimension and
 * the number type (double, or a vector of doubles with one element per
 * lane), like the mechanical kernels of element_kernel.h.
 */
#ifndef tmfdem_discrete_heat_kernel_h
#define tmfdem_discrete_heat_kernel_h

#include <tmfdem/discrete/solid.h>

namespace tmfdem
{
  namespace discrete
  {
    /**
     * Signed measure of a simplex [m^2 in 2D, m^3 in 3D]: the area of the
     * triangle or the volume of the tetrahedron with the nodes @p x
     * (x[i][a]: coordinate i of node a), positive for the counterclockwise
     * (2D) or right-handed (3D) node order of deal.II's simplices.
     */
    template <int dim, typename Number>
    __attribute__((always_inline)) inline Number
    simplex_measure(const Number *const (&x)[dim])
    {
      static_assert(dim == 2 || dim == 3, "2D or 3D");
      if constexpr (dim == 2)
        {
          const Number *X = x[0], *Y = x[1];
          return 0.5 * ((X[1] - X[0]) * (Y[2] - Y[0]) -
                        (X[2] - X[0]) * (Y[1] - Y[0]));
        }
      else
        {
          Number e[3][3]; // edges from node 0, e[a][i]
          for (int a = 0; a < 3; ++a)
            for (int i = 0; i < 3; ++i)
              e[a][i] = x[i][a + 1] - x[i][0];
          const Number det = e[0][0] * (e[1][1] * e[2][2] - e[1][2] * e[2][1]) -
                             e[0][1] * (e[1][0] * e[2][2] - e[1][2] * e[2][0]) +
                             e[0][2] * (e[1][0] * e[2][1] - e[1][1] * e[2][0]);
          return det * (1. / 6.);
        }
    }

    /**
     * The conductivity matrix of an isotropic P1 simplex in its current
     * configuration, K_ab = k V grad N_a . grad N_b [W/(m K) in 2D, W/K in
     * 3D], with the conductivity @p k [W/(m K)] and the current nodes @p x
     * (x[i][a]). With g_a = dim! V grad N_a (scaled_shape_gradients()),
     * K_ab = k g_a . g_b / ((dim!)^2 V).
     */
    template <int dim, typename Number>
    __attribute__((always_inline)) inline void
    conductivity_matrix(const Number *const (&x)[dim],
                        const Number k,
                        Number (&K)[dim + 1][dim + 1])
    {
      Number g[dim + 1][dim];
      scaled_shape_gradients<dim>(x, g);
      constexpr double factorial_squared = dim == 2 ? 4. : 36.;
      const Number scale = k / (factorial_squared * simplex_measure<dim>(x));
      for (int a = 0; a <= dim; ++a)
        for (int b = 0; b <= dim; ++b)
          {
            Number sum = g[a][0] * g[b][0];
            for (int i = 1; i < dim; ++i)
              sum = sum + g[a][i] * g[b][i];
            K[a][b] = scale * sum;
          }
    }

    /**
     * Makes the conduction matrix @p K of one element (n = dim + 1 nodes,
     * symmetric, zero row sums) an M-matrix (Discrete heat/Conduction
     * matrix = M-matrix): every positive coupling K_ab of two nodes (the
     * two faces opposite them meet at an obtuse angle) is set to zero and
     * added to both diagonals, K <- K + sum K_ab (e_a - e_b)(e_a - e_b)^T
     * over those pairs. The row sums stay zero (a uniform temperature
     * carries no heat, and every element conserves heat), K stays
     * symmetric positive semi-definite with more conduction along those
     * edges (discrete upwinding, Kuzmin's low-order operator), and its
     * Gershgorin row bound sum_b |K_ab| does not change. With the lumped
     * capacity an implicit step then keeps every node between the extremes
     * of the old temperatures and the boundary values (discrete maximum
     * principle); the price is a first-order error on obtuse elements.
     */
    template <int n>
    inline void
    make_conduction_m_matrix(double (*K)[n])
    {
      for (int a = 0; a < n; ++a)
        for (int b = a + 1; b < n; ++b)
          if (K[a][b] > 0.)
            {
              K[a][a] += K[a][b];
              K[b][b] += K[b][a];
              K[a][b] = K[b][a] = 0.;
            }
    }

    /**
     * Entry (a, b) of the consistent capacity matrix of a P1 simplex,
     * M_ab = c V (1 + delta_ab) / ((dim + 1)(dim + 2)) [J/(m K) in 2D, J/K
     * in 3D], with the volumetric heat capacity @p c = rho c_p [J/(m^3 K)]
     * and the measure @p V [m^2 or m^3]. The lumped capacity is the row
     * sum c V / (dim + 1).
     */
    template <int dim>
    inline double
    consistent_capacity(const double       c,
                        const double       V,
                        const unsigned int a,
                        const unsigned int b)
    {
      constexpr double denominator = (dim + 1) * (dim + 2);
      return c * V / denominator * (a == b ? 2. : 1.);
    }

    /**
     * Entry (a, b) of the implicit step's capacity matrix of a P1 simplex
     * [J/(m K) in 2D, J/K in 3D]: consistent_capacity(), or with @p lumped
     * its row sum c V / (dim + 1) on the diagonal (Discrete heat/Capacity
     * matrix).
     */
    template <int dim>
    inline double
    implicit_capacity(const bool         lumped,
                      const double       c,
                      const double       V,
                      const unsigned int a,
                      const unsigned int b)
    {
      if (lumped)
        return a == b ? c * V / (dim + 1) : 0.;
      return consistent_capacity<dim>(c, V, a, b);
    }

    /**
     * Conductance between one node pair of an intact joint [W/(m K) in
     * 2D, W/K in 3D] (paper Eqs. 25-27): the joint conducts k_i = beta k /
     * h per unit area (@p beta the joint conductance factor, @p k the
     * conductivity of the two sides [W/(m K)], @p h the joint's size [m]:
     * its edge length in 2D, the mean edge of its face in 3D), and each of
     * its dim node pairs takes 1/dim of the joint's @p measure (edge length
     * [m] or face area [m^2]). In 2D the measure is h itself, and the
     * conductance beta k / 2 does not depend on the edge.
     */
    template <int dim>
    inline double
    joint_pair_conductance(const double beta,
                           const double k,
                           const double measure,
                           const double h)
    {
      if constexpr (dim == 2)
        {
          (void)measure;
          (void)h;
          return 0.5 * beta * k;
        }
      else
        return beta * k / h * measure / dim;
    }
  } // namespace discrete
} // namespace tmfdem

#endif
