// Text, links and the Content-Security-Policy of the rig's HTML pages (html_page.hpp).
#include "rigs/report/html_page.hpp"

#include <openssl/evp.h>

#include <array>
#include <stdexcept>

namespace a3::rigs {
namespace {

bool is_unreserved(unsigned char c) {
  return (c >= 'A' && c <= 'Z') || (c >= 'a' && c <= 'z') || (c >= '0' && c <= '9') || c == '-' || c == '.' ||
         c == '_' || c == '~';
}

std::string percent_encoded(const std::string& segment) {
  static constexpr char kHex[] = "0123456789ABCDEF";
  std::string out;
  for (const char c : segment) {
    const auto byte = static_cast<unsigned char>(c);
    if (is_unreserved(byte)) {
      out += c;
    } else {
      out += '%';
      out += kHex[byte >> 4];
      out += kHex[byte & 15];
    }
  }
  return out;
}

// 'sha256-<base64 of the SHA-256 of text>'
std::string hash_source(std::string_view text) {
  std::array<unsigned char, EVP_MAX_MD_SIZE> digest{};
  unsigned int length = 0;
  if (EVP_Digest(text.data(), text.size(), digest.data(), &length, EVP_sha256(), nullptr) != 1) {
    throw std::runtime_error("SHA-256 of an inline script failed (OpenSSL)");
  }
  std::array<unsigned char, 4 * ((EVP_MAX_MD_SIZE + 2) / 3) + 1> base64{};
  const int written = EVP_EncodeBlock(base64.data(), digest.data(), static_cast<int>(length));
  return "'sha256-" + std::string(reinterpret_cast<const char*>(base64.data()), static_cast<std::size_t>(written)) + "'";
}

std::string hash_sources(const std::vector<std::string_view>& texts) {
  std::string out;
  for (const std::string_view text : texts) out += " " + hash_source(text);
  return texts.empty() ? " 'none'" : out;
}

}  // namespace

std::string html_escaped(std::string_view text) {
  std::string out;
  out.reserve(text.size());
  for (const char c : text) {
    switch (c) {
      case '&': out += "&amp;"; break;
      case '<': out += "&lt;"; break;
      case '>': out += "&gt;"; break;
      case '"': out += "&quot;"; break;
      case '\'': out += "&#39;"; break;
      default: out += c;
    }
  }
  return out;
}

std::string relative_href(const std::filesystem::path& relative) {
  if (relative.is_absolute() || relative.has_root_name()) {
    throw std::invalid_argument("'" + relative.string() + "': a link must be relative to the page");
  }
  std::string href = ".";
  for (const auto& segment : relative) {
    const std::string text = segment.string();
    if (text.empty() || text == ".") continue;
    if (text == "..") throw std::invalid_argument("'" + relative.string() + "': a link must stay below the page's folder");
    href += "/" + percent_encoded(text);
  }
  return href;
}

std::vector<std::string_view> inline_elements(std::string_view page, std::string_view tag) {
  const std::string open = "<" + std::string(tag) + ">";
  const std::string close = "</" + std::string(tag) + ">";
  std::vector<std::string_view> found;
  for (std::size_t at = page.find(open); at != std::string_view::npos; at = page.find(open, at)) {
    const std::size_t begin = at + open.size();
    const std::size_t end = page.find(close, begin);
    if (end == std::string_view::npos) break;
    found.push_back(page.substr(begin, end - begin));
    at = end + close.size();
  }
  return found;
}

std::string content_security_policy(const std::vector<std::string_view>& inline_scripts,
                                    const std::vector<std::string_view>& inline_styles,
                                    std::string_view img_sources) {
  return "default-src 'none'; script-src" + hash_sources(inline_scripts) + "; style-src" + hash_sources(inline_styles) +
         "; img-src " + (img_sources.empty() ? std::string("'none'") : std::string(img_sources)) +
         "; base-uri 'none'; form-action 'none'; object-src 'none'";
}

std::string content_security_policy_meta(const std::string& policy) {
  return "<meta http-equiv=\"Content-Security-Policy\" content=\"" + html_escaped(policy) + "\">";
}

}  // namespace a3::rigs
