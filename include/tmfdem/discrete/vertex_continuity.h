/**
 * @file
 * Which elements of the exploded mesh are still one piece of material
 * around a vertex they share: the elements that hold a vertex of the
 * original mesh (its star), joined where an intact joint's face or edge
 * holds that vertex. The 3D contact search leaves out the pairs of
 * tetrahedra that share a vertex or an edge and are continuous around it:
 * their corners overlap only through the joints' compliance, not because
 * two pieces touch (doc/theory.md 5.13).
 */
#ifndef tmfdem_discrete_vertex_continuity_h
#define tmfdem_discrete_vertex_continuity_h

#include <vector>

namespace tmfdem
{
  namespace discrete
  {
    class DiscreteModel;

    /**
     * The pieces of material around each vertex of the original mesh: per
     * node of the exploded mesh the smallest node it is connected to
     * through intact joints that hold the node's vertex (a union-find over
     * the joints' coinciding node pairs, O(nodes)). Rebuilt with update()
     * after joints broke.
     */
    class VertexContinuity
    {
    public:
      /** Labels the nodes of @p model from its intact joints; @p model
       *  must outlive the calls to continuous(). */
      void
      update(const DiscreteModel &model);

      /**
       * Whether elements @p a and @p b (of dim + 1 nodes each, as in
       * update()'s model) share at least one vertex of the original mesh,
       * share no face (a face pair is governed by its own joint), and are
       * one piece of material around every vertex they share. Safe to call
       * from several threads.
       */
      bool
      continuous(const unsigned int a, const unsigned int b) const;

    private:
      unsigned int nodes_per_element = 0;
      /** The model's vertex of each node (DiscreteModel::node_vertex). */
      const std::vector<unsigned int> *node_vertex = nullptr;
      std::vector<unsigned int>        piece; ///< per node
    };
  } // namespace discrete
} // namespace tmfdem

#endif
