// The nesting depth TinyXML would reach on a text (see xml_depth.hpp). A recursive
// descent over the same grammar TinyXML 2.6.2 parses, keeping only where each node ends:
// every function takes the position of a node and returns the position after it, or
// nullptr where TinyXML would stop with an error (after which it reads nothing more, so
// neither does the scan). The recursion stops at depth limit + 1, so the scan itself
// never goes deep.
#include "xml_depth.hpp"

#include <algorithm>
#include <cctype>
#include <cstring>
#include <string>
#include <vector>

namespace achd {
namespace {

class DepthScan {
 public:
  // `entity_encoding_means_utf8`: what to take an encoding written with entities for.
  DepthScan(const char* text, int limit, bool entity_encoding_means_utf8)
      : begin_(text), limit_(limit), entity_encoding_means_utf8_(entity_encoding_means_utf8) {}

  // Whether the text declared its encoding with entities, which the scan does not
  // decode: it then has to be scanned with both assumptions.
  bool encoding_had_entities() const { return encoding_had_entities_; }

  // TinyXML's TiXmlDocument::Parse: top-level nodes until the text ends or one fails.
  std::size_t run() {
    const char* p = begin_;
    if (!*p) return std::string::npos;
    const auto* u = reinterpret_cast<const unsigned char*>(p);
    if (u[0] == 0xef && u[1] == 0xbb && u[2] == 0xbf) encoding_ = Encoding::Utf8;  // BOM
    p = skip_space(p);
    while (p && *p) {
      const Kind kind = identify(p);
      if (kind == Kind::None) break;
      declared_utf8_ = true;  // no encoding attribute: ""
      p = parse(kind, p);
      // The first declaration read while the encoding is unknown sets it.
      if (kind == Kind::Declaration && encoding_ == Encoding::Unknown)
        encoding_ = declared_utf8_ ? Encoding::Utf8 : Encoding::Legacy;
      p = skip_space(p);
    }
    return too_deep_at_;
  }

 private:
  enum class Encoding { Unknown, Utf8, Legacy };
  enum class Kind { None, Declaration, Comment, Cdata, Unknown, Element };

  static bool is_space(char c) { return std::isspace(static_cast<unsigned char>(c)) != 0; }
  // TinyXML counts every byte from 127 up as a letter.
  static bool is_alpha(char c) {
    const auto u = static_cast<unsigned char>(c);
    return u >= 127 || std::isalpha(u);
  }
  static bool is_name_char(char c) {
    const auto u = static_cast<unsigned char>(c);
    return u >= 127 || std::isalnum(u) || c == '_' || c == '-' || c == '.' || c == ':';
  }
  static bool starts_with(const char* p, const char* tag) {
    return std::strncmp(p, tag, std::strlen(tag)) == 0;
  }
  static bool starts_with_nocase(const char* p, const char* tag) {
    for (; *tag; ++p, ++tag)
      if (!*p || std::tolower(static_cast<unsigned char>(*p)) != *tag) return false;
    return true;
  }

  // TiXmlBase::SkipWhiteSpace: nullptr at the end of the text; with UTF-8 it also
  // skips the byte-order mark and the two non-characters EF BF BE and EF BF BF.
  const char* skip_space(const char* p) const {
    if (!p || !*p) return nullptr;
    for (;;) {
      const auto* u = reinterpret_cast<const unsigned char*>(p);
      if (encoding_ == Encoding::Utf8 && u[0] == 0xef &&
          ((u[1] == 0xbb && u[2] == 0xbf) || (u[1] == 0xbf && (u[2] == 0xbe || u[2] == 0xbf)))) {
        p += 3;
      } else if (*p && is_space(*p)) {
        ++p;
      } else {
        return p;
      }
    }
  }

  // TinyXML's table of UTF-8 sequence lengths by lead byte (1 for invalid leads).
  static int utf8_length(unsigned char lead) {
    if (lead >= 0xc2 && lead <= 0xdf) return 2;
    if (lead >= 0xe0 && lead <= 0xef) return 3;
    if (lead >= 0xf0 && lead <= 0xf4) return 4;
    return 1;
  }

  // TiXmlBase::GetChar: one character of text or of a quoted attribute value. With
  // UTF-8, a lead byte steps over its continuation bytes whatever they are (a quote, a
  // '<'); TinyXML steps even past the end of the text, where the loader's padding puts
  // NULs: the scan stops at the end instead, as TinyXML then does.
  const char* next_char(const char* p) const {
    if (*p == '&') return entity_end(p);
    const int length = encoding_ == Encoding::Utf8 ? utf8_length(static_cast<unsigned char>(*p)) : 1;
    for (int i = 1; i < length; ++i)
      if (!p[i]) return p + i;
    return p + length;
  }

  // TiXmlBase::GetEntity. "&#x...;" and "&#...;" end at the next ';' anywhere after
  // them, provided the characters between it and the nearest 'x' (or '#') before it are
  // hex (decimal) digits: such an entity can span quotes and tags. A bad one stops TinyXML.
  static const char* entity_end(const char* p) {
    if (p[1] == '#' && p[2]) {
      const bool hex = p[2] == 'x';
      if (hex && !p[3]) return nullptr;
      const char* semicolon = std::strchr(p + (hex ? 3 : 2), ';');
      if (!semicolon) return nullptr;
      for (const char* q = semicolon - 1; *q != (hex ? 'x' : '#'); --q)
        if (!(hex ? std::isxdigit(static_cast<unsigned char>(*q)) : std::isdigit(static_cast<unsigned char>(*q))))
          return nullptr;
      return semicolon + 1;
    }
    for (const char* name : {"&amp;", "&lt;", "&gt;", "&quot;", "&apos;"})
      if (starts_with(p, name)) return p + std::strlen(name);
    return p + 1;
  }

  // TiXmlBase::ReadText up to and past `end` (a quote, or "<" for text); nullptr when the
  // text ends first or right after it.
  const char* read_text(const char* p, char end) const {
    while (p && *p && *p != end) p = is_space(*p) ? p + 1 : next_char(p);
    if (!p || !*p) return nullptr;
    ++p;
    return *p ? p : nullptr;
  }

  // TiXmlBase::ReadName: a letter or '_', then name characters; nullptr if none.
  static const char* read_name(const char* p) {
    if (!p || !*p || !(is_alpha(*p) || *p == '_')) return nullptr;
    while (*p && is_name_char(*p)) ++p;
    return p;
  }

  // TiXmlNode::Identify, at a '<'.
  static Kind identify(const char* p) {
    if (*p != '<') return Kind::None;
    if (starts_with_nocase(p, "<?xml")) return Kind::Declaration;
    if (starts_with(p, "<!--")) return Kind::Comment;
    if (starts_with(p, "<![CDATA[")) return Kind::Cdata;
    if (starts_with(p, "<!")) return Kind::Unknown;
    if (is_alpha(p[1]) || p[1] == '_') return Kind::Element;
    return Kind::Unknown;
  }

  const char* parse(Kind kind, const char* p) {
    switch (kind) {
      case Kind::Declaration: return declaration(p);
      case Kind::Comment: return raw_until(p + 4, "-->");
      case Kind::Cdata: {
        const char* end = raw_until(p + 9, "]]>");
        return end && *end ? end : nullptr;
      }
      case Kind::Unknown: return raw_until(p + 1, ">");
      case Kind::Element: return element(p);
      case Kind::None: break;
    }
    return nullptr;
  }

  // Byte by byte to `end` and past it (comments, CDATA, unknown nodes); at the end of the
  // text, the end of the text.
  static const char* raw_until(const char* p, const char* end) {
    const char* found = std::strstr(p, end);
    return found ? found + std::strlen(end) : p + std::strlen(p);
  }

  // TiXmlAttribute::Parse: name, '=', a quoted value or an unquoted one (which ends at
  // white space, '/' or '>' and must not contain a quote). The name goes to `name`, the
  // value's text (entities not decoded) to `value`.
  const char* attribute(const char* p, std::string& name, std::string& value) const {
    const char* start = skip_space(p);
    p = read_name(start);
    if (!p) return nullptr;
    name.assign(start, p);
    p = skip_space(p);
    if (!p || *p != '=') return nullptr;
    p = skip_space(p + 1);
    if (!p) return nullptr;
    if (*p == '\'' || *p == '"') {
      const char* end = read_text(p + 1, *p);
      if (end) value.assign(p + 1, end - 1);
      return end;
    }
    for (start = p; *p && !is_space(*p) && *p != '/' && *p != '>'; ++p)
      if (*p == '\'' || *p == '"') return nullptr;
    value.assign(start, p);
    return p;
  }

  // TiXmlDeclaration::Parse: "<?xml", then version/encoding/standalone attributes (any
  // name starting so) or other words, to the first '>' outside them. The encoding is
  // UTF-8 when the last "encoding..." value is empty or starts with UTF-8 or UTF8 (any
  // case), else a legacy one.
  const char* declaration(const char* p) {
    p += 5;
    while (p && *p) {
      if (*p == '>') return p + 1;
      p = skip_space(p);
      if (!p) break;
      const bool version = starts_with_nocase(p, "version");
      if (version || starts_with_nocase(p, "encoding") || starts_with_nocase(p, "standalone")) {
        std::string name, value;
        p = attribute(p, name, value);
        if (!version && starts_with_nocase(name.c_str(), "encoding")) {
          if (value.find('&') != std::string::npos) {
            encoding_had_entities_ = true;
            declared_utf8_ = entity_encoding_means_utf8_;
          } else {
            declared_utf8_ = value.empty() || starts_with_nocase(value.c_str(), "utf-8") ||
                             starts_with_nocase(value.c_str(), "utf8");
          }
        }
      } else {
        while (*p && *p != '>' && !is_space(*p)) ++p;
      }
    }
    return nullptr;
  }

  // TiXmlElement::Parse and ReadValue: the start tag, its content and its end tag.
  const char* element(const char* start) {
    if (depth_ == limit_) {
      too_deep_at_ = static_cast<std::size_t>(start - begin_);
      return nullptr;
    }
    ++depth_;
    const char* end = element_body(start);
    --depth_;
    return end;
  }

  const char* element_body(const char* p) {
    const char* name = skip_space(p + 1);
    p = read_name(name);
    if (!p || !*p) return nullptr;
    const std::string end_tag = "</" + std::string(name, p);
    std::vector<std::string> attributes;  // a repeated name stops TinyXML
    for (;;) {
      p = skip_space(p);
      if (!p) return nullptr;
      if (*p == '/') return p[1] == '>' ? p + 2 : nullptr;
      if (*p == '>') break;
      std::string attribute_name, value;
      p = attribute(p, attribute_name, value);
      if (!p || !*p) return nullptr;
      if (std::find(attributes.begin(), attributes.end(), attribute_name) != attributes.end()) return nullptr;
      attributes.push_back(attribute_name);
    }
    p = content(p + 1);
    if (!p || !*p || !starts_with(p, end_tag.c_str())) return nullptr;
    p = skip_space(p + end_tag.size());
    return p && *p == '>' ? p + 1 : nullptr;
  }

  // Text and child nodes up to an end tag ("</"), which the element then checks.
  const char* content(const char* p) {
    p = skip_space(p);
    while (p && *p) {
      if (*p != '<') {
        p = read_text(p, '<');  // TiXmlText::Parse: up to the '<', which it leaves
        if (p) --p;
      } else if (starts_with(p, "</")) {
        return p;
      } else {
        p = parse(identify(p), p);
      }
      p = skip_space(p);
    }
    return p;
  }

  const char* const begin_;
  const int limit_;
  const bool entity_encoding_means_utf8_;
  Encoding encoding_ = Encoding::Unknown;
  bool declared_utf8_ = true;  // the last declaration's encoding, while it is read
  bool encoding_had_entities_ = false;
  int depth_ = 0;
  std::size_t too_deep_at_ = std::string::npos;
};

}  // namespace

std::size_t xml_too_deep_at(const std::string& text, int limit) {
  DepthScan utf8(text.c_str(), limit, true);
  const std::size_t at = utf8.run();
  if (!utf8.encoding_had_entities()) return at;
  return std::min(at, DepthScan(text.c_str(), limit, false).run());
}

}  // namespace achd
