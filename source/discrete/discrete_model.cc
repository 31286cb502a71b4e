#include <deal.II/dofs/dof_handler.h>
#include <deal.II/grid/reference_cell.h>
#include <deal.II/grid/tria.h>

#include <cmath>
#include <numeric>
#include <set>
#include <sstream>
#include <tmfdem/base/exceptions.h>
#include <tmfdem/discrete/discrete_model.h>
#include <tmfdem/discrete/element_kernel.h>
#include <tmfdem/discrete/solid.h>
#include <unordered_map>

namespace tmfdem
{
  namespace discrete
  {
    void
    DiscreteModel::allocate(const unsigned int dimension,
                            const unsigned int elements)
    {
      dim                      = dimension;
      n_elements               = elements;
      n_nodes                  = nodes_per_element() * n_elements;
      const unsigned int faces = nodes_per_element();
      x_ref.assign(n_nodes, 0.);
      y_ref.assign(n_nodes, 0.);
      z_ref.assign(dim == 3 ? n_nodes : 0, 0.);
      node_vertex.assign(n_nodes, 0);
      mesh_index.resize(n_elements);
      std::iota(mesh_index.begin(), mesh_index.end(), 0u);
      mass.assign(n_nodes, 0.);
      vx.assign(n_nodes, 0.);
      vy.assign(n_nodes, 0.);
      vz.assign(dim == 3 ? n_nodes : 0, 0.);
      inverse_basis.assign(dim * dim * n_elements, 0.);
      reference_area.assign(n_elements, 0.);
      material.assign(n_elements, 0);
      body.assign(n_elements, no_body);
      thermal_stretch.assign(n_elements, 1.);
      stress.assign((dim == 3 ? 6 : 3) * n_elements, 0.);
      edge_joint.assign(faces * n_elements, -1);
      edge_boundary.assign(faces * n_elements,
                           numbers::internal_face_boundary_id);
      joint_nodes.clear();
      joint_elements.clear();
      joint_area.clear();
    }

    void
    DiscreteModel::build(const DoFHandler<2> &dof_handler)
    {
      allocate(2, dof_handler.get_triangulation().n_active_cells());
      if (dof_handler.n_dofs() != n_nodes)
        throw RunError("discrete layer: the DoFHandler has " +
                       std::to_string(dof_handler.n_dofs()) +
                       " DoFs, expected 3 per triangle (FE_SimplexDGP(1)).");

      std::vector<types::global_dof_index> dofs(3);
      auto                                 local_edge =
        [](const auto &cell, const unsigned int v0, const unsigned int v1) {
          for (unsigned int k = 0; k < 3; ++k)
            {
              const unsigned int a = cell->vertex_index(k);
              const unsigned int b = cell->vertex_index((k + 1) % 3);
              if ((a == v0 && b == v1) || (a == v1 && b == v0))
                return k;
            }
          return 3u;
        };

      for (const auto &cell : dof_handler.active_cell_iterators())
        {
          const unsigned int e = cell->active_cell_index();
          if (cell->reference_cell() != ReferenceCells::Triangle)
            throw InputError("discrete layer: cell " + std::to_string(e) +
                             " is not a triangle; the discrete layer needs "
                             "a triangle mesh (Mesh/Element type = "
                             "triangles).");
          cell->get_dof_indices(dofs);
          for (unsigned int k = 0; k < 3; ++k)
            if (dofs[k] != 3 * e + k)
              throw RunError("discrete layer: unexpected DoF numbering of "
                             "FE_SimplexDGP(1) at cell " +
                             std::to_string(e) + ".");
          for (unsigned int k = 0; k < 3; ++k)
            {
              x_ref[3 * e + k]       = cell->vertex(k)[0];
              y_ref[3 * e + k]       = cell->vertex(k)[1];
              node_vertex[3 * e + k] = cell->vertex_index(k);
            }
          material[e]         = cell->material_id();
          const Matrix2 basis = element_basis(x_ref[3 * e],
                                              y_ref[3 * e],
                                              x_ref[3 * e + 1],
                                              y_ref[3 * e + 1],
                                              x_ref[3 * e + 2],
                                              y_ref[3 * e + 2]);
          const double  det   = basis.determinant();
          if (!(det > 0.))
            {
              std::ostringstream where;
              where << "(" << cell->center()[0] << ", " << cell->center()[1]
                    << ")";
              throw InputError("discrete layer: triangle " + std::to_string(e) +
                               " at " + where.str() + " has " +
                               (det == 0. ? std::string("zero area") :
                                            std::string("clockwise nodes")) +
                               "; every triangle must have positive area "
                               "with counter-clockwise nodes.");
            }
          const Matrix2 inv        = basis.inverse();
          inverse_basis[4 * e + 0] = inv(0, 0);
          inverse_basis[4 * e + 1] = inv(0, 1);
          inverse_basis[4 * e + 2] = inv(1, 0);
          inverse_basis[4 * e + 3] = inv(1, 1);
          reference_area[e]        = 0.5 * det;

          for (unsigned int f = 0; f < 3; ++f)
            {
              const auto         face = cell->face(f);
              const unsigned int k =
                local_edge(cell, face->vertex_index(0), face->vertex_index(1));
              if (face->at_boundary())
                {
                  edge_boundary[3 * e + k] = face->boundary_id();
                  continue;
                }
              const auto neighbour = cell->neighbor(f);
              if (neighbour->has_children() ||
                  neighbour->level() != cell->level())
                throw InputError(
                  "discrete layer: the mesh has hanging nodes at triangle " +
                  std::to_string(e) +
                  "; the discrete layer needs a conforming mesh (use global "
                  "refinement only).");
              const unsigned int n = neighbour->active_cell_index();
              if (n < e)
                continue; // made when visiting n
              const unsigned int j  = joint_elements.size() / 2;
              const unsigned int a0 = 3 * e + k, a1 = 3 * e + (k + 1) % 3;
              unsigned int       b0 = 0, b1 = 0;
              for (unsigned int m = 0; m < 3; ++m)
                {
                  if (neighbour->vertex_index(m) == cell->vertex_index(k))
                    b0 = 3 * n + m;
                  if (neighbour->vertex_index(m) ==
                      cell->vertex_index((k + 1) % 3))
                    b1 = 3 * n + m;
                }
              const unsigned int kb =
                local_edge(neighbour,
                           cell->vertex_index(k),
                           cell->vertex_index((k + 1) % 3));
              joint_nodes.insert(joint_nodes.end(), {a0, a1, b0, b1});
              joint_elements.insert(joint_elements.end(), {e, n});
              edge_joint[3 * e + k]  = 2 * j;
              edge_joint[3 * n + kb] = 2 * j + 1;
            }
        }
      n_joints = joint_elements.size() / 2;
      x        = x_ref;
      y        = y_ref;
      joint_constants.assign(n_joints, JointConstants());
      joint_length.assign(n_joints, 0.);
      for (unsigned int j = 0; j < n_joints; ++j)
        {
          const unsigned int a0 = joint_nodes[4 * j],
                             a1 = joint_nodes[4 * j + 1];
          joint_length[j] =
            std::hypot(x_ref[a1] - x_ref[a0], y_ref[a1] - y_ref[a0]);
        }
      joint_damage.assign(2 * n_joints, 0.);
      joint_status.assign(n_joints, JointStatus::intact);
      joint_break_time.assign(n_joints, -1.);
      node_joint_force.assign(4 * n_nodes, 0.);
    }

    void
    DiscreteModel::build(const DoFHandler<3> &dof_handler)
    {
      allocate(3, dof_handler.get_triangulation().n_active_cells());
      if (dof_handler.n_dofs() != n_nodes)
        throw RunError("discrete layer: the DoFHandler has " +
                       std::to_string(dof_handler.n_dofs()) +
                       " DoFs, expected 4 per tetrahedron (FE_SimplexDGP(1)).");

      // the local vertex of @p cell at the global vertex @p v (4: none)
      const auto local_vertex = [](const auto &cell, const unsigned int v) {
        for (unsigned int m = 0; m < 4; ++m)
          if (cell->vertex_index(m) == v)
            return m;
        return 4u;
      };
      std::vector<types::global_dof_index> dofs(4);
      for (const auto &cell : dof_handler.active_cell_iterators())
        {
          const unsigned int e = cell->active_cell_index();
          std::ostringstream where;
          where << "(" << cell->center() << ")";
          if (cell->reference_cell() != ReferenceCells::Tetrahedron)
            throw InputError("discrete layer: cell " + std::to_string(e) +
                             " at " + where.str() +
                             " is not a tetrahedron; the discrete layer in "
                             "3D needs a tetrahedral mesh (Mesh/Element type "
                             "= tetrahedra).");
          cell->get_dof_indices(dofs);
          for (unsigned int k = 0; k < 4; ++k)
            if (dofs[k] != 4 * e + k)
              throw RunError("discrete layer: unexpected DoF numbering of "
                             "FE_SimplexDGP(1) at cell " +
                             std::to_string(e) + ".");
          for (unsigned int k = 0; k < 4; ++k)
            {
              x_ref[4 * e + k]       = cell->vertex(k)[0];
              y_ref[4 * e + k]       = cell->vertex(k)[1];
              z_ref[4 * e + k]       = cell->vertex(k)[2];
              node_vertex[4 * e + k] = cell->vertex_index(k);
            }
          material[e] = cell->material_id();
          // the basis [x1 - x0, x2 - x0, x3 - x0] (columns), its inverse
          const double *const nodes[3] = {&x_ref[4 * e],
                                          &y_ref[4 * e],
                                          &z_ref[4 * e]};
          double              basis[3][3], inverse_matrix[3][3];
          for (unsigned int i = 0; i < 3; ++i)
            for (unsigned int k = 0; k < 3; ++k)
              basis[i][k] = nodes[i][k + 1] - nodes[i][0];
          const double det = constitutive::determinant<3>(basis);
          if (!(det > 0.))
            throw InputError(
              "discrete layer: tetrahedron " + std::to_string(e) + " at " +
              where.str() + " has " +
              (det == 0. ? std::string("zero volume") :
                           std::string("negatively oriented vertices")) +
              "; every tetrahedron must have positive volume with "
              "(x1 - x0) x (x2 - x0) . (x3 - x0) > 0.");
          inverse<3>(basis, det, inverse_matrix);
          for (unsigned int i = 0; i < 3; ++i)
            for (unsigned int k = 0; k < 3; ++k)
              inverse_basis[9 * e + 3 * i + k] = inverse_matrix[i][k];
          reference_area[e] = det / 6.;

          for (unsigned int f = 0; f < 4; ++f)
            {
              const auto face = cell->face(f);
              if (face->at_boundary())
                {
                  edge_boundary[4 * e + f] = face->boundary_id();
                  continue;
                }
              const auto neighbour = cell->neighbor(f);
              if (neighbour->has_children() ||
                  neighbour->level() != cell->level())
                throw InputError(
                  "discrete layer: the mesh has hanging nodes at "
                  "tetrahedron " +
                  std::to_string(e) + " at " + where.str() +
                  "; the discrete layer needs a conforming mesh (use global "
                  "refinement only).");
              const unsigned int n = neighbour->active_cell_index();
              if (n < e)
                continue; // made when visiting n
              // the face's vertices in A, ordered so that (a1 - a0) x
              // (a2 - a0) points out of A (away from its fourth vertex)
              unsigned int a[3];
              for (unsigned int k = 0; k < 3; ++k)
                a[k] = local_vertex(cell, face->vertex_index(k));
              const unsigned int opposite = 6 - a[0] - a[1] - a[2];
              double             e1[3], e2[3], to_opposite[3];
              for (unsigned int i = 0; i < 3; ++i)
                {
                  e1[i]          = nodes[i][a[1]] - nodes[i][a[0]];
                  e2[i]          = nodes[i][a[2]] - nodes[i][a[0]];
                  to_opposite[i] = nodes[i][opposite] - nodes[i][a[0]];
                }
              const double orientation =
                (e1[1] * e2[2] - e1[2] * e2[1]) * to_opposite[0] +
                (e1[2] * e2[0] - e1[0] * e2[2]) * to_opposite[1] +
                (e1[0] * e2[1] - e1[1] * e2[0]) * to_opposite[2];
              if (orientation > 0.)
                std::swap(a[1], a[2]);
              unsigned int b[3];
              for (unsigned int k = 0; k < 3; ++k)
                b[k] = local_vertex(neighbour, cell->vertex_index(a[k]));
              // the neighbour's face that is this one
              const unsigned int fb = cell->neighbor_of_neighbor(f);
              const unsigned int j  = joint_elements.size() / 2;
              joint_nodes.insert(joint_nodes.end(),
                                 {4 * e + a[0],
                                  4 * e + a[1],
                                  4 * e + a[2],
                                  4 * n + b[0],
                                  4 * n + b[1],
                                  4 * n + b[2]});
              joint_elements.insert(joint_elements.end(), {e, n});
              edge_joint[4 * e + f]  = 2 * j;
              edge_joint[4 * n + fb] = 2 * j + 1;
            }
        }
      n_joints = joint_elements.size() / 2;
      x        = x_ref;
      y        = y_ref;
      z        = z_ref;
      joint_constants.assign(n_joints, JointConstants());
      joint_length.assign(n_joints, 0.);
      joint_area.assign(n_joints, 0.);
      for (unsigned int j = 0; j < n_joints; ++j)
        {
          const unsigned int *a = &joint_nodes[6 * j];
          const auto edge = [&](const unsigned int p, const unsigned int q) {
            return std::sqrt((x_ref[q] - x_ref[p]) * (x_ref[q] - x_ref[p]) +
                             (y_ref[q] - y_ref[p]) * (y_ref[q] - y_ref[p]) +
                             (z_ref[q] - z_ref[p]) * (z_ref[q] - z_ref[p]));
          };
          joint_length[j] =
            (edge(a[0], a[1]) + edge(a[1], a[2]) + edge(a[2], a[0])) / 3.;
          double e1[3], e2[3];
          for (unsigned int i = 0; i < 3; ++i)
            {
              const std::vector<double> &c =
                i == 0 ? x_ref : (i == 1 ? y_ref : z_ref);
              e1[i] = c[a[1]] - c[a[0]];
              e2[i] = c[a[2]] - c[a[0]];
            }
          joint_area[j] =
            0.5 * std::sqrt(std::pow(e1[1] * e2[2] - e1[2] * e2[1], 2) +
                            std::pow(e1[2] * e2[0] - e1[0] * e2[2], 2) +
                            std::pow(e1[0] * e2[1] - e1[1] * e2[0], 2));
        }
      joint_damage.assign(3 * n_joints, 0.);
      joint_status.assign(n_joints, JointStatus::intact);
      joint_break_time.assign(n_joints, -1.);
      // per node: the forces of the joints on its three faces (x, y, z each)
      node_joint_force.assign(9 * n_nodes, 0.);
    }

    void
    DiscreteModel::check_boundary_ids(
      const std::string                     &entry,
      const std::vector<types::boundary_id> &ids) const
    {
      std::set<types::boundary_id> mesh_ids;
      for (const auto id : edge_boundary)
        if (id != numbers::internal_face_boundary_id)
          mesh_ids.insert(id);
      for (const auto id : ids)
        if (mesh_ids.count(id) == 0)
          {
            std::string on_mesh;
            for (const auto m : mesh_ids)
              on_mesh += " " + std::to_string(m);
            throw InputError(entry + ": boundary id " + std::to_string(id) +
                             " is not on the mesh; the mesh has boundary ids" +
                             on_mesh + ".");
          }
    }

    void
    DiscreteModel::contact_candidate_elements(
      std::vector<unsigned int> &elements) const
    {
      std::vector<unsigned char> free_edge(n_elements, 0);
      for (unsigned int e = 0; e < n_elements; ++e)
        for (unsigned int k = 0; k < nodes_per_element(); ++k)
          if (intact_neighbour(e, k) < 0)
            {
              free_edge[e] = 1;
              break;
            }
      std::vector<unsigned char> candidate = free_edge;
      for (unsigned int e = 0; e < n_elements; ++e)
        if (free_edge[e])
          for (unsigned int k = 0; k < nodes_per_element(); ++k)
            {
              const int neighbour = intact_neighbour(e, k);
              if (neighbour >= 0)
                candidate[neighbour] = 1;
            }
      elements.clear();
      for (unsigned int e = 0; e < n_elements; ++e)
        if (candidate[e])
          elements.push_back(e);
    }

    void
    DiscreteModel::intact_pieces(std::vector<unsigned int> &piece) const
    {
      piece.resize(n_elements);
      for (unsigned int e = 0; e < n_elements; ++e)
        piece[e] = e;
      const auto root = [&piece](unsigned int e) {
        while (piece[e] != e)
          e = piece[e] = piece[piece[e]];
        return e;
      };
      for (unsigned int j = 0; j < n_joints; ++j)
        if (joint_status[j] == JointStatus::intact)
          {
            const unsigned int ra   = root(joint_elements[2 * j]),
                               rb   = root(joint_elements[2 * j + 1]);
            piece[std::max(ra, rb)] = std::min(ra, rb);
          }
      for (unsigned int e = 0; e < n_elements; ++e)
        piece[e] = root(e);
    }

    unsigned int
    DiscreteModel::n_broken_joints() const
    {
      unsigned int n = 0;
      for (const auto status : joint_status)
        n += status != JointStatus::intact;
      return n;
    }

    unsigned int
    DiscreteModel::n_damaged_joints() const
    {
      unsigned int       n = 0;
      const unsigned int q = gauss_points_per_joint();
      for (unsigned int j = 0; j < n_joints; ++j)
        {
          bool damaged = joint_status[j] != JointStatus::intact;
          for (unsigned int p = 0; p < q; ++p)
            damaged = damaged || joint_damage[q * j + p] > 0.;
          n += damaged;
        }
      return n;
    }

    unsigned int
    DiscreteModel::n_cracks() const
    {
      std::vector<unsigned int> parent(n_joints);
      std::iota(parent.begin(), parent.end(), 0u);
      auto find = [&](unsigned int a) {
        while (parent[a] != a)
          a = parent[a] = parent[parent[a]];
        return a;
      };
      std::unordered_map<unsigned int, unsigned int> joint_at_vertex;
      unsigned int                                   n_broken = 0;
      for (unsigned int j = 0; j < n_joints; ++j)
        if (joint_status[j] != JointStatus::intact)
          {
            ++n_broken;
            // the vertices of the edge or face (its nodes on side A)
            for (unsigned int end = 0; end < dim; ++end)
              {
                const unsigned int vertex =
                  node_vertex[joint_nodes[nodes_per_joint() * j + end]];
                const auto [it, inserted] = joint_at_vertex.emplace(vertex, j);
                if (!inserted)
                  {
                    const unsigned int r1 = find(j), r2 = find(it->second);
                    if (r1 != r2)
                      {
                        parent[r1] = r2;
                        --n_broken;
                      }
                  }
              }
          }
      return n_broken;
    }
  } // namespace discrete
} // namespace tmfdem
