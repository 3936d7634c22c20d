// A strict JSON reader for tests that parse a tool's JSON output back (RFC 8259: one value,
// whitespace around it, no trailing commas, no comments, no NaN). Header-only, no dependencies:
// include it as "support/json_value.hpp" with tests/ on the include path. Numbers are read with
// strtod, so "%.17g" output reads back as the same double. A malformed text throws
// std::runtime_error naming the byte offset.
#pragma once

#include <cstdint>
#include <cstdlib>
#include <stdexcept>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace ntn_test {

class Json {
 public:
  enum class Type : std::uint8_t { kNull, kBool, kNumber, kString, kArray, kObject };

  static Json parse(std::string_view text) {
    Reader r{text, 0};
    r.space();
    Json v = r.value(0);
    r.space();
    if (r.at != text.size()) r.fail("text after the JSON value");
    return v;
  }

  Type type() const { return type_; }
  bool is_null() const { return type_ == Type::kNull; }
  bool boolean() const { return want(Type::kBool), bool_; }
  double number() const { return want(Type::kNumber), number_; }
  const std::string& string() const { return want(Type::kString), string_; }
  const std::vector<Json>& array() const { return want(Type::kArray), items_; }
  // An array's items or an object's members.
  std::size_t size() const { return type_ == Type::kObject ? items_.size() : array().size(); }
  const Json& operator[](std::size_t i) const { return array().at(i); }
  bool has(const std::string& key) const { return find(key) != nullptr; }
  const Json& operator[](const std::string& key) const {
    const Json* v = find(key);
    if (v == nullptr) throw std::runtime_error("JSON: no key '" + key + "'");
    return *v;
  }
  // An object's keys in the text's order.
  const std::vector<std::string>& keys() const { return want(Type::kObject), keys_; }

 private:
  const Json* find(const std::string& key) const {
    want(Type::kObject);
    for (std::size_t i = 0; i < keys_.size(); ++i)
      if (keys_[i] == key) return &items_[i];
    return nullptr;
  }
  void want(Type t) const {
    if (type_ != t) throw std::runtime_error("JSON: the value has another type");
  }

  struct Reader {
    std::string_view s;
    std::size_t at;

    [[noreturn]] void fail(const std::string& what) const {
      throw std::runtime_error("JSON: " + what + " at byte " + std::to_string(at));
    }
    void space() {
      while (at < s.size() && (s[at] == ' ' || s[at] == '\n' || s[at] == '\r' || s[at] == '\t'))
        ++at;
    }
    bool take(char c) {
      if (at < s.size() && s[at] == c) return ++at, true;
      return false;
    }
    void word(std::string_view w) {
      if (s.substr(at, w.size()) != w) fail("bad literal");
      at += w.size();
    }
    Json value(int depth) {
      if (depth > 64) fail("nested too deep");
      if (at >= s.size()) fail("unexpected end");
      Json v;
      const char c = s[at];
      if (c == '{') {
        ++at;
        v.type_ = Type::kObject;
        space();
        if (take('}')) return v;
        do {
          space();
          if (at >= s.size() || s[at] != '"') fail("expected a key");
          std::string key = string_literal();
          space();
          if (!take(':')) fail("expected ':'");
          space();
          if (v.find(key) != nullptr) fail("repeated key '" + key + "'");
          v.items_.push_back(value(depth + 1));
          v.keys_.push_back(std::move(key));
          space();
        } while (take(','));
        if (!take('}')) fail("expected ',' or '}'");
      } else if (c == '[') {
        ++at;
        v.type_ = Type::kArray;
        space();
        if (take(']')) return v;
        do {
          space();
          v.items_.push_back(value(depth + 1));
          space();
        } while (take(','));
        if (!take(']')) fail("expected ',' or ']'");
      } else if (c == '"') {
        v.type_ = Type::kString;
        v.string_ = string_literal();
      } else if (c == 't' || c == 'f') {
        v.type_ = Type::kBool;
        v.bool_ = c == 't';
        word(c == 't' ? "true" : "false");
      } else if (c == 'n') {
        word("null");
      } else {
        v.type_ = Type::kNumber;
        v.number_ = number_literal();
      }
      return v;
    }
    bool digit() const { return at < s.size() && s[at] >= '0' && s[at] <= '9'; }
    double number_literal() {
      const std::size_t start = at;
      take('-');
      if (take('0')) {
      } else if (digit()) {
        while (digit())
          ++at;
      } else {
        fail("bad number");
      }
      if (take('.')) {
        if (!digit()) fail("bad fraction");
        while (digit())
          ++at;
      }
      if (take('e') || take('E')) {
        if (!take('+')) take('-');
        if (!digit()) fail("bad exponent");
        while (digit())
          ++at;
      }
      const std::string text(s.substr(start, at - start));
      return std::strtod(text.c_str(), nullptr);
    }
    unsigned hex4() {
      if (at + 4 > s.size()) fail("short \\u escape");
      unsigned u = 0;
      for (int i = 0; i < 4; ++i, ++at) {
        const char c = s[at];
        u <<= 4;
        if (c >= '0' && c <= '9') {
          u |= static_cast<unsigned>(c - '0');
        } else if (c >= 'a' && c <= 'f') {
          u |= static_cast<unsigned>(c - 'a' + 10);
        } else if (c >= 'A' && c <= 'F') {
          u |= static_cast<unsigned>(c - 'A' + 10);
        } else {
          fail("bad \\u escape");
        }
      }
      return u;
    }
    static void utf8(std::string& o, unsigned cp) {
      if (cp < 0x80) {
        o += static_cast<char>(cp);
      } else if (cp < 0x800) {
        o += static_cast<char>(0xC0 | (cp >> 6));
        o += static_cast<char>(0x80 | (cp & 0x3F));
      } else if (cp < 0x10000) {
        o += static_cast<char>(0xE0 | (cp >> 12));
        o += static_cast<char>(0x80 | ((cp >> 6) & 0x3F));
        o += static_cast<char>(0x80 | (cp & 0x3F));
      } else {
        o += static_cast<char>(0xF0 | (cp >> 18));
        o += static_cast<char>(0x80 | ((cp >> 12) & 0x3F));
        o += static_cast<char>(0x80 | ((cp >> 6) & 0x3F));
        o += static_cast<char>(0x80 | (cp & 0x3F));
      }
    }
    std::string string_literal() {
      ++at;  // the opening quote
      std::string o;
      while (true) {
        if (at >= s.size()) fail("unterminated string");
        const char c = s[at++];
        if (c == '"') return o;
        if (static_cast<unsigned char>(c) < 0x20) fail("control character in a string");
        if (c != '\\') {
          o += c;
          continue;
        }
        if (at >= s.size()) fail("unterminated escape");
        const char e = s[at++];
        switch (e) {
          case '"':
          case '\\':
          case '/':
            o += e;
            break;
          case 'b':
            o += '\b';
            break;
          case 'f':
            o += '\f';
            break;
          case 'n':
            o += '\n';
            break;
          case 'r':
            o += '\r';
            break;
          case 't':
            o += '\t';
            break;
          case 'u': {
            unsigned cp = hex4();
            if (cp >= 0xD800 && cp < 0xDC00) {  // a surrogate pair
              if (!take('\\') || !take('u')) fail("lone high surrogate");
              const unsigned lo = hex4();
              if (lo < 0xDC00 || lo >= 0xE000) fail("bad low surrogate");
              cp = 0x10000 + ((cp - 0xD800) << 10) + (lo - 0xDC00);
            } else if (cp >= 0xDC00 && cp < 0xE000) {
              fail("lone low surrogate");
            }
            utf8(o, cp);
            break;
          }
          default:
            fail("bad escape");
        }
      }
    }
  };

  Type type_ = Type::kNull;
  bool bool_ = false;
  double number_ = 0;
  std::string string_;
  std::vector<Json> items_;        // an array's items, an object's values
  std::vector<std::string> keys_;  // an object's keys
};

}  // namespace ntn_test
