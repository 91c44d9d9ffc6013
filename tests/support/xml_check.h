// A small, strict reader of the XML the tools write (junit.xml): it accepts only well-formed
// documents (one root, balanced tags, quoted attributes, no raw '<' or stray '&' in text or values,
// only the predefined and numeric entities) and returns the element tree with decoded text, so a
// test can both check that CI systems will parse the file and count what is in it.
#pragma once

#include <cctype>
#include <cstdlib>
#include <map>
#include <string>
#include <vector>

namespace haif::test {

struct XmlElement {
  std::string name;
  std::map<std::string, std::string> attributes;  ///< decoded values
  std::string text;                               ///< decoded character data directly inside
  std::vector<XmlElement> children;

  /// Children named `n`.
  std::vector<const XmlElement*> all(const std::string& n) const {
    std::vector<const XmlElement*> out;
    for (const XmlElement& c : children)
      if (c.name == n) out.push_back(&c);
    return out;
  }
  std::string attr(const std::string& key) const {
    const auto it = attributes.find(key);
    return it == attributes.end() ? std::string() : it->second;
  }
};

class XmlReader {
 public:
  /// Parses `text`; false with `error` (what and at which byte) when it is not well formed.
  bool parse(const std::string& text, XmlElement& root, std::string& error) {
    s_ = &text;
    pos_ = 0;
    error_.clear();
    skipSpace();
    if (text.compare(pos_, 5, "<?xml") == 0) {
      const size_t end = text.find("?>", pos_);
      if (end == std::string::npos) return failAt("unterminated XML declaration", error);
      pos_ = end + 2;
    }
    skipSpace();
    if (!element(root, 0)) return failAt(error_, error);
    skipSpace();
    if (pos_ != text.size()) return failAt("content after the root element", error);
    return true;
  }

 private:
  bool failAt(const std::string& what, std::string& error) {
    error = what + " at byte " + std::to_string(pos_);
    return false;
  }
  bool bad(const std::string& what) {
    if (error_.empty()) error_ = what;
    return false;
  }
  void skipSpace() {
    while (pos_ < s_->size() && std::string(" \t\r\n").find((*s_)[pos_]) != std::string::npos) ++pos_;
  }
  static bool nameChar(char c) {
    return std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '-' || c == '.' || c == ':';
  }
  bool name(std::string& out) {
    const size_t start = pos_;
    while (pos_ < s_->size() && nameChar((*s_)[pos_])) ++pos_;
    out = s_->substr(start, pos_ - start);
    return !out.empty() || bad("expected a name");
  }
  // Decodes character data up to `stop` (exclusive), refusing '<' and entities XML does not define.
  bool decode(size_t stop, std::string& out) {
    while (pos_ < stop) {
      const char c = (*s_)[pos_];
      if (c == '<') return bad("raw '<' in text or attribute value");
      if (c != '&') {
        out += c;
        ++pos_;
        continue;
      }
      const size_t semi = s_->find(';', pos_);
      if (semi == std::string::npos || semi > stop) return bad("'&' that starts no entity");
      const std::string ent = s_->substr(pos_ + 1, semi - pos_ - 1);
      static const std::map<std::string, char> named = {
          {"amp", '&'}, {"lt", '<'}, {"gt", '>'}, {"quot", '"'}, {"apos", '\''}};
      if (named.count(ent)) {
        out += named.at(ent);
      } else if (ent.size() > 1 && ent[0] == '#') {
        const bool hex = ent[1] == 'x';
        char* end = nullptr;
        const long code = std::strtol(ent.c_str() + (hex ? 2 : 1), &end, hex ? 16 : 10);
        if (*end != '\0' || code <= 0 || code > 0x7f) return bad("unsupported character reference &" + ent + ";");
        out += char(code);
      } else {
        return bad("unknown entity &" + ent + ";");
      }
      pos_ = semi + 1;
    }
    return true;
  }
  bool element(XmlElement& e, int depth) {
    if (depth > 64) return bad("nested too deep");
    if (pos_ >= s_->size() || (*s_)[pos_] != '<') return bad("expected '<'");
    ++pos_;
    if (!name(e.name)) return false;
    for (;;) {
      skipSpace();
      if (pos_ >= s_->size()) return bad("unterminated start tag <" + e.name);
      if (s_->compare(pos_, 2, "/>") == 0) {
        pos_ += 2;
        return true;
      }
      if ((*s_)[pos_] == '>') {
        ++pos_;
        break;
      }
      std::string key, value;
      if (!name(key)) return false;
      if (pos_ >= s_->size() || (*s_)[pos_] != '=') return bad("attribute " + key + " without '='");
      ++pos_;
      if (pos_ >= s_->size() || (*s_)[pos_] != '"') return bad("attribute " + key + " not in double quotes");
      const size_t close = s_->find('"', ++pos_);
      if (close == std::string::npos) return bad("unterminated attribute " + key);
      if (!decode(close, value)) return false;
      pos_ = close + 1;
      if (!e.attributes.emplace(key, value).second) return bad("attribute " + key + " given twice");
    }
    for (;;) {
      const size_t lt = s_->find('<', pos_);
      if (lt == std::string::npos) return bad("unterminated element <" + e.name + ">");
      if (!decode(lt, e.text)) return false;
      if (s_->compare(pos_, 2, "</") == 0) {
        pos_ += 2;
        std::string closing;
        if (!name(closing)) return false;
        if (closing != e.name) return bad("</" + closing + "> closes <" + e.name + ">");
        skipSpace();
        if (pos_ >= s_->size() || (*s_)[pos_] != '>') return bad("unterminated end tag");
        ++pos_;
        return true;
      }
      e.children.emplace_back();
      if (!element(e.children.back(), depth + 1)) return false;
    }
  }

  const std::string* s_ = nullptr;
  size_t pos_ = 0;
  std::string error_;
};

}  // namespace haif::test
