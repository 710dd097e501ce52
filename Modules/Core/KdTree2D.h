#ifndef vimlop_KdTree2D_h
#define vimlop_KdTree2D_h

#include <Eigen/Core>

#include <algorithm>
#include <vector>

namespace vimlop
{

/**
 * @brief A 2-D k-d tree over points (pixels) for bounded nearest searches.
 *
 * visit() calls a visitor for every point that may lie within a search radius
 * that the visitor itself may shrink as it finds better candidates, which is
 * how the oriented contour match (V5) prunes with its cost bound.
 */
class KdTree2D
{
public:
  KdTree2D() = default;
  explicit KdTree2D(std::vector<Eigen::Vector2d> points);

  const std::vector<Eigen::Vector2d>& points() const { return this->Points; }
  bool empty() const { return this->Points.empty(); }

  /**
   * @brief Calls `visit(index)` for points whose distance² to `query` may be
   * at most `radius2`, nearer regions first. The visitor may lower `radius2`.
   */
  template <typename Visitor>
  void visit(const Eigen::Vector2d& query, double& radius2, Visitor&& visitor) const;

  /// @brief Index of the point nearest to `query`, -1 for an empty tree.
  int nearest(const Eigen::Vector2d& query) const;

private:
  struct Node
  {
    int first = 0; ///< leaf: first slot in Order
    int count = 0; ///< leaf: number of points, 0 for inner nodes
    int axis = 0;  ///< inner: split axis
    double split = 0.0;
    int right = -1; ///< inner: right child (the left child follows the node)
  };

  int build(int begin, int end);

  std::vector<Eigen::Vector2d> Points;
  std::vector<int> Order;
  std::vector<Node> Nodes;
};

template <typename Visitor>
void KdTree2D::visit(const Eigen::Vector2d& query, double& radius2, Visitor&& visitor) const
{
  if (this->Nodes.empty())
  {
    return;
  }
  // (node, squared distance from the query to the node's half-space side)
  std::pair<int, double> stack[128];
  int top = 0;
  stack[top++] = { 0, 0.0 };
  while (top > 0)
  {
    const auto [index, d2] = stack[--top];
    if (d2 > radius2)
    {
      continue;
    }
    const Node& node = this->Nodes[index];
    if (node.count > 0)
    {
      for (int i = node.first; i < node.first + node.count; ++i)
      {
        visitor(this->Order[i]);
      }
      continue;
    }
    const double delta = query[node.axis] - node.split;
    const int nearChild = delta <= 0.0 ? index + 1 : node.right;
    const int farChild = delta <= 0.0 ? node.right : index + 1;
    stack[top++] = { farChild, std::max(d2, delta * delta) };
    stack[top++] = { nearChild, d2 };
  }
}

} // namespace vimlop

#endif
