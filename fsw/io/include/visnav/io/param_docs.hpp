// Markdown reference rows for a parameter table: config/PARAMETERS.md is generated from these
// (visnav-params), and a test fails when the committed file is stale.
#pragma once

#include <sstream>
#include <string>

#include "visnav/core/param_visitor.hpp"

namespace visnav::io {

class MarkdownParamWriter final : public ParamVisitor {
 public:
  void real(const ParamInfo& info, double& value) override { row(info, "real", number(value), ""); }
  void integer(const ParamInfo& info, int& value) override {
    row(info, "integer", std::to_string(value), "");
  }
  void boolean(const ParamInfo& info, bool& value) override {
    row(info, "bool", value ? "true" : "false", "");
  }
  void enumeration(const ParamInfo& info, const char* names, int& value) override {
    std::string list(names);
    std::string chosen;
    std::istringstream in(list);
    for (int i = 0; std::getline(in, chosen, '|'); ++i)
      if (i == value) break;
    row(info, "enum", "\"" + chosen + "\"", list);
  }
  void text(const ParamInfo& info, std::string& value) override {
    row(info, "string", "\"" + value + "\"", number(info.min) + " .. " + number(info.max) + " chars");
  }
  std::string text() const { return m_out.str(); }

 private:
  static std::string number(double v) {
    std::ostringstream s;
    s << v;
    return s.str();
  }
  void row(const ParamInfo& info, const char* type, const std::string& def, const std::string& choices) {
    m_out << "| `[" << info.section << "] " << info.key << "` | " << type << " | " << def << " | "
          << (choices.empty() ? number(info.min) + " .. " + number(info.max) : choices) << " | " << info.unit
          << " | " << info.description << " |\n";
  }
  std::ostringstream m_out;
};

template <typename Params>
std::string parameterTableMarkdown(Params defaults) {
  MarkdownParamWriter writer;
  defaults.visit(writer);
  return "| key | type | default | range | unit | description |\n|---|---|---|---|---|---|\n" + writer.text();
}

}  // namespace visnav::io
