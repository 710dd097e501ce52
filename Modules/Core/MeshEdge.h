#ifndef vimlop_MeshEdge_h
#define vimlop_MeshEdge_h

namespace vimlop
{

/**
 * @brief An edge of a triangle mesh with the faces on either side.
 *
 * `vertex0 < vertex1`. `face1` is -1 on an open boundary. An edge shared by
 * more than two faces is non-manifold: `face0` and `face1` are then the first
 * two and `nonManifold` is set.
 */
struct MeshEdge
{
  int vertex0 = -1;
  int vertex1 = -1;
  int face0 = -1;
  int face1 = -1;
  bool nonManifold = false;

  bool isBoundary() const { return face1 < 0; }
};

} // namespace vimlop

#endif
