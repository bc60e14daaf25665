// The loader's nesting scan (xml_depth.cpp) against TinyXML itself: on random
// texts made of the tokens TinyXML reads specially (tags, quotes, comments, CDATA,
// declarations, "<!" and "<?" nodes, entities, UTF-8 lead bytes, byte-order marks), the
// depth at which the scan stops is the deepest element TinyXML builds, exactly.
#include "xml_depth.hpp"  // achd_internals

#include <random>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <tinyxml.h>

namespace {

// The deepest element under `node` (TinyXML links every element it opens, even when
// the text fails later, so this is how deep its parser recursed).
int element_depth(const TiXmlNode* node) {
  int deepest = 0;
  for (const TiXmlNode* c = node->FirstChild(); c; c = c->NextSibling())
    deepest = std::max(deepest, element_depth(c) + (c->ToElement() ? 1 : 0));
  return deepest;
}

// The least limit the scan accepts the text under.
int scanned_depth(const std::string& text) {
  int limit = 0;
  while (achd::xml_too_deep_at(text, limit) != std::string::npos) ++limit;
  return limit;
}

TEST(XmlDepth, MatchesTinyXmlOnRandomTexts) {
  const std::vector<std::string> tokens = {
      "<x>", "<x>", "<x>", "<x>", "<x>", "<x>", "</x>", "</x>", "<y/>", "<x a=\"", "<x a='", "<x a=b", " b=\"1\"", "\"", "'",
      ">", "/>", "<!--", "-->", "<![CDATA[", "]]>", "<?xml version=\"1.0\"?>", "<?xml encoding=\"latin1\"?>",
      "<?pi", "<!d [", "]", "&#x", "x41;", "&#", "65;", "&amp;", "&", ";", "\xc3", "\xe2\x82", "\xf0",
      "\xef\xbb\xbf", " ", "\n", "t", "=", "<", "</", "x", "_"};
  std::mt19937 rng(13);
  std::uniform_int_distribution<size_t> pick(0, tokens.size() - 1);
  std::uniform_int_distribution<int> length(1, 60);
  int deep = 0;
  for (int k = 0; k < 200000; ++k) {
    std::string text;
    for (int n = length(rng); n > 0; --n) text += tokens[pick(rng)];
    text += std::string(3, '\0');  // as the loader pads it
    TiXmlDocument doc;
    doc.Parse(text.c_str());
    const int depth = element_depth(&doc);
    ASSERT_EQ(scanned_depth(text), depth) << text.c_str();
    deep += depth >= 3;
  }
  EXPECT_GT(deep, 8000);  // the texts do nest
}

}  // namespace
