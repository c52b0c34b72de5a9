// Who may talk to the server, decided from a request's Host and Origin: a server without a token
// answers only this machine's own addresses and pages, and with a token no other site's page may
// use the cookie it gave the viewer. Hosts are parsed, never matched by prefix ("127.attacker.example"
// is not this machine).
#pragma once

#include <optional>
#include <string>
#include <string_view>

namespace dem::server {

// The host of an authority ("127.0.0.1:8080" -> "127.0.0.1", "[::1]:80" -> "::1", "Example.org" ->
// "example.org"); nothing when it is malformed (a bad port, an unclosed bracket).
std::optional<std::string> host_of_authority(std::string_view authority);

// The authority of an Origin ("http://127.0.0.1:8080" -> "127.0.0.1:8080"); nothing for "null" or a
// value without a scheme.
std::optional<std::string> authority_of_origin(std::string_view origin);

// A request target in absolute form ("http://127.0.0.1:8080/api/jobs?x=1", RFC 9112 3.2.2), which a
// server must accept: its authority then names the server in place of the Host header.
struct AbsoluteTarget {
  std::string authority;    // "127.0.0.1:8080"
  std::string origin_form;  // "/api/jobs?x=1" ("/" when the target has no path)
};

// Whether a target is meant as absolute form: not a path from the root, and a scheme before "://".
bool is_absolute_form(std::string_view target);

// The parts of an absolute-form target of scheme http or https (any case); nothing when the scheme
// is another, the authority is empty or malformed, or it carries user information.
std::optional<AbsoluteTarget> split_absolute_form(std::string_view target);

// "localhost" or a literal loopback address (127.0.0.0/8, ::1), nothing else.
bool is_loopback_host(std::string_view host);

// The same scheme-less authority, hosts compared without case ("LOCALHOST:8080" == "localhost:8080").
bool same_authority(std::string_view a, std::string_view b);

// A token the server can hand to a browser in a cookie unquoted: printable ASCII without blanks,
// quotes, commas, semicolons or backslashes (RFC 6265 cookie-octet).
bool is_cookie_safe(std::string_view token);

// What a request's Transfer-Encoding asks of the server (RFC 9112 6.1): the body is framed only
// when chunked is the last coding and appears once; codings before it this server does not decode.
enum class TransferCoding { Chunked, UnknownBeforeChunked, NotChunkedLast };
TransferCoding classify_transfer_coding(std::string_view value);

// The date of now for the Date header (RFC 9110 5.6.7): "Wed, 02 Dec 2026 10:00:00 GMT".
std::string http_date_now();

}  // namespace dem::server
