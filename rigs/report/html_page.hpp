// What every HTML page the rig writes (the episode report, the sweep index) does with text from
// outside: episode fields, model output, scenario names and file names are data, never markup.
// Values go in as escaped text or as JSON in a data block; links to files are relative paths
// percent-encoded; and each page carries a Content-Security-Policy that lets only its own inline
// scripts and styles run (by SHA-256 hash) and loads nothing from the network, so a slip in the
// escaping is still blocked by the browser.
#pragma once

#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

namespace a3::rigs {

// Text for an element's content or a quoted attribute: & < > " ' as entities.
std::string html_escaped(std::string_view text);

// An href/src for a file at `relative` below the page's folder: "./" and each segment
// percent-encoded (RFC 3986 unreserved characters kept), so that no name becomes a scheme
// ("javascript:"), a host ("//x") or a parent ("..", refused with std::invalid_argument).
std::string relative_href(const std::filesystem::path& relative);

// The contents of each <TAG>...</TAG> element written exactly so (no attributes) in `page`: the
// inline scripts or styles of a page skeleton that holds only the rig's own text.
std::vector<std::string_view> inline_elements(std::string_view page, std::string_view tag);

// The policy: default-src 'none'; scripts and styles only those whose exact text is given (by
// 'sha256-...'), images only from `img_sources` (e.g. "'self'"; empty: none), no base, forms,
// frames, plugins or connections.
std::string content_security_policy(const std::vector<std::string_view>& inline_scripts,
                                    const std::vector<std::string_view>& inline_styles,
                                    std::string_view img_sources);

// <meta http-equiv="Content-Security-Policy" content="POLICY">, to go first in <head>.
std::string content_security_policy_meta(const std::string& policy);

}  // namespace a3::rigs
