#include "io_util.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <utility>

namespace visnav::io::detail {

std::string extensionOf(const std::string& path) {
  const std::size_t slash = path.find_last_of('/');
  const std::size_t dot = path.find_last_of('.');
  if (dot == std::string::npos || (slash != std::string::npos && dot < slash)) return {};
  std::string ext = path.substr(dot);
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return ext;
}

std::string formatDouble(double value) {
  char buf[64];
  for (int digits = 15; digits <= 17; ++digits) {
    std::snprintf(buf, sizeof(buf), "%.*g", digits, value);
    if (std::strtod(buf, nullptr) == value) break;
  }
  std::string text(buf);
  // "%g" prints 1000 as "1000": add ".0" so TOML and YAML see a float, not an integer.
  if (text.find_first_of(".eEn") == std::string::npos) text += ".0";
  return text;
}

LoadError writeTextFile(const std::string& path, const std::string& text) {
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  if (!out) return LoadError::failure(path + ": cannot open file for writing");
  out << text;
  out.flush();
  if (!out) return LoadError::failure(path + ": write failed");
  return LoadError::success();
}

LoadError buildError(const std::string& path, const std::string& message,
                     const std::vector<int>& surface_lines) {
  const std::string prefix = "surface ";
  if (message.compare(0, prefix.size(), prefix) == 0) {
    const std::size_t end = message.find_first_not_of("0123456789", prefix.size());
    if (end != prefix.size() && end != std::string::npos && end - prefix.size() < 9) {
      const std::size_t index = std::stoul(message.substr(prefix.size(), end - prefix.size()));
      if (index < surface_lines.size() && surface_lines[index] > 0)
        return LoadError::failure(path + ":" + std::to_string(surface_lines[index]) + ": " + message);
    }
  }
  return LoadError::failure(path + ": " + message);
}

LoadError parseTomlFile(const std::string& path, toml::table& root) {
  std::string text;
  if (LoadError e = readTextFile(path, text, kMaxTomlFileBytes); !e.ok) return e;
  if (LoadError e = checkTomlAscii(path, text); !e.ok) return e;
  try {
    root = toml::parse(text, path);
  } catch (const toml::parse_error& e) {
    return LoadError::failure(path + ":" + std::to_string(e.source().begin.line) + ":" +
                              std::to_string(e.source().begin.column) + ": " + std::string(e.description()));
  }
  return LoadError::success();
}

bool TomlChecker::fail(const toml::source_region& where, const std::string& problem) {
  if (m_error.ok) {
    m_error = LoadError::failure(where.begin.line > 0
                                     ? m_path + ":" + std::to_string(where.begin.line) + ": " + problem
                                     : m_path + ": " + problem);
  }
  return false;
}

bool TomlChecker::fail(const toml::node& where, const std::string& problem) {
  return fail(where.source(), problem);
}

bool TomlChecker::failNoLine(const std::string& problem) {
  if (m_error.ok) m_error = LoadError::failure(m_path + ": " + problem);
  return false;
}

bool TomlChecker::onlyKeys(const toml::table& table, const std::string& table_name,
                           std::initializer_list<const char*> allowed) {
  for (auto&& [key, value] : table) {
    const bool known =
        std::any_of(allowed.begin(), allowed.end(), [&key = key](const char* a) { return key.str() == a; });
    if (!known) return fail(value, table_name + ": unknown key '" + std::string(key.str()) + "'");
  }
  return true;
}

const toml::node* TomlChecker::find(const toml::table& table, const std::string& table_name, const char* key,
                                    bool required, bool* present) {
  const toml::node* node = table.get(key);
  if (present != nullptr) *present = node != nullptr;
  if (node == nullptr && required) fail(table, table_name + ": missing key '" + key + "'");
  return node;
}

bool TomlChecker::table(const toml::table& parent, const std::string& parent_name, const char* key,
                        bool required, const toml::table*& out) {
  out = nullptr;
  bool present = false;
  const toml::node* node = find(parent, parent_name, key, required, &present);
  if (!present) return !required;
  out = node->as_table();
  if (out == nullptr) return fail(*node, "'" + std::string(key) + "' has the wrong type: expected a table");
  return true;
}

bool TomlChecker::number(const toml::node& node, const std::string& what, double& out) {
  if (node.is_integer()) {
    out = static_cast<double>(node.as_integer()->get());
  } else if (node.is_floating_point()) {
    out = node.as_floating_point()->get();
  } else {
    return fail(node, what + " has the wrong type: expected a number");
  }
  if (!std::isfinite(out)) return fail(node, what + " is not finite");
  return true;
}

bool TomlChecker::number(const toml::table& table, const std::string& table_name, const char* key,
                         bool required, double& out, bool* present) {
  bool here = false;
  const toml::node* node = find(table, table_name, key, required, &here);
  if (present != nullptr) *present = here;
  if (!here) return !required;
  return number(*node, "'" + std::string(key) + "'", out);
}

bool TomlChecker::integer(const toml::node& node, const std::string& what, std::int64_t& out) {
  if (!node.is_integer()) return fail(node, what + " has the wrong type: expected an integer");
  out = node.as_integer()->get();
  return true;
}

bool TomlChecker::integer(const toml::table& table, const std::string& table_name, const char* key,
                          bool required, std::int64_t& out, bool* present) {
  bool here = false;
  const toml::node* node = find(table, table_name, key, required, &here);
  if (present != nullptr) *present = here;
  if (!here) return !required;
  return integer(*node, "'" + std::string(key) + "'", out);
}

bool TomlChecker::string(const toml::table& table, const std::string& table_name, const char* key,
                         bool required, std::string& out, bool* present) {
  bool here = false;
  const toml::node* node = find(table, table_name, key, required, &here);
  if (present != nullptr) *present = here;
  if (!here) return !required;
  if (!node->is_string())
    return fail(*node, "'" + std::string(key) + "' has the wrong type: expected a string");
  out = node->as_string()->get();
  return true;
}

bool TomlChecker::array(const toml::table& table, const std::string& table_name, const char* key,
                        bool required, const toml::array*& out) {
  out = nullptr;
  bool here = false;
  const toml::node* node = find(table, table_name, key, required, &here);
  if (!here) return !required;
  out = node->as_array();
  if (out == nullptr) return fail(*node, "'" + std::string(key) + "' has the wrong type: expected an array");
  return true;
}

bool TomlChecker::vec3(const toml::node& node, const std::string& what, Vec3& out) {
  const toml::array* arr = node.as_array();
  if (arr == nullptr || arr->size() != 3)
    return fail(node, what + " has the wrong type: expected an array of 3 numbers [x, y, z]");
  Vec3 v;
  for (std::size_t i = 0; i < 3; ++i)
    if (!number((*arr)[i], what + "[" + std::to_string(i) + "]", v[static_cast<Eigen::Index>(i)]))
      return false;
  out = v;
  return true;
}

}  // namespace visnav::io::detail
