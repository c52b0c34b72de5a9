#include "server/header_list.hpp"

#include <cctype>

namespace dem::server {
namespace {

// RFC 9110 5.6.2: a token's characters.
bool is_token_char(char c) {
  const auto u = static_cast<unsigned char>(c);
  if (std::isalnum(u)) return true;
  switch (c) {
    case '!':
    case '#':
    case '$':
    case '%':
    case '&':
    case '\'':
    case '*':
    case '+':
    case '-':
    case '.':
    case '^':
    case '_':
    case '`':
    case '|':
    case '~':
      return true;
    default:
      return false;
  }
}

std::string lower(std::string_view text) {
  std::string out(text);
  for (char& c : out) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return out;
}

// Reads the list left to right; each read_* moves `at` past what it read.
class ListReader {
 public:
  explicit ListReader(std::string_view text) : text_(text) {}

  bool done() const { return at_ >= text_.size(); }
  void skip_blanks() {
    while (at_ < text_.size() && (text_[at_] == ' ' || text_[at_] == '\t')) ++at_;
  }
  bool take(char c) {
    skip_blanks();
    if (at_ < text_.size() && text_[at_] == c) {
      ++at_;
      return true;
    }
    return false;
  }
  std::string read_token() {
    skip_blanks();
    const std::size_t start = at_;
    while (at_ < text_.size() && is_token_char(text_[at_])) ++at_;
    return std::string(text_.substr(start, at_ - start));
  }
  // A token or a quoted string (RFC 9110 5.6.4: backslash quotes the next character).
  std::string read_value() {
    skip_blanks();
    if (at_ >= text_.size() || text_[at_] != '"') return read_token();
    std::string out;
    for (++at_; at_ < text_.size() && text_[at_] != '"'; ++at_) {
      if (text_[at_] == '\\' && at_ + 1 < text_.size()) ++at_;
      out.push_back(text_[at_]);
    }
    if (at_ < text_.size()) ++at_;  // the closing quote
    return out;
  }
  // Past the next comma outside a quoted string (what is left of a malformed element).
  void skip_element() {
    bool quoted = false;
    for (; at_ < text_.size(); ++at_) {
      const char c = text_[at_];
      if (quoted && c == '\\') {
        ++at_;
      } else if (c == '"') {
        quoted = !quoted;
      } else if (c == ',' && !quoted) {
        ++at_;
        return;
      }
    }
  }
  bool at_element_end() {
    skip_blanks();
    return done() || text_[at_] == ',';
  }

 private:
  std::string_view text_;
  std::size_t at_ = 0;
};

}  // namespace

std::optional<std::string> HeaderElement::param(std::string_view wanted) const {
  for (const auto& [key, value] : params)
    if (key == wanted) return value;
  return std::nullopt;
}

std::vector<HeaderElement> parse_header_list(std::string_view value) {
  std::vector<HeaderElement> elements;
  ListReader in(value);
  while (!in.done()) {
    if (in.take(',')) continue;  // an empty element
    HeaderElement element;
    element.name = lower(in.read_token());
    bool good = !element.name.empty();
    if (good && in.take('=')) element.value = in.read_value();
    while (good && in.take(';')) {
      const std::string key = lower(in.read_token());
      if (key.empty()) {  // "gzip;" or "gzip; ;q=1": nothing there
        if (in.at_element_end()) break;
        continue;
      }
      std::string param_value;
      if (in.take('=')) param_value = in.read_value();
      element.params.emplace_back(key, std::move(param_value));
    }
    good = good && in.at_element_end();
    in.skip_element();
    if (good) elements.push_back(std::move(element));
  }
  return elements;
}

std::vector<HeaderElement> header_list(const Request& req, http::field field) {
  std::vector<HeaderElement> all;
  for (auto [at, end] = req.equal_range(field); at != end; ++at) {
    std::vector<HeaderElement> line = parse_header_list(std::string_view(at->value().data(), at->value().size()));
    all.insert(all.end(), std::make_move_iterator(line.begin()), std::make_move_iterator(line.end()));
  }
  return all;
}

}  // namespace dem::server
