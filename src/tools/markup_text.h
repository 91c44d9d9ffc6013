// Text placed in XML and HTML (the suite's junit.xml and report.html): escaped so that any message,
// path or scene name reads back as written and the document stays well formed.
#pragma once

#include <string>

namespace haif {

/// `text` escaped for an XML 1.0 / HTML attribute value or element: & < > " ' as entities, tab,
/// newline and carriage return as character references (so attribute values keep them; element text
/// may keep tabs and newlines as they are: `keepLineBreaks`), other control characters and bytes that
/// are not UTF-8 (which XML 1.0 forbids) as '?'.
std::string escapeMarkup(const std::string& text, bool keepLineBreaks = false);

/// A relative path as a URL path: bytes that would end or confuse a link are percent-encoded.
std::string urlPath(const std::string& path);

}  // namespace haif
