#pragma once
// The markdown the experiments write (summary.md, the validation report.md) as HTML, for
// the report pages: ATX headings, paragraphs, `-`/`*` and `1.` lists, pipe tables (with
// their alignment row), fenced code blocks; inline `code`, **bold**, *emphasis*, images
// ![alt](src) and links [text](href). Everything else is text, HTML-escaped: no raw HTML
// passes through. Underscores are text (file names such as gem_cuts_METRIC.png).
#include <string>

namespace refract::experiments {

// Percent-encodes what a relative URL path must not carry raw (anything but letters, digits
// and -._~/).
std::string url_path(const std::string& path);

// `base` is prefixed to relative image and link targets (no scheme, not starting with '/' or
// '#'), so that a summary of OUT/NAME/ rendered into OUT/NAME.html keeps pointing at its
// files: base "NAME/".
std::string markdown_to_html(const std::string& markdown, const std::string& base = "");

}  // namespace refract::experiments
