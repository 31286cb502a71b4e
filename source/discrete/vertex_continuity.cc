#include <tmfdem/discrete/discrete_model.h>
#include <tmfdem/discrete/vertex_continuity.h>

namespace tmfdem
{
  namespace discrete
  {
    void
    VertexContinuity::update(const DiscreteModel &model)
    {
      nodes_per_element         = model.nodes_per_element();
      node_vertex               = &model.node_vertex;
      const std::size_t n_nodes = model.node_vertex.size();
      piece.resize(n_nodes);
      for (std::size_t n = 0; n < n_nodes; ++n)
        piece[n] = static_cast<unsigned int>(n);
      const auto root = [this](unsigned int n) {
        while (piece[n] != n)
          n = piece[n] = piece[piece[n]];
        return n;
      };
      // a joint's nodes a_i and b_i sit on the same vertex: an intact joint
      // joins its two elements around each vertex of its edge or face
      const unsigned int per_side = model.nodes_per_joint() / 2;
      for (unsigned int j = 0; j < model.n_joints; ++j)
        if (model.joint_status[j] == JointStatus::intact)
          for (unsigned int i = 0; i < per_side; ++i)
            {
              const unsigned int ra =
                root(model.joint_nodes[2 * per_side * j + i]);
              const unsigned int rb =
                root(model.joint_nodes[2 * per_side * j + per_side + i]);
              if (ra < rb)
                piece[rb] = ra;
              else
                piece[ra] = rb;
            }
      for (std::size_t n = 0; n < n_nodes; ++n)
        piece[n] = root(static_cast<unsigned int>(n));
    }

    bool
    VertexContinuity::continuous(const unsigned int a,
                                 const unsigned int b) const
    {
      const unsigned int               m      = nodes_per_element;
      const std::vector<unsigned int> &vertex = *node_vertex;
      unsigned int                     shared = 0;
      for (unsigned int k = 0; k < m; ++k)
        for (unsigned int l = 0; l < m; ++l)
          if (vertex[m * a + k] == vertex[m * b + l])
            {
              if (piece[m * a + k] != piece[m * b + l])
                return false;
              ++shared;
            }
      // a face (2D: an edge) is shared by dim vertices, one less than m
      return shared > 0 && shared + 1 < m;
    }
  } // namespace discrete
} // namespace tmfdem
