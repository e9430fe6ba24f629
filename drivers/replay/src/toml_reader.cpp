#include "visnav/replay/toml_reader.hpp"

#include <toml++/toml.h>

#include <cmath>
#include <sstream>

#include "visnav/io/text_file.hpp"

namespace visnav::replay {

struct TomlReader::Impl {
  toml::table table;

  const toml::node* find(const std::string& key) const {
    const toml::node* node = &table;
    std::size_t start = 0;
    while (node != nullptr) {
      const std::size_t dot = key.find('.', start);
      const std::string part = key.substr(start, dot == std::string::npos ? std::string::npos : dot - start);
      const toml::table* t = node->as_table();
      if (t == nullptr) return nullptr;
      node = t->get(part);
      if (dot == std::string::npos) break;
      start = dot + 1;
    }
    return node;
  }

  // Shared by every getter: nothing after the first error, the key counts as known, a missing required key
  // is the error. nullptr: nothing to read.
  static const toml::node* lookup(TomlReader& reader, const std::string& key, bool required);

  // Collects every leaf key (dotted) with its line.
  static void leaves(const toml::table& t, const std::string& prefix,
                     std::vector<std::pair<std::string, int>>& out) {
    for (const auto& [k, v] : t) {
      const std::string name = prefix.empty() ? std::string(k.str()) : prefix + "." + std::string(k.str());
      if (const toml::table* sub = v.as_table()) {
        leaves(*sub, name, out);
      } else {
        out.emplace_back(name, static_cast<int>(v.source().begin.line));
      }
    }
  }
};

TomlReader::TomlReader() : m_impl(std::make_unique<Impl>()) {}
TomlReader::~TomlReader() = default;

LoadError TomlReader::open(const std::string& path) {
  m_path = path;
  m_used.clear();
  m_error = LoadError::success();
  std::string text;
  if (LoadError e = io::readTextFile(path, text, io::kMaxTomlFileBytes); !e.ok) return m_error = e;
  if (LoadError e = io::checkTomlAscii(path, text); !e.ok) return m_error = e;
  try {
    m_impl->table = toml::parse(text, path);
  } catch (const toml::parse_error& e) {
    std::ostringstream s;
    s << path << ":" << e.source().begin.line << ": " << e.description();
    m_error = LoadError::failure(s.str());
  }
  return m_error;
}

bool TomlReader::has(const std::string& key) const { return m_impl->find(key) != nullptr; }

const toml::node* TomlReader::Impl::lookup(TomlReader& reader, const std::string& key, bool required) {
  if (!reader.m_error.ok) return nullptr;
  reader.m_used.insert(key);
  const toml::node* node = reader.m_impl->find(key);
  if (node == nullptr && required) reader.fail(key, "missing required key");
  return node;
}

void TomlReader::fail(const std::string& key, const std::string& problem) {
  if (!m_error.ok) return;
  const toml::node* node = m_impl->find(key);
  std::ostringstream s;
  s << m_path;
  if (node != nullptr) s << ":" << node->source().begin.line;
  s << ": " << key << ": " << problem;
  m_error = LoadError::failure(s.str());
}

void TomlReader::checkRange(const std::string& key, double value, double lo, double hi) {
  if (!(value >= lo && value <= hi)) {
    std::ostringstream s;
    s << "value " << value << " must be in [" << lo << ", " << hi << "]";
    fail(key, s.str());
  }
}

namespace {
bool numberOf(const toml::node& node, double& out) {
  if (const auto* f = node.as_floating_point()) {
    out = f->get();
  } else if (const auto* i = node.as_integer()) {
    out = static_cast<double>(i->get());
  } else {
    return false;
  }
  return std::isfinite(out);
}
}  // namespace

void TomlReader::getDouble(const std::string& key, double& out, bool required) {
  const toml::node* node = Impl::lookup(*this, key, required);
  if (node == nullptr) return;
  double value = 0.0;
  if (!numberOf(*node, value)) return fail(key, "expected a finite number");
  out = value;
}

void TomlReader::getInt(const std::string& key, std::int64_t& out, bool required) {
  const toml::node* node = Impl::lookup(*this, key, required);
  if (node == nullptr) return;
  const auto* i = node->as_integer();
  if (i == nullptr) return fail(key, "expected an integer");
  out = i->get();
}

void TomlReader::getInt(const std::string& key, int& out, bool required) {
  std::int64_t value = out;
  getInt(key, value, required);
  if (!m_error.ok) return;
  if (value < -2147483647LL || value > 2147483647LL) return fail(key, "integer out of range");
  out = static_cast<int>(value);
}

void TomlReader::getBool(const std::string& key, bool& out, bool required) {
  const toml::node* node = Impl::lookup(*this, key, required);
  if (node == nullptr) return;
  const auto* b = node->as_boolean();
  if (b == nullptr) return fail(key, "expected true or false");
  out = b->get();
}

void TomlReader::getString(const std::string& key, std::string& out, bool required) {
  const toml::node* node = Impl::lookup(*this, key, required);
  if (node == nullptr) return;
  const auto* s = node->as_string();
  if (s == nullptr) return fail(key, "expected a string");
  out = s->get();
}

void TomlReader::getVector(const std::string& key, double* out, int n, bool required) {
  const toml::node* node = Impl::lookup(*this, key, required);
  if (node == nullptr) return;
  const auto* a = node->as_array();
  if (a == nullptr || a->size() != static_cast<std::size_t>(n)) {
    return fail(key, "expected an array of " + std::to_string(n) + " numbers");
  }
  double values[16] = {};
  if (n > 16) return fail(key, "internal: vector too long");
  for (int i = 0; i < n; ++i) {
    if (!numberOf(*a->get(static_cast<std::size_t>(i)), values[i])) {
      return fail(key, "element " + std::to_string(i) + " is not a finite number");
    }
  }
  for (int i = 0; i < n; ++i) out[i] = values[i];
}

void TomlReader::getArray(const std::string& key, std::vector<double>& out, std::size_t max_size,
                          bool required) {
  const toml::node* node = Impl::lookup(*this, key, required);
  if (node == nullptr) return;
  const auto* a = node->as_array();
  if (a == nullptr || a->size() > max_size) {
    return fail(key, "expected an array of at most " + std::to_string(max_size) + " numbers");
  }
  std::vector<double> values(a->size());
  for (std::size_t i = 0; i < a->size(); ++i) {
    if (!numberOf(*a->get(i), values[i]))
      return fail(key, "element " + std::to_string(i) + " is not a finite number");
  }
  out = std::move(values);
}

LoadError TomlReader::finish() {
  if (!m_error.ok) return m_error;
  std::vector<std::pair<std::string, int>> keys;
  Impl::leaves(m_impl->table, "", keys);
  for (const auto& [name, line] : keys) {
    if (m_used.count(name) == 0U) {
      return LoadError::failure(m_path + ":" + std::to_string(line) + ": unknown key '" + name + "'");
    }
  }
  return LoadError::success();
}

}  // namespace visnav::replay
