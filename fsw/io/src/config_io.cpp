#include "visnav/io/config_io.hpp"

#include <toml++/toml.h>

#include <cmath>
#include <cstring>
#include <set>
#include <sstream>
#include <utility>

namespace visnav::io {

struct ConfigFile::Impl {
  toml::table root;
  std::set<std::string> claimed;  // "section.key"
};

ConfigFile::ConfigFile() : m_impl(std::make_unique<Impl>()) {}
ConfigFile::~ConfigFile() = default;

LoadError ConfigFile::open(const std::string& path) {
  m_path = path;
  try {
    m_impl->root = toml::parse_file(path);
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

LoadError ConfigFile::checkNoUnknownKeys() const {
  for (const auto& [section_key, section_node] : m_impl->root) {
    const std::string section(section_key.str());
    const toml::table* table = section_node.as_table();
    if (table == nullptr) continue;
    for (const auto& [key, node] : *table) {
      if (node.is_table()) continue;
      if (m_impl->claimed.count(section + "." + std::string(key.str())) == 0U)
        return LoadError::failure(where(m_path, node) + ": unknown key [" + section + "] " +
                                  std::string(key.str()));
    }
  }
  return LoadError::success();
}

std::string ConfigFile::stringValue(const char* section, const char* key) const {
  m_impl->claimed.insert(std::string(section) + "." + key);
  const auto v = m_impl->root[section][key].value<std::string>();
  return v ? *v : std::string();
}

}  // namespace visnav::io
