// A reader for the shader ops' JSON tables of cases (core/tests/data/shader_*_cases.json, which
// the Python twins' tests read too): numbers, strings (an escape keeps the character it escapes:
// \" and \\ suffice), true/false (as the numbers 1 and 0), arrays and objects.
#pragma once

#include "torrance/util/math.h"

#include <cctype>
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace torrance::test {

struct Json {
  enum class Kind { Number, String, Array, Object } kind = Kind::Number;
  float number = 0.0f;  // rounded to float once (strtof), as a node's inputs are
  double exact = 0.0;   // as a double (integers beyond float's 24 bits)
  std::string text;     // a string, or a number's digits as written (true/false: the word)
  std::vector<Json> items;
  std::vector<std::pair<std::string, Json>> members;

  const Json& operator[](const std::string& key) const {
    for (const auto& [k, v] : members)
      if (k == key) return v;
    throw std::runtime_error("no member " + key);
  }
  bool has(const std::string& key) const {
    for (const auto& m : members)
      if (m.first == key) return true;
    return false;
  }
  const Json& operator[](size_t i) const { return items.at(i); }
  size_t size() const { return items.size(); }
  Vec3 vec3() const { return Vec3(items.at(0).number, items.at(1).number, items.at(2).number); }
  std::vector<float> floats() const {
    std::vector<float> out;
    for (const Json& v : items) out.push_back(v.number);
    return out;
  }
  // A number's digits read as an integer (strtoul: a uint32 hash key; atoi).
  uint32_t uint() const { return uint32_t(std::strtoul(text.c_str(), nullptr, 10)); }
  int integer() const { return std::atoi(text.c_str()); }
};

class JsonReader {
 public:
  explicit JsonReader(std::string text) : s_(std::move(text)) {}
  Json read() {
    Json v = value();
    skip_space();
    if (i_ != s_.size()) fail("trailing text");
    return v;
  }

 private:
  void skip_space() {
    while (i_ < s_.size() && std::isspace(static_cast<unsigned char>(s_[i_]))) ++i_;
  }
  [[noreturn]] void fail(const std::string& what) const {
    throw std::runtime_error("JSON: " + what + " at offset " + std::to_string(i_));
  }
  bool take(char c) {
    skip_space();
    if (i_ < s_.size() && s_[i_] == c) return ++i_, true;
    return false;
  }
  std::string string() {
    if (!take('"')) fail("expected a string");
    std::string out;
    for (; i_ < s_.size() && s_[i_] != '"'; ++i_) {
      if (s_[i_] == '\\' && ++i_ == s_.size()) break;
      out += s_[i_];
    }
    if (i_ >= s_.size()) fail("unterminated string");
    ++i_;
    return out;
  }
  Json value() {
    skip_space();
    Json v;
    if (i_ >= s_.size()) fail("unexpected end");
    if (s_[i_] == '"') {
      v.kind = Json::Kind::String;
      v.text = string();
    } else if (take('[')) {
      v.kind = Json::Kind::Array;
      if (!take(']')) {
        do v.items.push_back(value());
        while (take(','));
        if (!take(']')) fail("expected ]");
      }
    } else if (take('{')) {
      v.kind = Json::Kind::Object;
      if (!take('}')) {
        do {
          std::string key = string();
          if (!take(':')) fail("expected :");
          v.members.emplace_back(std::move(key), value());
        } while (take(','));
        if (!take('}')) fail("expected }");
      }
    } else if (s_.compare(i_, 4, "true") == 0 || s_.compare(i_, 5, "false") == 0) {
      const bool yes = s_[i_] == 't';
      v.text = yes ? "true" : "false";
      v.number = yes ? 1.0f : 0.0f;
      v.exact = yes ? 1.0 : 0.0;
      i_ += v.text.size();
    } else {
      const char* begin = s_.c_str() + i_;
      char* end = nullptr;
      v.number = std::strtof(begin, &end);
      if (end == begin) fail("expected a value");
      v.exact = std::strtod(begin, nullptr);
      v.text.assign(begin, size_t(end - begin));
      i_ += size_t(end - begin);
    }
    return v;
  }

  std::string s_;
  size_t i_ = 0;
};

// The table core/tests/data/<name>.
inline Json read_json_table(const std::string& name) {
#ifdef TORRANCE_TEST_DATA_DIR
  const auto path = std::filesystem::path(TORRANCE_TEST_DATA_DIR) / name;
#else
  const auto path = std::filesystem::path(__FILE__).parent_path() / "data" / name;
#endif
  std::ifstream file(path);
  if (!file) throw std::runtime_error("cannot read " + path.string());
  std::stringstream text;
  text << file.rdbuf();
  return JsonReader(text.str()).read();
}

// The table core/tests/data/<name>, read once (the tests ask for it again and again).
inline const Json& json_table(const std::string& name) {
  static std::map<std::string, Json> tables;
  auto it = tables.find(name);
  if (it == tables.end()) it = tables.emplace(name, read_json_table(name)).first;
  return it->second;
}

}  // namespace torrance::test
