// A reader for the shader ops' JSON tables of cases (core/tests/data/shader_*_cases.json, which
// the Python twins' tests read too): numbers, strings without escapes, arrays and objects.
#pragma once

#include "torrance/math.h"

#include <cctype>
#include <cstdlib>
#include <filesystem>
#include <fstream>
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
  std::string text;
  std::vector<Json> items;
  std::vector<std::pair<std::string, Json>> members;

  const Json& operator[](const std::string& key) const {
    for (const auto& [k, v] : members)
      if (k == key) return v;
    throw std::runtime_error("no member " + key);
  }
  const Json& operator[](size_t i) const { return items.at(i); }
  size_t size() const { return items.size(); }
  Vec3 vec3() const { return Vec3(items.at(0).number, items.at(1).number, items.at(2).number); }
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
    const size_t end = s_.find('"', i_);
    if (end == std::string::npos) fail("unterminated string");
    std::string out = s_.substr(i_, end - i_);
    i_ = end + 1;
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
    } else {
      const char* begin = s_.c_str() + i_;
      char* end = nullptr;
      v.number = std::strtof(begin, &end);
      if (end == begin) fail("expected a value");
      v.exact = std::strtod(begin, nullptr);
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

}  // namespace torrance::test
