/**
 * @file
 * Contact heat between two tetrahedra (paper Sec. 3.4 in 3D, with the
 * driving term of `shared/design/physics-notes.md`, section "Heat"; theory
 * manual 5.13, "Contact heat between tetrahedra"). The 3D counterpart of
 * contact_heat.h, with the same two models:
 *  - temperature difference (the default): Q = h_c A_c (T_1(G) - T_0(G))
 *    [W] into tetrahedron 0, A_c the contact area of the pair and G the
 *    centroid of its contact surface;
 *  - paper literal (Eqs. 29-33 read in 3D): Q = h_c V (grad T_0 +
 *    grad T_1) . n_0 [W], V the overlap volume (the 2D overlap area one
 *    dimension up) and n_0 the unit vector from tetrahedron 0's centroid
 *    to tetrahedron 1's.
 * Q goes to the eight nodes with the barycentric coordinates of G
 * (Eq. 36), split so that the eight nodal heats sum to exactly 0.0
 * (split_heat_exactly()).
 *
 * The contact area. The overlap of two tetrahedra is bounded by the part
 * of each one's surface inside the other (its faces clipped by the other's
 * four face planes); the vector areas (sums of area times outward normal)
 * of the two parts are opposite, as together they close the overlap's
 * surface. The contact direction m is the normal of the largest clipped
 * free face (a boundary face, or a face of a broken joint: where bodies
 * touch; the largest clipped face if none is free), and A_c the vector
 * area of either part projected onto m: the 3D
 * counterpart of the 2D contact length, where the contactor's boundary
 * inside the target has the chord of the overlap as its vector length.
 * Where two bodies press along a plane, every pair's overlap (a thin
 * prism under a face, a wedge under an edge, a pyramid under a vertex) has
 * its largest clipped free face in that plane, and the pairs' A_c add up to
 * the area of the contact exactly: the slab's sides count with their
 * component along m, which cancels between neighbouring pairs.
 * (Summing the clipped areas instead adds the overlap depth times every
 * patch's perimeter, +0.5 % in the pressed blocks of
 * prm/contact_conduction-3d.prm; the magnitude of the vector area adds
 * the wedges' sides, +0.26 %; the largest clipped face, free or not, may
 * be a steep side of a wedge, +0.15 %.) G is the centroid of the clipped faces
 * weighted by their area projected onto m: it lies in both tetrahedra, so
 * its barycentric coordinates interpolate both temperatures there.
 *
 * Pairs that only touch (no overlap volume: a separating plane,
 * touching_tolerance) exchange nothing, as in 2D and as their contact
 * force. Header-only, allocation-free, double only.
 */
#ifndef tmfdem_discrete_tetrahedron_contact_heat_h
#define tmfdem_discrete_tetrahedron_contact_heat_h

#include <array>
#include <cmath>
#include <tmfdem/discrete/contact_heat.h>
#include <tmfdem/discrete/tetrahedron_contact.h>

namespace tmfdem
{
  namespace discrete
  {
    /** The contact heat of a pair of tetrahedra [W]. */
    using TetrahedronContactHeat = ContactHeatTransferT<4>;

    /**
     * The geometry of the contact of two tetrahedra, which does not depend
     * on their temperatures: contact area, the barycentric coordinates of
     * the contact surface's centroid G in both, and the paper literal
     * model's weights.
     */
    struct TetrahedronContactInterface
    {
      /** A_c, half the area of the faces of either inside the other
       *  [m^2]; 0 without overlap. */
      double area = 0.;
      /** Overlap volume [m^3] (paper literal model only, 0 otherwise). */
      double overlap_volume = 0.;
      /** Barycentric coordinates of G in tetrahedron 0 and 1 [-]. */
      std::array<double, 4> shape[2] = {{{0., 0., 0., 0.}}, {{0., 0., 0., 0.}}};
      /** Paper literal model only: V grad(lambda_k) . n_0 of node k of
       *  tetrahedron side [m^2], so that Q = h_c sum weights T. */
      std::array<double, 4> literal_weights[2] = {{{0., 0., 0., 0.}},
                                                  {{0., 0., 0., 0.}}};
    };

    /**
     * The contact geometry of the tetrahedra @p x[0] and @p x[1] (nodes
     * [k][i], positively oriented) [m] whose free faces (bit f: the face
     * opposite node f is a boundary face or that of a broken joint) are
     * @p free_faces: fills @p interface (zero where they do not overlap in
     * a volume, tetrahedra_overlap()) and returns whether they exchange
     * heat (A_c > 0). With @p paper_literal, also the overlap volume and
     * the literal model's weights.
     */
    inline bool
    tetrahedron_contact_interface(const double (&x)[2][4][3],
                                  const unsigned char (&free_faces)[2],
                                  const bool                   paper_literal,
                                  TetrahedronContactInterface &interface)
    {
      using namespace tetrahedron_contact_internal;
      interface = TetrahedronContactInterface();
      TetrahedronCoordinates coordinates[2];
      if (!tetrahedra_overlap(x, coordinates))
        return false;
      // per face of either (entry 4 c + f): its clipped area, the
      // area-weighted sums of both tetrahedra's coordinates over it, and
      // its outward normal
      double clipped[8]        = {};
      double sums[8][2][4]     = {};
      double normal[8][3]      = {};
      double vector_area[2][3] = {};
      for (unsigned int c = 0; c < 2; ++c)
        {
          const unsigned int t = 1 - c;
          double             g[4][3];
          scaled_gradients(x[c], g);
          for (unsigned int f = 0; f < 4; ++f)
            {
              const unsigned int                entry = 4 * c + f;
              const std::array<unsigned int, 3> face =
                tetrahedron_face_nodes(f);
              FaceVertex base[3];
              face_vertices(x[c], f, coordinates[t], base);
              // the face clipped by the target's four face planes
              FaceVertex        buffers[2][max_face_vertices];
              const FaceVertex *P = base;
              unsigned int      n = 3;
              for (unsigned int k = 0; k < 4 && n > 0; ++k)
                {
                  n = clip_face(P, n, 3 + k, 7, buffers[k % 2]);
                  P = buffers[k % 2];
                }
              const double face_area = outward_face_normal(g, f, normal[entry]);
              // fan from vertex 0: area and centroid of each triangle (the
              // coordinates are linear: the centroid's are the mean)
              for (unsigned int v = 1; v + 1 < n; ++v)
                {
                  const double *p0 = P[0].value, *p1 = P[v].value,
                               *p2  = P[v + 1].value;
                  const double area = fan_triangle_area(p0, p1, p2, face_area);
                  if (!(area > 0.))
                    continue;
                  clipped[entry] += area;
                  const double w = area / 3.;
                  for (unsigned int a = 0; a < 3; ++a)
                    sums[entry][c][face[a]] += w * (p0[a] + p1[a] + p2[a]);
                  for (unsigned int k = 0; k < 4; ++k)
                    sums[entry][t][k] +=
                      w * (p0[3 + k] + p1[3 + k] + p2[3 + k]);
                }
              for (unsigned int i = 0; i < 3; ++i)
                vector_area[c][i] += clipped[entry] * normal[entry][i];
            }
        }
      // the contact direction m: the normal of the largest clipped free
      // face (of the largest clipped face if none is free); the contact
      // area: the vector area of either tetrahedron's surface inside the
      // other projected onto m (the two are opposite: they close the
      // overlap's surface)
      unsigned int largest = 8;
      for (unsigned int entry = 0; entry < 8; ++entry)
        if ((free_faces[entry / 4] >> (entry % 4) & 1) && clipped[entry] > 0. &&
            (largest == 8 || clipped[entry] > clipped[largest]))
          largest = entry;
      if (largest == 8)
        {
          largest = 0;
          for (unsigned int entry = 1; entry < 8; ++entry)
            if (clipped[entry] > clipped[largest])
              largest = entry;
        }
      const double *m         = normal[largest];
      double        projected = 0.;
      for (unsigned int i = 0; i < 3; ++i)
        projected += (vector_area[0][i] - vector_area[1][i]) * m[i];
      interface.area = 0.5 * std::abs(projected);
      if (!(interface.area > 0.))
        {
          interface = TetrahedronContactInterface();
          return false;
        }
      // G: the centroid of the clipped faces weighted by their area
      // projected onto the contact direction m
      double weighted[2][4] = {}, weight_sum = 0.;
      for (unsigned int entry = 0; entry < 8; ++entry)
        {
          const double projection =
            std::abs(normal[entry][0] * m[0] + normal[entry][1] * m[1] +
                     normal[entry][2] * m[2]);
          weight_sum += projection * clipped[entry];
          for (unsigned int side = 0; side < 2; ++side)
            for (unsigned int k = 0; k < 4; ++k)
              weighted[side][k] += projection * sums[entry][side][k];
        }
      if (!(weight_sum > 0.))
        {
          interface = TetrahedronContactInterface();
          return false;
        }
      for (unsigned int side = 0; side < 2; ++side)
        {
          // G lies in both: round-off negatives clamped, then renormalised
          double sum = 0.;
          for (unsigned int k = 0; k < 4; ++k)
            {
              interface.shape[side][k] = std::max(weighted[side][k], 0.);
              sum += interface.shape[side][k];
            }
          for (double &N : interface.shape[side])
            N /= sum;
        }
      if (paper_literal)
        {
          interface.overlap_volume = overlap_volume_3d(x[0], coordinates[1]);
          double n[3], length = 0.;
          for (unsigned int i = 0; i < 3; ++i)
            {
              n[i] = 0.25 * (x[1][0][i] + x[1][1][i] + x[1][2][i] + x[1][3][i] -
                             x[0][0][i] - x[0][1][i] - x[0][2][i] - x[0][3][i]);
              length += n[i] * n[i];
            }
          length = std::sqrt(length);
          for (unsigned int side = 0; side < 2; ++side)
            for (unsigned int k = 0; k < 4; ++k)
              {
                const double *gradient = coordinates[side].gradient[k];
                interface.literal_weights[side][k] =
                  length > 0. ? interface.overlap_volume *
                                  (gradient[0] * n[0] + gradient[1] * n[1] +
                                   gradient[2] * n[2]) /
                                  length :
                                0.;
              }
        }
      return true;
    }

    /**
     * The contact heat of a pair of tetrahedra of geometry @p interface
     * (tetrahedron_contact_interface()) at the nodal temperatures @p T0 and
     * @p T1 [C] with the contact conductance @p h_c [W/(m^2 K)] and the
     * driving term @p model: Q into tetrahedron 0 (the contactor of the
     * transfer, tetrahedron 1 its target) [W], its split to the eight nodes
     * and, for the default model, the pair's conductance h_c A_c [W/K];
     * for the paper literal model the weights dQ/dT_j [W/K].
     */
    inline void
    tetrahedron_contact_heat(const ContactHeatModel             model,
                             const TetrahedronContactInterface &interface,
                             const double                      *T0,
                             const double                      *T1,
                             const double                       h_c,
                             TetrahedronContactHeat            &transfer)
    {
      transfer = TetrahedronContactHeat();
      if (!(interface.area > 0.))
        return;
      transfer.contactor_shape = interface.shape[0];
      transfer.target_shape    = interface.shape[1];
      transfer.contactor_temperature =
        interpolate_temperature(T0, transfer.contactor_shape);
      transfer.target_temperature =
        interpolate_temperature(T1, transfer.target_shape);
      if (model == ContactHeatModel::paper_literal)
        {
          // differences, so that isothermal tetrahedra exchange exactly 0
          const double *T[2] = {T0, T1};
          double        flow = 0.;
          for (unsigned int side = 0; side < 2; ++side)
            for (unsigned int k = 0; k < 4; ++k)
              {
                const double w = h_c * interface.literal_weights[side][k];
                transfer.flow_weights[4 * side + k] = w;
                if (k > 0)
                  flow += w * (T[side][k] - T[side][0]);
              }
          transfer.heat_flow = flow;
        }
      else
        {
          temperature_difference_heat(h_c * interface.area, transfer);
          return;
        }
      split_heat_exactly(transfer.heat_flow,
                         transfer.contactor_shape,
                         transfer.target_shape,
                         transfer.contactor_nodal_heat,
                         transfer.target_nodal_heat);
    }
  } // namespace discrete
} // namespace tmfdem

#endif
