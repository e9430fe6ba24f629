// visnav's own TOML polygon model format (documented field by field in fsw/io/README.md).
#include <cstdio>
#include <string>
#include <utility>
#include <vector>

#include "io_util.hpp"
#include "visnav/io/model_io.hpp"

namespace visnav::io {
namespace {

using detail::TomlChecker;

std::string quoteTomlString(const std::string& text) {
  std::string out = "\"";
  for (const char c : text) {
    if (c == '"' || c == '\\') {
      out += '\\';
      out += c;
    } else if (static_cast<unsigned char>(c) < 0x20 || c == 0x7f) {
      char buf[8];
      std::snprintf(buf, sizeof(buf), "\\u%04x", static_cast<unsigned>(static_cast<unsigned char>(c)));
      out += buf;
    } else {
      out += c;
    }
  }
  return out + "\"";
}

std::string formatVec3(const Vec3& v) {
  return "[" + detail::formatDouble(v.x()) + ", " + detail::formatDouble(v.y()) + ", " +
         detail::formatDouble(v.z()) + "]";
}

std::string fileStem(const std::string& path) {
  const std::size_t slash = path.find_last_of('/');
  std::string name = slash == std::string::npos ? path : path.substr(slash + 1);
  const std::size_t dot = name.find_last_of('.');
  return dot == std::string::npos || dot == 0 ? name : name.substr(0, dot);
}

bool readVertices(TomlChecker& check, const toml::table& model, std::vector<Vec3>& vertices) {
  const toml::array* arr = nullptr;
  if (!check.array(model, "[model]", "vertices", true, arr)) return false;
  if (arr->empty()) return check.fail(*arr, "[model] vertices is empty");
  if (arr->size() > PolygonModel::kMaxVertices)
    return check.fail(*arr, "[model] vertices has " + std::to_string(arr->size()) +
                                " entries, more than the limit " +
                                std::to_string(PolygonModel::kMaxVertices));
  for (std::size_t i = 0; i < arr->size(); ++i) {
    Vec3 v;
    if (!check.vec3((*arr)[i], "vertex " + std::to_string(i), v)) return false;
    vertices.push_back(v);
  }
  return true;
}

bool readSurface(TomlChecker& check, const toml::table& table, std::size_t index, std::size_t num_vertices,
                 ModelSurface& surface) {
  const std::string label = "[[surface]] " + std::to_string(index);
  if (!check.onlyKeys(table, label, {"name", "vertices", "normal", "albedo"})) return false;
  if (!check.string(table, label, "name", false, surface.name)) return false;
  const toml::array* idx = nullptr;
  if (!check.array(table, label, "vertices", true, idx)) return false;
  if (idx->size() > PolygonModel::kMaxSurfaceVertices)
    return check.fail(*idx, label + " vertices has " + std::to_string(idx->size()) +
                                " entries, more than the limit " +
                                std::to_string(PolygonModel::kMaxSurfaceVertices));
  for (std::size_t k = 0; k < idx->size(); ++k) {
    std::int64_t v = 0;
    if (!check.integer((*idx)[k], label + " vertices[" + std::to_string(k) + "]", v)) return false;
    if (v < 0 || static_cast<std::uint64_t>(v) >= num_vertices)
      return check.fail((*idx)[k], label + ": vertex index " + std::to_string(v) + " out of range [0, " +
                                       std::to_string(num_vertices) + ")");
    surface.vertex_indices.push_back(static_cast<int>(v));
  }
  if (const toml::node* normal = table.get("normal")) {
    if (!check.vec3(*normal, label + " normal", surface.normal_m)) return false;
    if (surface.normal_m.squaredNorm() == 0.0) return check.fail(*normal, label + " normal is zero");
  }
  bool has_albedo = false;
  double albedo = 0.0;
  if (!check.number(table, label, "albedo", false, albedo, &has_albedo)) return false;
  if (has_albedo) {
    if (albedo < 0.0 || albedo > 1.0)
      return check.fail(*table.get("albedo"),
                        label + " albedo " + detail::formatDouble(albedo) + " out of range [0, 1]");
    surface.albedo = albedo;
  }
  return true;
}

}  // namespace

LoadError loadModelToml(const std::string& path, PolygonModel& out) {
  toml::table root;
  if (LoadError e = detail::parseTomlFile(path, root); !e.ok) return e;
  TomlChecker check(path);

  std::vector<Vec3> vertices;
  std::vector<ModelSurface> surfaces;
  std::vector<int> surface_lines;
  const toml::table* model = nullptr;
  bool ok = check.onlyKeys(root, "top level", {"model", "surface"}) &&
            check.table(root, "top level", "model", true, model) &&
            check.onlyKeys(*model, "[model]", {"name", "units", "vertices"});
  std::string name;
  std::string units;
  ok = ok && check.string(*model, "[model]", "name", false, name) &&
       check.string(*model, "[model]", "units", true, units);
  if (ok && units != "m")
    ok = check.fail(*model->get("units"), "[model] units '" + units + "' not supported (only \"m\")");
  ok = ok && readVertices(check, *model, vertices);
  if (ok) {
    const toml::node* list = root.get("surface");
    if (list == nullptr) {
      ok = check.failNoLine("missing [[surface]] (a model needs at least one surface)");
    } else if (!list->is_array_of_tables()) {
      ok = check.fail(*list, "'surface' has the wrong type: expected an array of tables [[surface]]");
    } else {
      const toml::array& arr = *list->as_array();
      if (arr.size() > PolygonModel::kMaxSurfaces)
        ok = check.fail(*list, "[[surface]] has " + std::to_string(arr.size()) +
                                   " entries, more than the limit " +
                                   std::to_string(PolygonModel::kMaxSurfaces));
      for (std::size_t s = 0; ok && s < arr.size(); ++s) {
        ModelSurface surface;
        ok = readSurface(check, *arr[s].as_table(), s, vertices.size(), surface);
        surfaces.push_back(std::move(surface));
        surface_lines.push_back(static_cast<int>(arr[s].source().begin.line));
      }
    }
  }
  if (!ok) return check.error();

  PolygonModel built;
  if (LoadError e = PolygonModel::build(vertices, std::move(surfaces), built); !e.ok)
    return detail::buildError(path, e.message, surface_lines);
  out = std::move(built);
  return LoadError::success();
}

LoadError loadModel(const std::string& path, PolygonModel& out) {
  const std::string ext = detail::extensionOf(path);
  if (ext == ".toml") return loadModelToml(path, out);
  if (ext == ".cao") return loadModelCao(path, out);
  return LoadError::failure(path + ": unknown model file extension '" + ext + "' (expected .toml or .cao)");
}

LoadError writeModelToml(const std::string& path, const PolygonModel& model) {
  if (model.vertices().empty() || model.surfaces().empty())
    return LoadError::failure(path + ": refusing to write an empty model");
  std::string text = "# visnav polygon model, format: fsw/io/README.md. Written by writeModelToml.\n";
  text += "[model]\nname = " + quoteTomlString(fileStem(path)) + "\nunits = \"m\"\nvertices = [\n";
  for (const Vec3& v : model.vertices()) text += "  " + formatVec3(v) + ",\n";
  text += "]\n";
  for (const ModelSurface& s : model.surfaces()) {
    text += "\n[[surface]]\n";
    if (!s.name.empty()) text += "name = " + quoteTomlString(s.name) + "\n";
    text += "vertices = [";
    for (std::size_t k = 0; k < s.vertex_indices.size(); ++k)
      text += (k == 0 ? "" : ", ") + std::to_string(s.vertex_indices[k]);
    text += "]\nnormal = " + formatVec3(s.normal_m) + "\nalbedo = " + detail::formatDouble(s.albedo) + "\n";
  }
  return detail::writeTextFile(path, text);
}

}  // namespace visnav::io
