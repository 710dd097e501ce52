#include <vimlop/Core/KdTree2D.h>

#include <limits>
#include <numeric>

namespace vimlop
{

namespace
{
constexpr int LeafSize = 8;
}

KdTree2D::KdTree2D(std::vector<Eigen::Vector2d> points)
  : Points(std::move(points))
{
  if (this->Points.empty())
  {
    return;
  }
  this->Order.resize(this->Points.size());
  std::iota(this->Order.begin(), this->Order.end(), 0);
  this->build(0, static_cast<int>(this->Points.size()));
}

int KdTree2D::build(int begin, int end)
{
  const int index = static_cast<int>(this->Nodes.size());
  this->Nodes.emplace_back();
  if (end - begin <= LeafSize)
  {
    this->Nodes[index].first = begin;
    this->Nodes[index].count = end - begin;
    return index;
  }
  Eigen::Vector2d lo = this->Points[this->Order[begin]];
  Eigen::Vector2d hi = lo;
  for (int i = begin; i < end; ++i)
  {
    lo = lo.cwiseMin(this->Points[this->Order[i]]);
    hi = hi.cwiseMax(this->Points[this->Order[i]]);
  }
  const int axis = (hi - lo).x() >= (hi - lo).y() ? 0 : 1;
  const int mid = begin + (end - begin) / 2;
  std::nth_element(this->Order.begin() + begin, this->Order.begin() + mid,
    this->Order.begin() + end,
    [&](int a, int b) { return this->Points[a][axis] < this->Points[b][axis]; });
  this->Nodes[index].axis = axis;
  this->Nodes[index].split = this->Points[this->Order[mid]][axis];
  this->build(begin, mid);
  this->Nodes[index].right = this->build(mid, end);
  return index;
}

int KdTree2D::nearest(const Eigen::Vector2d& query) const
{
  int best = -1;
  double radius2 = std::numeric_limits<double>::infinity();
  this->visit(query, radius2,
    [&](int i)
    {
      const double d2 = (this->Points[i] - query).squaredNorm();
      if (d2 < radius2)
      {
        radius2 = d2;
        best = i;
      }
    });
  return best;
}

} // namespace vimlop
