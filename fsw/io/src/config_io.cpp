#include "visnav/io/config_io.hpp"

#include <toml++/toml.h>

#include <cmath>
#include <cstring>
#include <set>
#include <sstream>
#include <utility>

#include "visnav/io/text_file.hpp"

namespace visnav::io {

struct ConfigFile::Impl {
  toml::table root;
  std::set<std::string> claimed;  // "section.key"
};

ConfigFile::ConfigFile() : m_impl(std::make_unique<Impl>()) {}
ConfigFile::~ConfigFile() = default;

LoadError ConfigFile::open(const std::string& path) {
  m_path = path;
  std::string text;
  if (LoadError e = readTextFile(path, text, kMaxTomlFileBytes); !e.ok) return e;
  if (LoadError e = checkTomlAscii(path, text); !e.ok) return e;
  try {
    m_impl->root = toml::parse(text, path);
  } catch (const toml::parse_error& e) {
    std::ostringstream msg;
    msg << path << ":" << e.source().begin.line << ":" << e.source().begin.column << ": " << e.description();
    return LoadError::failure(msg.str());
  }
  return LoadError::success();
}

namespace {

std::string where(const std::string& path, const toml::node& node) {
  return path + ":" + std::to_string(node.source().begin.line);
}

// file:line:col of a key (where a typo is), falling back to its value.
std::string whereKey(const std::string& path, const toml::key& key, const toml::node& node) {
  const toml::source_position at = key.source().begin.line > 0 ? key.source().begin : node.source().begin;
  return path + ":" + std::to_string(at.line) + ":" + std::to_string(at.column);
}

class TomlReader final : public ParamVisitor {
 public:
  TomlReader(const toml::table& root, const std::string& path, std::set<std::string>& claimed)
      : m_root(root), m_path(path), m_claimed(claimed) {}

  void real(const ParamInfo& info, double& value) override {
    const toml::node* node = find(info);
    if (node == nullptr) return;
    std::optional<double> v = node->value<double>();  // accepts integers too
    if (!v || !node->is_number()) return fail(*node, info, "must be a number");
    if (!std::isfinite(*v)) return fail(*node, info, "must be finite");
    if (*v < info.min || *v > info.max) return failRange(*node, info, *v);
    value = *v;
  }
  void integer(const ParamInfo& info, int& value) override {
    const toml::node* node = find(info);
    if (node == nullptr) return;
    if (!node->is_integer()) return fail(*node, info, "must be an integer");
    const auto v = static_cast<double>(*node->value<std::int64_t>());
    if (v < info.min || v > info.max) return failRange(*node, info, v);
    value = static_cast<int>(v);
  }
  void boolean(const ParamInfo& info, bool& value) override {
    const toml::node* node = find(info);
    if (node == nullptr) return;
    if (!node->is_boolean()) return fail(*node, info, "must be true or false");
    value = *node->value<bool>();
  }
  void enumeration(const ParamInfo& info, const char* names, int& value) override {
    const toml::node* node = find(info);
    if (node == nullptr) return;
    if (!node->is_string()) return fail(*node, info, std::string("must be one of: ") + names);
    const std::string given = *node->value<std::string>();
    std::istringstream list(names);
    std::string name;
    for (int index = 0; std::getline(list, name, '|'); ++index) {
      if (name == given) {
        value = index;
        return;
      }
    }
    fail(*node, info, "'" + given + "' is not one of: " + names);
  }
  void text(const ParamInfo& info, std::string& value) override {
    const toml::node* node = find(info);
    if (node == nullptr) return;
    if (!node->is_string()) return fail(*node, info, "must be a string");
    std::string given = *node->value<std::string>();
    const auto length = static_cast<double>(given.size());
    if (length < info.min || length > info.max) {
      std::ostringstream msg;
      msg << "has " << given.size() << " characters, outside [" << info.min << ", " << info.max << "]";
      return fail(*node, info, msg.str());
    }
    value = std::move(given);
  }

  LoadError error() const { return m_error; }

 private:
  const toml::node* find(const ParamInfo& info) {
    m_claimed.insert(std::string(info.section) + "." + info.key);
    if (!m_error.ok) return nullptr;
    const toml::table* section = m_root[info.section].as_table();
    return section == nullptr ? nullptr : section->get(info.key);
  }
  void fail(const toml::node& node, const ParamInfo& info, const std::string& problem) {
    if (!m_error.ok) return;
    m_error =
        LoadError::failure(where(m_path, node) + ": [" + info.section + "] " + info.key + " " + problem);
  }
  void failRange(const toml::node& node, const ParamInfo& info, double v) {
    std::ostringstream msg;
    msg << "= " << v << " is outside [" << info.min << ", " << info.max << "] " << info.unit;
    fail(node, info, msg.str());
  }

  const toml::table& m_root;
  const std::string& m_path;
  std::set<std::string>& m_claimed;
  LoadError m_error;
};

}  // namespace

LoadError ConfigFile::applyErased(void (*call)(void*, ParamVisitor&), void* fn) {
  TomlReader reader(m_impl->root, m_path, m_impl->claimed);
  call(fn, reader);
  return reader.error();
}

// Every parameter lives in a [section] one level deep. Anything else is a typo the reader would never look
// at (a key above the first table, [[section]], [section.sub]), so it is an error, never skipped.
LoadError ConfigFile::checkNoUnknownKeys() const {
  for (const auto& [section_key, section_node] : m_impl->root) {
    const std::string section(section_key.str());
    const toml::table* table = section_node.as_table();
    if (section_node.is_array_of_tables())
      return LoadError::failure(whereKey(m_path, section_key, section_node) + ": [[" + section +
                                "]] is an array of tables; the config has only plain [sections]");
    if (table == nullptr)
      return LoadError::failure(whereKey(m_path, section_key, section_node) + ": key '" + section +
                                "' outside any [section] (keys before the first table belong to none)");
    for (const auto& [key, node] : *table) {
      const std::string name(key.str());
      if (node.is_table() || node.is_array_of_tables())
        return LoadError::failure(whereKey(m_path, key, node) + ": unknown table [" + section + "." + name +
                                  "] (sections do not nest)");
      if (m_impl->claimed.count(section + "." + name) == 0U)
        return LoadError::failure(where(m_path, node) + ": unknown key [" + section + "] " + name);
    }
  }
  return LoadError::success();
}

std::string ConfigFile::stringValue(const char* section, const char* key) const {
  m_impl->claimed.insert(std::string(section) + "." + key);
  const auto v = m_impl->root[section][key].value<std::string>();
  return v ? *v : std::string();
}

LoadError ConfigFile::stringValue(const char* section, const char* key, std::string& out,
                                  bool& present) const {
  m_impl->claimed.insert(std::string(section) + "." + key);
  present = false;
  const toml::node* node = m_impl->root[section][key].node();
  if (node == nullptr) return LoadError::success();
  if (!node->is_string())
    return LoadError::failure(where(m_path, *node) + ": [" + section + "] " + key + " must be a string");
  present = true;
  out = *node->value<std::string>();
  return LoadError::success();
}

}  // namespace visnav::io
