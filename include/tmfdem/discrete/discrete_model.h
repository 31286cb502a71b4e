/**
 * @file
 * The state of the discrete layer in flat structure-of-arrays form: the
 * exploded mesh (every simplex owns its nodes: in 2D node 3e+k is local node
 * k of triangle e, counter-clockwise; in 3D node 4e+k is local vertex k of
 * tetrahedron e, positively oriented), the joints on every interior edge
 * (2D) or triangular face (3D), and the per-element and per-joint history.
 * Built once from a deal.II triangulation; the explicit loop touches nothing
 * else. The strides follow the dimension: dim + 1 nodes and faces per
 * element, 2 dim nodes and dim Gauss points per joint, dim^2 entries of the
 * inverse basis per element.
 *
 * Node numbering equals the DoF numbering of FE_SimplexDGP(1) on the same
 * triangulation (checked when built), so a nodal field of the discrete layer
 * is a deal.II Vector on that DoFHandler. The discrete solvers build that
 * triangulation with its cells along a Hilbert curve (mesh/cell_order.h).
 */
#ifndef tmfdem_discrete_discrete_model_h
#define tmfdem_discrete_discrete_model_h

#include <deal.II/base/types.h>
#include <deal.II/dofs/dof_handler.h>

#include <string>
#include <tmfdem/discrete/cohesive_law.h>
#include <vector>

namespace tmfdem
{
  using namespace dealii;

  namespace discrete
  {
    /** How a joint ended. */
    enum class JointStatus : unsigned char
    {
      intact  = 0,
      mode_I  = 1, ///< broken in tension
      mode_II = 2, ///< broken in shear
      mixed   = 3  ///< broken in mixed mode
    };

    /** The body index of elements and nodes that belong to no body
     *  (Discrete bodies): they move freely. */
    constexpr unsigned char no_body = 255;

    /** The flat state of the discrete layer. Units SI. */
    struct DiscreteModel
    {
      /** Space dimension: 2 (triangles, joints on edges) or 3 (tetrahedra,
       *  joints on triangular faces). */
      unsigned int dim        = 2;
      unsigned int n_elements = 0;
      unsigned int n_nodes    = 0;
      unsigned int n_joints   = 0;

      /** Nodes (and faces) per element: dim + 1. */
      unsigned int
      nodes_per_element() const
      {
        return dim + 1;
      }
      /** Nodes per joint: dim on each side. */
      unsigned int
      nodes_per_joint() const
      {
        return 2 * dim;
      }
      /** Gauss points per joint: 2 on an edge, 3 on a triangular face. */
      unsigned int
      gauss_points_per_joint() const
      {
        return dim;
      }

      // ------------------------------------------------------------ nodes
      std::vector<double> x, y;         ///< current position [m]
      std::vector<double> x_ref, y_ref; ///< reference position [m]
      std::vector<double> vx, vy;       ///< velocity (half step) [m/s]
      /** The third components in 3D (empty in 2D) [m], [m/s]. */
      std::vector<double> z, z_ref, vz;
      /** Lumped mass [kg/m in 2D, kg in 3D]. */
      std::vector<double> mass;
      /** Vertex of the original (unexploded) mesh the node sits on. */
      std::vector<unsigned int> node_vertex;

      /** Index of each element in the mesh's own order (after global
       *  refinement, before the triangles were renumbered along a Hilbert
       *  curve; the identity otherwise). What must not depend on the
       *  numbering (random joint strengths, monitor elements) goes by it. */
      std::vector<unsigned int> mesh_index;

      // --------------------------------------------------------- elements
      /** Inverse initial basis F_i^-1 (row-major dim x dim) per element
       *  [1/m]. */
      std::vector<double> inverse_basis;
      /** Reference area of a triangle [m^2], volume of a tetrahedron
       *  [m^3]. */
      std::vector<double>             reference_area;
      std::vector<types::material_id> material;
      /** Body index per element (see DiscreteBodyParameters), or no_body. */
      std::vector<unsigned char> body;
      /** N of the `Discrete bodies/Body N` subsection of each body index
       *  (outputs name the bodies by it). */
      std::vector<unsigned int> body_number;
      /** In-plane thermal stretch s of F_T = s I per element [-]; 1 here,
       *  set by the thermal coupling. */
      std::vector<double> thermal_stretch;
      /** Factor of the material's thermal expansion coefficient per element
       *  [-] (Discrete mechanics/Expansion heterogeneity, heterogeneity.h);
       *  empty: 1 everywhere. */
      std::vector<double> expansion_factor;
      /** Cauchy stress of the last step per element (2D: xx, yy, xy; 3D:
       *  xx, yy, zz, xy, yz, xz) [Pa]. */
      std::vector<double> stress;
      /**
       * Per element edge k (2D: nodes k -> k+1) or face k (3D: deal.II's
       * face k of the tetrahedron): 2 j + side for joint j with the element
       * on side 0 (A) or 1 (B), or -1 for a boundary edge or face.
       */
      std::vector<int> edge_joint;
      /** Boundary id per element edge or face
       *  (numbers::internal_face_boundary_id for interior ones). */
      std::vector<types::boundary_id> edge_boundary;

      // ----------------------------------------------------------- joints
      /** 2D: nodes a0, a1 (edge of element A, counter-clockwise in A) and
       *  b0, b1 of element B coinciding initially with a0, a1. 3D: a0, a1,
       *  a2 (face of A, (a1 - a0) x (a2 - a0) pointing out of A) and b0, b1,
       *  b2 of B coinciding initially with them. */
      std::vector<unsigned int>   joint_nodes;
      std::vector<unsigned int>   joint_elements; ///< A, B per joint
      std::vector<JointConstants> joint_constants;
      /** Reference size of each joint [m]: the edge's length in 2D, the
       *  mean length of the face's three edges in 3D (the penalties are
       *  per this size: make_joint_constants()). */
      std::vector<double> joint_length;
      /** Reference area of each face joint [m^2] (3D; empty in 2D). */
      std::vector<double> joint_area;
      /** Damage per Gauss point (2 per joint in 2D, 3 in 3D) [-]. */
      std::vector<double>      joint_damage;
      std::vector<JointStatus> joint_status;
      std::vector<double>      joint_break_time; ///< [s]
      /**
       * The joint forces of the last step per node [N/m], four per node:
       * (x, y) from the joint of the element edge that starts at the node,
       * then (x, y) from the joint of the edge that ends there (counter-
       * clockwise in the node's triangle; a0 and b1 start a joint's edge,
       * a1 and b0 end it). Each slot has one writer (the joint of that
       * edge), so the joint pass scatters without conflicts and the node
       * update reads its node's forces in order, without indirection. Zero
       * where the edge has no intact joint. In 3D nine per node: (x, y, z)
       * from the joint of each of the element's three faces at the node, in
       * the order of the element's faces. Not state: every step forms it
       * before the node update reads it (not in checkpoints).
       */
      std::vector<double> node_joint_force;

      /**
       * Builds the exploded mesh from @p dof_handler, which must carry
       * FE_SimplexDGP(1) on a serial triangle mesh. Joint constants are left
       * for the caller. Throws InputError for cells with non-positive area
       * (naming the cell).
       */
      void
      build(const DoFHandler<2> &dof_handler);

      /**
       * The same in 3D from @p dof_handler with FE_SimplexDGP(1) on a
       * serial tetrahedral mesh: joints on every interior triangular face.
       * Throws InputError for a cell that is not a tetrahedron or has a
       * non-positive volume, and for hanging nodes (naming the cell).
       */
      void
      build(const DoFHandler<3> &dof_handler);

      /** Sets @p dimension and @p elements, sizes every per-node and
       *  per-element array for them (zero, no joints; thermal stretch 1,
       *  no body): the first step of build(). */
      void
      allocate(const unsigned int dimension, const unsigned int elements);

      /** Elements joined across edge k of element e by an intact joint, or
       *  -1. */
      int
      intact_neighbour(const unsigned int e, const unsigned int k) const
      {
        const int code = edge_joint[nodes_per_element() * e + k];
        if (code < 0)
          return -1;
        const unsigned int j = code / 2;
        if (joint_status[j] != JointStatus::intact)
          return -1;
        return joint_elements[2 * j + 1 - code % 2];
      }

      /** The joint (intact or broken) between elements @p a and @p b, or
       *  -1 if they share no edge or face. */
      int
      joint_between(const unsigned int a, const unsigned int b) const
      {
        for (unsigned int k = 0; k < nodes_per_element(); ++k)
          {
            const int code = edge_joint[nodes_per_element() * a + k];
            if (code >= 0 && joint_elements[2 * (code / 2) + 1 - code % 2] == b)
              return code / 2;
          }
        return -1;
      }

      /** True if an intact joint joins elements @p a and @p b. */
      bool
      joined(const unsigned int a, const unsigned int b) const
      {
        for (unsigned int k = 0; k < nodes_per_element(); ++k)
          if (intact_neighbour(a, k) == static_cast<int>(b))
            return true;
        return false;
      }

      /**
       * Throws InputError naming @p entry (e.g. "Thermal boundary
       * conditions/Condition 1/Boundary ids") if a boundary id in @p ids is
       * not on the mesh, listing those that are.
       */
      void
      check_boundary_ids(const std::string                     &entry,
                         const std::vector<types::boundary_id> &ids) const;

      /** Number of broken joints. */
      unsigned int
      n_broken_joints() const;

      /**
       * The elements that can touch another element: those with a free
       * edge (boundary or broken joint) and their intact neighbours, in
       * index order, written into @p elements. The contact search of the
       * mechanics and that of the contact heat both start from this set.
       */
      void
      contact_candidate_elements(std::vector<unsigned int> &elements) const;

      /** The pieces of the model: elements connected by intact joints get
       *  the same index (the smallest element of the piece), written to
       *  @p piece (one per element). */
      void
      intact_pieces(std::vector<unsigned int> &piece) const;

      /** Number of joints whose traction has reached the strength at some
       * time (damage > 0 at a Gauss point), broken ones included. */
      unsigned int
      n_damaged_joints() const;

      /** Number of cracks: connected sets of broken joints (joints that
       *  share a vertex of the original mesh are connected). */
      unsigned int
      n_cracks() const;
    };
  } // namespace discrete
} // namespace tmfdem

#endif
