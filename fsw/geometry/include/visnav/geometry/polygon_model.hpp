// Polygon target model (paper sec. II-H): vertices, planar surfaces as vertex lists in counter-clockwise
// order seen from outside, and stored outward normals. Built and validated once at init; read-only
// afterwards.
#pragma once

#include <cstddef>
#include <string>
#include <vector>

#include "visnav/core/status.hpp"
#include "visnav/core/types.hpp"

namespace visnav {

struct ModelSurface {
  std::string name;
  std::vector<int> vertex_indices;  ///< >= 3, counter-clockwise seen from outside (right-hand rule = normal)
  Vec3 normal_m = Vec3::Zero();     ///< outward unit normal in the model frame (stored, sec. II-H)
  Vec3 centroid_m = Vec3::Zero();
  double albedo = 0.8;  ///< brightness in [0, 1] for rendering; optional in files
};

struct ModelEdge {
  int v0 = -1;
  int v1 = -1;
  int surface_left = -1;   ///< surface in which v0 -> v1 runs counter-clockwise
  int surface_right = -1;  ///< the neighbouring surface sharing the edge, -1 for an open boundary
};

class PolygonModel {
 public:
  /// Bounds on a model (fsw/io/README.md, "Limits"). Not parameters: they bound the work and memory of
  /// loading a wrong or hostile file, and a real target is orders of magnitude inside them.
  static constexpr std::size_t kMaxVertices = 100000;
  static constexpr std::size_t kMaxSurfaces = 100000;
  static constexpr std::size_t kMaxSurfaceVertices = 1000;
  /// |coordinate| bound [m]: a spacecraft target is metres across; 10 km leaves room for any unit slip
  /// while keeping every cross product far from overflow (1e300 gave NaN normals).
  static constexpr double kMaxCoordinateM = 1e4;

  /// Validates and builds. Checks: counts within the bounds above, finite coordinates within
  /// kMaxCoordinateM, >= 3 vertices per surface, indices in range, no repeated vertex, planarity
  /// (tolerance 1e-6 relative to size), convex simple polygon (every turn the same way and the turns add
  /// up to one full turn: a star, whose turns add up to two or more, is rejected), finite normal, stored
  /// normal within 1 degree of the one implied by the vertex order (a zero stored normal means "compute
  /// it"), each edge shared by at most two surfaces and traversed in opposite directions by them. On error
  /// `out` is left untouched.
  static LoadError build(const std::vector<Vec3>& vertices, std::vector<ModelSurface> surfaces,
                         PolygonModel& out);

  const std::vector<Vec3>& vertices() const { return m_vertices; }
  const std::vector<ModelSurface>& surfaces() const { return m_surfaces; }
  const std::vector<ModelEdge>& edges() const { return m_edges; }
  /// Edge index for the surface's k-th side (vertex k -> k+1).
  int surfaceEdge(int surface, int k) const { return m_surface_edges[surface][k]; }
  int maxSurfaceVertices() const { return m_max_surface_vertices; }
  /// Radius of the smallest origin-centred sphere holding every vertex [m].
  double boundingRadius() const { return m_bounding_radius; }

 private:
  std::vector<Vec3> m_vertices;
  std::vector<ModelSurface> m_surfaces;
  std::vector<ModelEdge> m_edges;
  std::vector<std::vector<int>> m_surface_edges;
  int m_max_surface_vertices = 0;
  double m_bounding_radius = 0.0;
};

/// A flat rectangular plate of width x height [m] in the model x-y plane, normal +z (the paper's 4-edge
/// target).
PolygonModel makeRectanglePlate(double width_m, double height_m, double albedo = 0.8);
/// A rectangle w x h [m] with its corners cut by `chamfer_m` along each side, or a regular octagon of
/// circumradius r [m]: one surface, normal +z, in the model x-y plane, like makeRectanglePlate (no back
/// face; the campaign's octagon family).
PolygonModel makeOctagonPlate(double width_m, double height_m, double chamfer_m);
PolygonModel makeRegularOctagonPlate(double circumradius_m);
/// A closed box with half-sizes (hx, hy, hz) [m] centred on the origin.
PolygonModel makeBox(double hx_m, double hy_m, double hz_m, double albedo = 0.8);

}  // namespace visnav
