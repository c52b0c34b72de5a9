// A window of a file compressed with gzip as it is sent: a Body of Beast's (chunked, its length
// unknown ahead) that reads the file a block at a time and deflates each block (zlib), so that a
// file of hundreds of MB is never in memory, whole or compressed: a writer holds two 64 KB buffers
// and zlib's state (about 270 KB at the level used).
#pragma once

#include <cstdint>
#include <memory>
#include <utility>
#include <vector>

#include <boost/asio/buffer.hpp>
#include <boost/beast/core/error.hpp>
#include <boost/beast/core/file.hpp>
#include <boost/beast/http/message.hpp>
#include <boost/optional.hpp>

namespace dem::server {

struct GzipFileBody {
  class writer;

  // The file, open and at its first byte, and how many bytes of it to send (its size when the
  // answer began: a file a running job appends to is sent as it was then).
  class value_type {
   public:
    value_type() = default;
    value_type(boost::beast::file&& file, std::uint64_t length) : file_(std::move(file)), length_(length) {}

   private:
    friend class writer;
    boost::beast::file file_;
    std::uint64_t length_ = 0;
  };

  class writer {
   public:
    using const_buffers_type = boost::asio::const_buffer;

    template <bool isRequest, class Fields>
    writer(boost::beast::http::header<isRequest, Fields>&, value_type& body) : writer(body) {}
    explicit writer(value_type& body);  // out of line, where zlib's stream is a complete type
    ~writer();
    writer(const writer&) = delete;
    writer& operator=(const writer&) = delete;

    void init(boost::beast::error_code& ec);
    boost::optional<std::pair<const_buffers_type, bool>> get(boost::beast::error_code& ec);

   private:
    struct Deflater;  // zlib's stream, kept at one address (its state points back at it)
    value_type& body_;
    std::unique_ptr<Deflater> deflater_;
    std::vector<unsigned char> in_, out_;
    std::uint64_t read_ = 0;
    bool finished_ = false;
  };
};

}  // namespace dem::server
