#include "visnav/geometry/polygon_model.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <map>
#include <utility>

namespace visnav {
namespace {

std::string surfaceLabel(const ModelSurface& s, std::size_t index) {
  return "surface " + std::to_string(index) + (s.name.empty() ? "" : " ('" + s.name + "')");
}

}  // namespace

LoadError PolygonModel::build(const std::vector<Vec3>& vertices, std::vector<ModelSurface> surfaces,
                              PolygonModel& out) {
  if (vertices.size() < 3) return LoadError::failure("model needs at least 3 vertices");
  if (surfaces.empty()) return LoadError::failure("model needs at least 1 surface");
  if (vertices.size() > kMaxVertices)
    return LoadError::failure("model has " + std::to_string(vertices.size()) +
                              " vertices, more than the limit " + std::to_string(kMaxVertices));
  if (surfaces.size() > kMaxSurfaces)
    return LoadError::failure("model has " + std::to_string(surfaces.size()) +
                              " surfaces, more than the limit " + std::to_string(kMaxSurfaces));
  double radius = 0.0;
  for (std::size_t i = 0; i < vertices.size(); ++i) {
    if (!vertices[i].allFinite()) return LoadError::failure("vertex " + std::to_string(i) + " is not finite");
    if (vertices[i].cwiseAbs().maxCoeff() > kMaxCoordinateM)
      return LoadError::failure("vertex " + std::to_string(i) + " has a coordinate beyond +-" +
                                std::to_string(static_cast<int>(kMaxCoordinateM)) + " m");
    radius = std::max(radius, vertices[i].norm());
  }
  const double tol = 1e-6 * std::max(1.0, radius);

  std::map<std::pair<int, int>, int> directed;  // (v0, v1) -> surface
  for (std::size_t s = 0; s < surfaces.size(); ++s) {
    ModelSurface& surf = surfaces[s];
    const auto& idx = surf.vertex_indices;
    const std::string label = surfaceLabel(surf, s);
    if (idx.size() < 3) return LoadError::failure(label + " has fewer than 3 vertices");
    if (idx.size() > kMaxSurfaceVertices)
      return LoadError::failure(label + " has " + std::to_string(idx.size()) +
                                " vertices, more than the limit " + std::to_string(kMaxSurfaceVertices));
    for (std::size_t k = 0; k < idx.size(); ++k) {
      if (idx[k] < 0 || static_cast<std::size_t>(idx[k]) >= vertices.size())
        return LoadError::failure(label + " refers to vertex " + std::to_string(idx[k]) +
                                  ", which does not exist");
    }
    std::vector<int> sorted = idx;  // n log n: a long face must not cost n^2
    std::sort(sorted.begin(), sorted.end());
    const auto repeat = std::adjacent_find(sorted.begin(), sorted.end());
    if (repeat != sorted.end())
      return LoadError::failure(label + " repeats vertex " + std::to_string(*repeat));
    // Newell's method: robust normal of a (nearly) planar polygon; its direction follows the vertex order.
    Vec3 newell = Vec3::Zero();
    Vec3 centroid = Vec3::Zero();
    for (std::size_t k = 0; k < idx.size(); ++k) {
      const Vec3& a = vertices[idx[k]];
      const Vec3& b = vertices[idx[(k + 1) % idx.size()]];
      newell += a.cross(b);
      centroid += a;
    }
    centroid /= static_cast<double>(idx.size());
    if (!newell.allFinite()) return LoadError::failure(label + " has a normal that is not finite");
    if (newell.norm() < tol * tol) return LoadError::failure(label + " has zero area");
    const Vec3 n = newell.normalized();
    if (!n.allFinite()) return LoadError::failure(label + " has a normal that is not finite");
    for (int v : idx)
      if (std::fabs(n.dot(vertices[v] - centroid)) > tol)
        return LoadError::failure(label + " is not planar (vertex " + std::to_string(v) +
                                  " is off its plane)");
    // Convex and simple: no turn against the normal, and the exterior angles add up to exactly one turn.
    // Turning the same way at every vertex alone lets a star through (its turns add up to 2 pi per loop).
    double turning_rad = 0.0;
    for (std::size_t k = 0; k < idx.size(); ++k) {
      const Vec3& a = vertices[idx[k]];
      const Vec3& b = vertices[idx[(k + 1) % idx.size()]];
      const Vec3& c = vertices[idx[(k + 2) % idx.size()]];
      const Vec3 turn = (b - a).cross(c - b);
      if (turn.dot(n) < -tol * tol)
        return LoadError::failure(label + " is not convex at vertex " +
                                  std::to_string(idx[(k + 1) % idx.size()]));
      turning_rad += std::atan2(turn.dot(n), (b - a).dot(c - b));
    }
    if (std::fabs(turning_rad - 2.0 * kPi) > 1e-6)
      return LoadError::failure(label + " is not a simple polygon (its edges turn " +
                                std::to_string(turning_rad / (2.0 * kPi)) +
                                " times around: self-intersecting, e.g. a star)");
    if (surf.normal_m.squaredNorm() == 0.0) {
      surf.normal_m = n;
    } else {
      const Vec3 given = surf.normal_m.normalized();
      if (given.dot(n) < std::cos(1.0 * kRadPerDeg))
        return LoadError::failure(label +
                                  ": stored normal disagrees with the vertex order (vertices must run "
                                  "counter-clockwise seen from outside)");
      surf.normal_m = given;
    }
    surf.centroid_m = centroid;
    if (!(surf.albedo >= 0.0 && surf.albedo <= 1.0))
      return LoadError::failure(label + " albedo must be in [0, 1]");
    for (std::size_t k = 0; k < idx.size(); ++k) {
      const std::pair<int, int> key(idx[k], idx[(k + 1) % idx.size()]);
      if (directed.count(key) != 0U)
        return LoadError::failure(label + " traverses edge " + std::to_string(key.first) + "-" +
                                  std::to_string(key.second) + " in the same direction as surface " +
                                  std::to_string(directed[key]) + " (inconsistent orientation)");
      directed[key] = static_cast<int>(s);
    }
  }

  PolygonModel model;
  model.m_vertices = vertices;
  model.m_surface_edges.resize(surfaces.size());
  std::map<std::pair<int, int>, int> undirected;  // (min, max) -> edge index
  for (std::size_t s = 0; s < surfaces.size(); ++s) {
    const auto& idx = surfaces[s].vertex_indices;
    model.m_max_surface_vertices = std::max(model.m_max_surface_vertices, static_cast<int>(idx.size()));
    for (std::size_t k = 0; k < idx.size(); ++k) {
      const int a = idx[k];
      const int b = idx[(k + 1) % idx.size()];
      const std::pair<int, int> key(std::min(a, b), std::max(a, b));
      auto it = undirected.find(key);
      if (it == undirected.end()) {
        ModelEdge e;
        e.v0 = a;
        e.v1 = b;
        e.surface_left = static_cast<int>(s);
        undirected[key] = static_cast<int>(model.m_edges.size());
        model.m_surface_edges[s].push_back(static_cast<int>(model.m_edges.size()));
        model.m_edges.push_back(e);
      } else {
        ModelEdge& e = model.m_edges[it->second];
        if (e.surface_right != -1)
          return LoadError::failure("edge " + std::to_string(a) + "-" + std::to_string(b) +
                                    " is shared by more than two surfaces");
        e.surface_right = static_cast<int>(s);
        model.m_surface_edges[s].push_back(it->second);
      }
    }
  }
  model.m_surfaces = std::move(surfaces);
  model.m_bounding_radius = radius;
  out = std::move(model);
  return LoadError::success();
}

namespace {

/// One flat surface through `ring` (counter-clockwise seen from +z, its normal), no back face.
PolygonModel flatPlate(const std::vector<Vec3>& ring, double albedo) {
  ModelSurface s;
  s.name = "plate";
  for (int i = 0; i < static_cast<int>(ring.size()); ++i) s.vertex_indices.push_back(i);
  s.albedo = albedo;
  PolygonModel m;
  PolygonModel::build(ring, {s}, m);
  return m;
}

}  // namespace

PolygonModel makeRectanglePlate(double width_m, double height_m, double albedo) {
  const double hx = 0.5 * width_m;
  const double hy = 0.5 * height_m;
  return flatPlate({{-hx, -hy, 0.0}, {hx, -hy, 0.0}, {hx, hy, 0.0}, {-hx, hy, 0.0}}, albedo);
}

PolygonModel makeOctagonPlate(double width_m, double height_m, double chamfer_m) {
  const double hx = 0.5 * width_m;
  const double hy = 0.5 * height_m;
  const double c = chamfer_m;
  return flatPlate({{hx - c, -hy, 0.0},
                    {hx, -hy + c, 0.0},
                    {hx, hy - c, 0.0},
                    {hx - c, hy, 0.0},
                    {-hx + c, hy, 0.0},
                    {-hx, hy - c, 0.0},
                    {-hx, -hy + c, 0.0},
                    {-hx + c, -hy, 0.0}},
                   ModelSurface{}.albedo);
}

PolygonModel makeRegularOctagonPlate(double circumradius_m) {
  std::vector<Vec3> ring;
  for (int k = 0; k < 8; ++k) {
    const double a = (22.5 + 45.0 * k) * kRadPerDeg;
    ring.emplace_back(circumradius_m * std::cos(a), circumradius_m * std::sin(a), 0.0);
  }
  return flatPlate(ring, ModelSurface{}.albedo);
}

PolygonModel makeBox(double hx, double hy, double hz, double albedo) {
  std::vector<Vec3> v = {{-hx, -hy, -hz}, {hx, -hy, -hz}, {hx, hy, -hz}, {-hx, hy, -hz},
                         {-hx, -hy, hz},  {hx, -hy, hz},  {hx, hy, hz},  {-hx, hy, hz}};
  const std::vector<std::pair<const char*, std::vector<int>>> faces = {
      {"+z", {4, 5, 6, 7}}, {"-z", {0, 3, 2, 1}}, {"+x", {1, 2, 6, 5}},
      {"-x", {0, 4, 7, 3}}, {"+y", {2, 3, 7, 6}}, {"-y", {0, 1, 5, 4}}};
  std::vector<ModelSurface> surfaces;
  for (const auto& f : faces) {
    ModelSurface s;
    s.name = f.first;
    s.vertex_indices = f.second;
    s.albedo = albedo;
    surfaces.push_back(s);
  }
  PolygonModel m;
  PolygonModel::build(v, surfaces, m);
  return m;
}

}  // namespace visnav
