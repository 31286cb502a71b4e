/**
 * @file
 * The constant-strain triangle at finite strain (paper Sec. 2, 4.1-4.2 with
 * the corrections of the theory manual): deformation gradient from the
 * current and initial element bases, the multiplicative thermal split
 * F = F_T F_e with F_T = s I, the compressible neo-Hookean-type Cauchy
 * stress of Eq. 44 evaluated with the ELASTIC part F_e, and the viscous
 * stress 2 eta D with D = sym(dF/dt F^-1) (Eqs. 45-46).
 *
 * The constitutive law (Lame constants per idealisation, thermal stretch,
 * Eq. 44 on F_e) is the core both layers share, base/constitutive.h; this
 * header adds the triangle's kinematics and forces around it: the
 * anisotropic correction and the nodal forces as templates on the number
 * type (double or a vector of doubles, one triangle per lane), which
 * element_kernel.h assembles into the one element kernel of the explicit
 * loop, and Matrix2 (Eigen::Matrix2d) versions of them for the set-up,
 * stress recovery and tests.
 */
#ifndef tmfdem_discrete_solid_h
#define tmfdem_discrete_solid_h

#include <Eigen/Core>
#include <Eigen/LU>
#include <array>
#include <tmfdem/base/constitutive.h>

namespace tmfdem
{
  namespace discrete
  {
    /**
     * A 2x2 matrix: Eigen's fixed-size type (no allocation; its product,
     * determinant and inverse form every entry in the same order as the
     * hand-written code they replaced, so results are bitwise unchanged:
     * doc/performance.md, "Eigen for the element algebra").
     */
    using Matrix2 = Eigen::Matrix2d;

    /** The matrix [a00, a01; a10, a11]. */
    inline Matrix2
    matrix2(const double a00,
            const double a01,
            const double a10,
            const double a11)
    {
      Matrix2 m;
      m << a00, a01, a10, a11;
      return m;
    }

    // The constitutive law itself (idealisation, Lame constants, thermal
    // stretch, Eq. 44 and its energy) is the one core of both layers in
    // base/constitutive.h; the discrete layer uses it under its own names.
    using constitutive::Idealisation;
    using constitutive::lame_constants;
    using constitutive::LameConstants;
    using constitutive::Stress2;
    using constitutive::thermal_stretch;

    /**
     * The element basis [x1-x0, x2-x0; y1-y0, y2-y0] of a triangle with the
     * given node coordinates [m] (paper Eq. 39).
     */
    inline Matrix2
    element_basis(const double x0,
                  const double y0,
                  const double x1,
                  const double y1,
                  const double x2,
                  const double y2)
    {
      return matrix2(x1 - x0, x2 - x0, y1 - y0, y2 - y0);
    }

    /**
     * Cauchy stress of paper Eq. 44 on the elastic deformation gradient
     * @p Fe [Pa] (constitutive::elastic_stress()).
     */
    inline Stress2
    elastic_stress(const Matrix2 &Fe, const LameConstants &lame)
    {
      return constitutive::elastic_stress(Fe(0, 0),
                                          Fe(0, 1),
                                          Fe(1, 0),
                                          Fe(1, 1),
                                          lame);
    }

    /** sqrt 2, of the Mandel components below. */
    constexpr double mandel_sqrt2 = 1.4142135623730951;

    /** The number of Mandel components of a symmetric dim x dim tensor:
     *  3 in 2D (xx, yy, sqrt 2 xy), 6 in 3D (xx, yy, zz, sqrt 2 xy,
     *  sqrt 2 xz, sqrt 2 yz). */
    template <int dim>
    constexpr int mandel_size = dim *(dim + 1) / 2;

    /** The number of stored components of a symmetric matrix of Mandel
     *  size n = mandel_size<dim> (6 in 2D, 21 in 3D): the diagonal
     *  (11, 22, ..., nn), then the entries above it row by row (12, 13,
     *  ..., 1n, 23, ...). */
    template <int dim>
    constexpr int anisotropy_size = mandel_size<dim> *(mandel_size<dim> + 1) /
                                    2;

    /** Row i and column j of Mandel component @p k of a symmetric dim x dim
     *  tensor: the diagonal first, then (0, 1), (0, 2), (1, 2). */
    template <int dim>
    constexpr std::array<int, 2>
    mandel_pair(const int k)
    {
      if (k < dim)
        return {{k, k}};
      if (dim == 2)
        return {{0, 1}};
      constexpr int rows[3] = {0, 0, 1}, cols[3] = {1, 2, 2};
      return {{rows[k - dim], cols[k - dim]}};
    }

    /** The stored index of entry (i, j) of a symmetric matrix of Mandel
     *  size n = mandel_size<dim> (layout of anisotropy_size). */
    template <int dim>
    constexpr int
    anisotropy_index(const int i, const int j)
    {
      constexpr int n = mandel_size<dim>;
      if (i == j)
        return i;
      const int r = i < j ? i : j, c = i < j ? j : i;
      // entries above the diagonal before row r: (n - 1) + ... + (n - r)
      return n + r * (2 * n - r - 1) / 2 + (c - r - 1);
    }

    /** Green-Lagrange strain E = (F_e^T F_e - I) / 2 of @p Fe [-] in
     *  Mandel components (mandel_pair()), written to @p e. @p Number:
     *  double or a vector of doubles. */
    template <int dim, typename Number>
    __attribute__((always_inline)) inline void
    green_lagrange_mandel(const Number (&Fe)[dim][dim],
                          Number (&e)[mandel_size<dim>])
    {
      for (int k = 0; k < mandel_size<dim>; ++k)
        {
          const auto [i, j] = mandel_pair<dim>(k);
          Number c          = Fe[0][i] * Fe[0][j];
          for (int l = 1; l < dim; ++l)
            c = c + Fe[l][i] * Fe[l][j];
          if (i == j)
            e[k] = 0.5 * (c - 1.);
          else
            e[k] = mandel_sqrt2 * 0.5 * c;
        }
    }

    /** The same for the 2D F_e = [f00, f01; f10, f11], in (xx, yy,
     *  sqrt 2 xy). */
    template <typename Number>
    __attribute__((always_inline)) inline void
    green_lagrange_mandel(const Number f00,
                          const Number f01,
                          const Number f10,
                          const Number f11,
                          Number      *e)
    {
      const Number Fe[2][2] = {{f00, f01}, {f10, f11}};
      Number       m[3];
      green_lagrange_mandel<2>(Fe, m);
      for (int k = 0; k < 3; ++k)
        e[k] = m[k];
    }

    /** The same for a Matrix2 @p Fe. */
    inline std::array<double, 3>
    green_lagrange_mandel(const Matrix2 &Fe)
    {
      std::array<double, 3> e;
      green_lagrange_mandel(Fe(0, 0), Fe(0, 1), Fe(1, 0), Fe(1, 1), e.data());
      return e;
    }

    /**
     * The anisotropic correction of an element's stress [Pa]
     * (joint_compliance.h): the Cauchy stress of the second Piola-Kirchhoff
     * stress Delta C : E, E = (F_e^T F_e - I) / 2, that is
     * F_e (Delta C : E) F_e^T / J, with @p c the stored components of the
     * Mandel matrix Delta C (anisotropy_index(): 11, 22, 33, 12, 13, 23 in
     * 2D; 21 in 3D) [Pa], for the elastic deformation gradient @p Fe [-];
     * written to @p sigma (symmetric). Linear in the small strain,
     * objective, and the derivative of anisotropic_energy_density().
     * @p Number: double or a vector of doubles.
     */
    template <int dim, typename Number>
    __attribute__((always_inline)) inline void
    anisotropic_stress(const Number (&Fe)[dim][dim],
                       const Number *c,
                       Number (&sigma)[dim][dim])
    {
      constexpr int n = mandel_size<dim>;
      Number        e[n];
      green_lagrange_mandel<dim>(Fe, e);
      // the second Piola-Kirchhoff stress S = Delta C : E as a tensor
      Number S[dim][dim];
      for (int k = 0; k < n; ++k)
        {
          Number s = c[anisotropy_index<dim>(k, 0)] * e[0];
          for (int l = 1; l < n; ++l)
            s = s + c[anisotropy_index<dim>(k, l)] * e[l];
          const auto [i, j] = mandel_pair<dim>(k);
          if (i == j)
            S[i][i] = s;
          else
            S[i][j] = S[j][i] = s / mandel_sqrt2;
        }
      // sigma = F_e S F_e^T / J
      const Number inverse_J = 1. / constitutive::determinant<dim>(Fe);
      Number       A[dim][dim];
      for (int i = 0; i < dim; ++i)
        for (int j = 0; j < dim; ++j)
          {
            Number a = Fe[i][0] * S[0][j];
            for (int k = 1; k < dim; ++k)
              a = a + Fe[i][k] * S[k][j];
            A[i][j] = a;
          }
      for (int i = 0; i < dim; ++i)
        for (int j = i; j < dim; ++j)
          {
            Number a = A[i][0] * Fe[j][0];
            for (int k = 1; k < dim; ++k)
              a = a + A[i][k] * Fe[j][k];
            sigma[i][j] = a * inverse_J;
            sigma[j][i] = sigma[i][j];
          }
    }

    /** The same for a Matrix2 @p Fe and Delta C @p delta_C [Pa]. */
    inline Stress2
    anisotropic_stress(const Matrix2 &Fe, const double *delta_C)
    {
      const double Fa[2][2] = {{Fe(0, 0), Fe(0, 1)}, {Fe(1, 0), Fe(1, 1)}};
      double       sigma[2][2];
      anisotropic_stress<2>(Fa, delta_C, sigma);
      Stress2 s;
      s.xx = sigma[0][0];
      s.yy = sigma[1][1];
      s.xy = sigma[0][1];
      return s;
    }

    /** The energy of anisotropic_stress() per unit measure (area, volume)
     *  of the stress-free configuration, E : Delta C : E / 2 [J/m^dim], for
     *  the elastic deformation gradient @p Fe [-] and the stored Delta C
     *  @p c [Pa]. */
    template <int dim>
    inline double
    anisotropic_energy_density(const double (&Fe)[dim][dim], const double *c)
    {
      constexpr int n = mandel_size<dim>;
      double        e[n];
      green_lagrange_mandel<dim>(Fe, e);
      double diagonal = c[0] * e[0] * e[0];
      for (int k = 1; k < n; ++k)
        diagonal += c[k] * e[k] * e[k];
      double psi = 0.5 * diagonal;
      for (int k = 0; k < n; ++k)
        for (int l = k + 1; l < n; ++l)
          psi += c[anisotropy_index<dim>(k, l)] * e[k] * e[l];
      return psi;
    }

    /** The same for a Matrix2 @p Fe. */
    inline double
    anisotropic_energy_density(const Matrix2 &Fe, const double *delta_C)
    {
      const double Fa[2][2] = {{Fe(0, 0), Fe(0, 1)}, {Fe(1, 0), Fe(1, 1)}};
      return anisotropic_energy_density<2>(Fa, delta_C);
    }

    /**
     * Strain energy per unit area of the stress-free configuration [J/m^2]
     * whose derivative is Eq. 44 (constitutive::strain_energy_density()).
     */
    inline double
    strain_energy_density(const Matrix2 &Fe, const LameConstants &lame)
    {
      return constitutive::strain_energy_density(Fe(0, 0),
                                                 Fe(0, 1),
                                                 Fe(1, 0),
                                                 Fe(1, 1),
                                                 lame);
    }

    /**
     * F times an element's inverse initial basis, or its rate: the matrix
     * B = [x_1 - x_0, ..., x_dim - x_0] of the current node positions (or
     * velocities) @p u (u[i][a]: component i of node a) times the inverse
     * initial basis @p inverse_basis (row-major dim x dim) [1/m], written to
     * @p G (paper Eq. 39 for a triangle; the same for a tetrahedron). The
     * sums run in the order of Eigen's fixed-size product.
     */
    template <int dim, typename Number>
    __attribute__((always_inline)) inline void
    times_inverse_basis(const Number *const (&u)[dim],
                        const Number *inverse_basis,
                        Number (&G)[dim][dim])
    {
      for (int i = 0; i < dim; ++i)
        {
          Number b[dim];
          for (int k = 0; k < dim; ++k)
            b[k] = u[i][k + 1] - u[i][0];
          for (int j = 0; j < dim; ++j)
            {
              Number g = b[0] * inverse_basis[j];
              for (int k = 1; k < dim; ++k)
                g = g + b[k] * inverse_basis[k * dim + j];
              G[i][j] = g;
            }
        }
    }

    /**
     * dim! V grad N_a of the linear shape functions of a simplex with the
     * current nodes @p x (x[i][a]: component i of node a) [m^(dim-1)],
     * written to @p g (g[a][i]): in 2D the opposite edge turned outward
     * (node 0: (y1 - y2, x2 - x1)), in 3D the cross product of two edges of
     * the opposite face, oriented as grad N_a for a positively oriented
     * tetrahedron (node 3: (x1 - x0) x (x2 - x0)).
     */
    template <int dim, typename Number>
    __attribute__((always_inline)) inline void
    scaled_shape_gradients(const Number *const (&x)[dim],
                           Number (&g)[dim + 1][dim])
    {
      static_assert(dim == 2 || dim == 3, "2D or 3D");
      if constexpr (dim == 2)
        {
          const Number *X = x[0], *Y = x[1];
          g[0][0] = Y[1] - Y[2];
          g[1][0] = Y[2] - Y[0];
          g[2][0] = Y[0] - Y[1];
          g[0][1] = X[2] - X[1];
          g[1][1] = X[0] - X[2];
          g[2][1] = X[1] - X[0];
        }
      else
        {
          // node a: (x_p - x_o) x (x_q - x_o) over the opposite face (o, p, q)
          constexpr int face[4][3] = {{1, 3, 2},
                                      {0, 2, 3},
                                      {0, 3, 1},
                                      {0, 1, 2}};
          for (int a = 0; a < 4; ++a)
            {
              const int o = face[a][0], p = face[a][1], q = face[a][2];
              Number    e[3], f[3];
              for (int i = 0; i < 3; ++i)
                {
                  e[i] = x[i][p] - x[i][o];
                  f[i] = x[i][q] - x[i][o];
                }
              g[a][0] = e[1] * f[2] - e[2] * f[1];
              g[a][1] = e[2] * f[0] - e[0] * f[2];
              g[a][2] = e[0] * f[1] - e[1] * f[0];
            }
        }
    }

    /**
     * Nodal forces of a constant-stress simplex [N/m in 2D, N in 3D]:
     * f_a = -V sigma grad N_a in the current configuration, with the
     * symmetric stress @p sigma [Pa] and the current nodes @p x (x[i][a])
     * [m]; written to @p f (f[a][i]). In 2D, -1/2 sigma n_a with n_a the
     * opposite edge turned outward; in 3D, -1/6 sigma n_a with n_a twice
     * the opposite face's area vector, pointing inward.
     * @p Number: double or a vector of doubles.
     */
    template <int dim, typename Number>
    __attribute__((always_inline)) inline void
    nodal_forces(const Number (&sigma)[dim][dim],
                 const Number *const (&x)[dim],
                 Number (&f)[dim + 1][dim])
    {
      // -V grad N_a = -(1 / dim!) scaled_shape_gradients()
      constexpr double minus_inverse_factorial = dim == 2 ? -0.5 : -1. / 6.;
      Number           g[dim + 1][dim];
      scaled_shape_gradients<dim>(x, g);
      for (int a = 0; a <= dim; ++a)
        for (int i = 0; i < dim; ++i)
          {
            Number sum = sigma[i][0] * g[a][0];
            for (int j = 1; j < dim; ++j)
              sum = sum + sigma[i][j] * g[a][j];
            f[a][i] = minus_inverse_factorial * sum;
          }
    }

    /**
     * The 2D nodal_forces() on the stress components @p sxx, @p syy, @p sxy
     * [Pa] and node coordinates @p x, @p y [m] (three each), written to
     * @p fx, @p fy (node by node) [N/m].
     */
    template <typename Number>
    __attribute__((always_inline)) inline void
    nodal_forces(const Number  sxx,
                 const Number  syy,
                 const Number  sxy,
                 const Number *x,
                 const Number *y,
                 Number       *fx,
                 Number       *fy)
    {
      const Number  sigma[2][2] = {{sxx, sxy}, {sxy, syy}};
      const Number *nodes[2]    = {x, y};
      Number        f[3][2];
      nodal_forces<2>(sigma, nodes, f);
      for (unsigned int k = 0; k < 3; ++k)
        {
          fx[k] = f[k][0];
          fy[k] = f[k][1];
        }
    }

    /** The same for a Stress2 @p s and nodes (x0, y0) ... (x2, y2) [m];
     *  written to @p f (x0, y0, x1, ...) [N/m]. */
    inline void
    nodal_forces(const Stress2 &s,
                 const double   x0,
                 const double   y0,
                 const double   x1,
                 const double   y1,
                 const double   x2,
                 const double   y2,
                 double        *f)
    {
      const double x[3] = {x0, x1, x2}, y[3] = {y0, y1, y2};
      double       fx[3], fy[3];
      nodal_forces(s.xx, s.yy, s.xy, x, y, fx, fy);
      for (unsigned int k = 0; k < 3; ++k)
        {
          f[2 * k]     = fx[k];
          f[2 * k + 1] = fy[k];
        }
    }
  } // namespace discrete
} // namespace tmfdem

#endif
