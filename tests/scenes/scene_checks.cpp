#include "tests/scenes/scene_checks.hpp"

#include <algorithm>
#include <cctype>
#include <cstdlib>
#include <filesystem>
#include <regex>
#include <sstream>
#include <stdexcept>

namespace loom::testing {
namespace {

class JsonParser {
 public:
  explicit JsonParser(const std::string& text) : s_(text) {}

  Json document() {
    Json v = value();
    space();
    if (i_ != s_.size()) fail("text after the JSON value");
    return v;
  }

 private:
  [[noreturn]] void fail(const std::string& what) const {
    throw std::runtime_error("JSON: " + what + " at offset " + std::to_string(i_));
  }
  void space() {
    while (i_ < s_.size() && (s_[i_] == ' ' || s_[i_] == '\n' || s_[i_] == '\r' || s_[i_] == '\t')) ++i_;
  }
  bool eat(char c) {
    space();
    if (i_ < s_.size() && s_[i_] == c) return ++i_, true;
    return false;
  }
  void expect(char c) {
    if (!eat(c)) fail(std::string("expected '") + c + "'");
  }
  bool word(const char* w) {
    const std::string ws(w);
    if (s_.compare(i_, ws.size(), ws) != 0) return false;
    i_ += ws.size();
    return true;
  }

  Json value() {
    space();
    if (i_ >= s_.size()) fail("unexpected end");
    Json v;
    const char c = s_[i_];
    if (c == '{') {
      ++i_;
      v.kind = Json::Kind::object;
      if (eat('}')) return v;
      do {
        space();
        const std::string key = string_literal();
        if (v.object.count(key)) fail("duplicate key " + key);
        expect(':');
        v.object[key] = value();
      } while (eat(','));
      expect('}');
    } else if (c == '[') {
      ++i_;
      v.kind = Json::Kind::array;
      if (eat(']')) return v;
      do v.array.push_back(value());
      while (eat(','));
      expect(']');
    } else if (c == '"') {
      v.kind = Json::Kind::string;
      v.string = string_literal();
    } else if (word("true")) {
      v.kind = Json::Kind::boolean, v.boolean = true;
    } else if (word("false")) {
      v.kind = Json::Kind::boolean;
    } else if (word("null")) {
    } else {
      v.kind = Json::Kind::number;
      v.number = number();
    }
    return v;
  }

  std::string string_literal() {
    if (i_ >= s_.size() || s_[i_] != '"') fail("expected a string");
    ++i_;
    std::string r;
    while (i_ < s_.size() && s_[i_] != '"') {
      const char c = s_[i_++];
      if (static_cast<unsigned char>(c) < 0x20) fail("control character in a string");
      if (c != '\\') {
        r += c;
        continue;
      }
      if (i_ >= s_.size()) fail("unfinished escape");
      const char e = s_[i_++];
      switch (e) {
        case '"': r += '"'; break;
        case '\\': r += '\\'; break;
        case '/': r += '/'; break;
        case 'b': r += '\b'; break;
        case 'f': r += '\f'; break;
        case 'n': r += '\n'; break;
        case 'r': r += '\r'; break;
        case 't': r += '\t'; break;
        case 'u':
          if (i_ + 4 > s_.size()) fail("short \\u escape");
          for (int k = 0; k < 4; ++k)
            if (!std::isxdigit(static_cast<unsigned char>(s_[i_ + std::size_t(k)]))) fail("bad \\u escape");
          r += char(std::strtol(s_.substr(i_, 4).c_str(), nullptr, 16));  // enough for the ASCII a writer escapes
          i_ += 4;
          break;
        default: fail("bad escape");
      }
    }
    if (i_ >= s_.size()) fail("unterminated string");
    ++i_;
    return r;
  }

  double number() {
    // JSON grammar: -?(0|[1-9][0-9]*)(\.[0-9]+)?([eE][+-]?[0-9]+)?  (no nan, inf, leading + or dot)
    static const std::regex grammar(R"(-?(0|[1-9][0-9]*)(\.[0-9]+)?([eE][+-]?[0-9]+)?)");
    std::size_t end = i_;
    while (end < s_.size() && (std::isdigit(static_cast<unsigned char>(s_[end])) || std::string("+-.eE").find(s_[end]) != std::string::npos))
      ++end;
    const std::string text = s_.substr(i_, end - i_);
    if (text.empty() || !std::regex_match(text, grammar)) fail("bad number '" + text + "'");
    i_ = end;
    return std::strtod(text.c_str(), nullptr);
  }

  const std::string& s_;
  std::size_t i_ = 0;
};

std::string attribute(const std::string& element, const std::string& name) {
  const std::regex re("\\s" + name + "=\"([^\"]*)\"");
  std::smatch m;
  if (!std::regex_search(element, m, re)) throw std::runtime_error("pvd: <DataSet> without " + name + ": " + element);
  return m[1];
}

}  // namespace

const Json& Json::at(const std::string& key) const {
  if (!has(key)) throw std::runtime_error("JSON: no key " + key);
  return object.at(key);
}

Json parse_json(const std::string& text) { return JsonParser(text).document(); }

std::vector<PvdEntry> parse_pvd(const std::string& text) {
  if (text.rfind("<?xml", 0) != 0) throw std::runtime_error("pvd: no XML declaration");
  if (!std::regex_search(text, std::regex(R"(<VTKFile[^>]*\stype="Collection")")))
    throw std::runtime_error("pvd: not a VTKFile of type Collection");
  const auto open = text.find("<Collection>"), close = text.find("</Collection>"), end = text.find("</VTKFile>");
  if (open == std::string::npos || close == std::string::npos || end == std::string::npos || !(open < close && close < end))
    throw std::runtime_error("pvd: <Collection> or </VTKFile> missing or out of order");
  std::vector<PvdEntry> r;
  const std::string body = text.substr(open, close - open);
  const std::regex dataset(R"(<DataSet\b[^>]*/>)");
  for (auto it = std::sregex_iterator(body.begin(), body.end(), dataset); it != std::sregex_iterator(); ++it) {
    const std::string e = it->str();
    r.push_back({std::stod(attribute(e, "timestep")), attribute(e, "file")});
  }
  // Anything in the collection other than DataSet elements and white space is malformed.
  const std::string rest = std::regex_replace(body.substr(std::string("<Collection>").size()), dataset, "");
  if (!std::all_of(rest.begin(), rest.end(), [](char c) { return std::isspace(static_cast<unsigned char>(c)); }))
    throw std::runtime_error("pvd: unexpected content in <Collection>: " + rest);
  return r;
}

std::vector<std::string> files_under(const std::string& dir) {
  std::vector<std::string> r;
  if (!std::filesystem::exists(dir)) return r;
  for (const auto& e : std::filesystem::recursive_directory_iterator(dir))
    if (e.is_regular_file()) r.push_back(std::filesystem::relative(e.path(), dir).string());
  std::sort(r.begin(), r.end());
  return r;
}

std::string without_warnings(const std::string& text) {
  std::istringstream in(text);
  std::string line, kept;
  while (std::getline(in, line))
    if (line.find(": warning: ") == std::string::npos) kept += line + "\n";
  return kept;
}

bool looks_like_crash(const std::string& err) {
  for (const char* sign : {"internal error", "terminate called", "Assertion", "assertion", "Aborted", "Segmentation",
                           "core dumped", "what():", "std::", "AddressSanitizer", "runtime error:"})
    if (err.find(sign) != std::string::npos) return true;
  return false;
}

}  // namespace loom::testing
