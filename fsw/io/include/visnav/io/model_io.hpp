// Init-time loaders and writers for target models. Formats: docs in fsw/io/README.md.
// Every error message names the file, the line (when the format has lines) and the problem; on error the
// output object is untouched, so nothing half-loaded is ever used.
#pragma once

#include <string>

#include "visnav/core/status.hpp"
#include "visnav/geometry/polygon_model.hpp"

namespace visnav::io {

/// visnav's own TOML model format (`.toml`).
LoadError loadModelToml(const std::string& path, PolygonModel& out);
/// ViSP `.cao` polygon models (V1: 3D points, 3D lines, faces from lines or points); cylinders/circles
/// are rejected with a clear message (not polygons).
LoadError loadModelCao(const std::string& path, PolygonModel& out);
/// Dispatch on the extension (.toml or .cao).
LoadError loadModel(const std::string& path, PolygonModel& out);
/// Writes the TOML format; a round trip load(write(m)) reproduces m.
LoadError writeModelToml(const std::string& path, const PolygonModel& model);

}  // namespace visnav::io
