#pragma once
// How deep TinyXML would nest a text's elements, found without TinyXML. Its parser calls
// itself once per nested element, and so does the destructor of its document: a URDF
// nested ~50000 deep overflows the native stack (SIGSEGV) and, at ~3000, the JS call
// stack of the wasm build (a RangeError that unwinds past every C++ destructor, leaking
// the half-built document). The loader measures the depth first with this scan, which
// follows TinyXML 2.6.2's own reading rules (the Debian source both builds use), not the
// XML specification's, so that whatever TinyXML would read as an element is counted:
// comments end at the first "-->", CDATA at the first "]]>", "<!..." and "<?..." other
// than "<?xml" at the first ">", quoted attribute values at their quote (with TinyXML's
// entity and UTF-8 rules, which can step over a quote or a '<'), and the XML
// declaration's encoding decides whether UTF-8 rules apply (both outcomes are scanned).
#include <cstddef>
#include <string>

namespace achd {

// The offset of the first '<' at which TinyXML would open an element at depth
// limit + 1 (the root element is at depth 1), or std::string::npos if it never would.
// Like TinyXML, reads `text` up to its first NUL.
std::size_t xml_too_deep_at(const std::string& text, int limit);

}  // namespace achd
