// The structure of a ROS 1 bag (format 2.0), checked before rosbag_storage reads it: rosbag_storage
// trusts the lengths and offsets it finds (a message offset in a corrupted index made it read out of
// bounds and crash), so every record, chunk and index entry is checked here first.
// http://wiki.ros.org/Bags/Format/2.0
#include <bzlib.h>
#include <roslz4/lz4s.h>

#include <cstdint>
#include <cstring>
#include <fstream>
#include <map>
#include <set>
#include <string>
#include <vector>

#include "core/errors.h"
#include "datasets/io/bag_messages.h"

namespace locbench::io {
namespace {

constexpr std::uint8_t kOpMessageData = 0x02, kOpBagHeader = 0x03, kOpIndexData = 0x04, kOpChunk = 0x05,
                       kOpChunkInfo = 0x06, kOpConnection = 0x07;
// rosbag writes chunks of 768 kB; a chunk that claims more than this is refused rather than allocated.
constexpr std::uint64_t kMaxChunkBytes = std::uint64_t{1} << 30;

class Check {
 public:
  explicit Check(const std::filesystem::path& path) : path_(path), in_(path, std::ios::binary) {
    if (!in_) fail(0, "cannot open");
    in_.seekg(0, std::ios::end);
    size_ = static_cast<std::uint64_t>(in_.tellg());
    in_.seekg(0);
  }

  void run() {
    char version[13];
    if (!in_.read(version, 13) || std::memcmp(version, "#ROSBAG V2.0\n", 13) != 0) {
      fail(0, "no \"#ROSBAG V2.0\" line at the start (expected a ROS 1 bag, format 2.0)");
    }
    std::uint64_t pos = 13, index_pos = 0;
    std::set<std::uint64_t> chunk_starts, record_starts;
    std::vector<std::uint64_t> chunk_info_positions;
    std::set<std::uint32_t> chunk_offsets;  // message records of the last chunk
    bool header_seen = false;
    while (pos < size_) {
      const std::uint64_t start = pos;
      record_starts.insert(start);
      Fields f = read_header(pos);
      const std::uint32_t data_len = u32_at(pos);
      pos += 4;
      if (data_len > size_ - pos)
        fail(start, "record data of " + std::to_string(data_len) + " bytes runs past the end");
      const std::uint8_t op = f.op(*this, start);
      if (op == kOpBagHeader) {
        header_seen = true;
        index_pos = f.u64(*this, start, "index_pos");
      } else if (op == kOpChunk) {
        chunk_starts.insert(start);
        chunk_offsets = check_chunk(f, start, pos, data_len);
      } else if (op == kOpIndexData) {
        const std::uint32_t count = f.u32(*this, start, "count");
        if (static_cast<std::uint64_t>(count) * 12 > data_len) fail(start, "index data: count larger than its data");
        std::vector<char> data = bytes(pos, data_len);
        for (std::uint32_t i = 0; i < count; ++i) {
          std::uint32_t offset;
          std::memcpy(&offset, data.data() + 12 * i + 8, 4);
          if (chunk_offsets.count(offset) == 0) {
            fail(start, "index entry " + std::to_string(i + 1) + " points at offset " + std::to_string(offset) +
                            ", not at a message of the chunk before it");
          }
        }
      } else if (op == kOpChunkInfo) {
        chunk_info_positions.push_back(f.u64(*this, start, "chunk_pos"));
      } else if (op != kOpConnection) {
        fail(start, "unknown record op " + std::to_string(op));
      }
      pos += data_len;
    }
    if (!header_seen) fail(13, "no bag header record");
    if (index_pos == 0) fail(13, "the bag was not closed (index_pos 0): reindex it with `rosbag reindex`");
    if (record_starts.count(index_pos) == 0) {
      fail(13, "index_pos " + std::to_string(index_pos) + " is not the start of a record (a truncated file?)");
    }
    for (const std::uint64_t p : chunk_info_positions) {
      if (chunk_starts.count(p) == 0) fail(index_pos, "chunk info points at " + std::to_string(p) + ", not at a chunk");
    }
  }

 private:
  struct Fields {
    std::map<std::string, std::string> values;
    std::uint8_t op(Check& c, std::uint64_t at) const {
      const auto it = values.find("op");
      if (it == values.end() || it->second.size() != 1) c.fail(at, "record without a one-byte op field");
      return static_cast<std::uint8_t>(it->second[0]);
    }
    std::uint64_t u64(Check& c, std::uint64_t at, const char* name) const {
      const auto it = values.find(name);
      if (it == values.end() || it->second.size() != 8) c.fail(at, std::string("record without an 8-byte ") + name);
      std::uint64_t v;
      std::memcpy(&v, it->second.data(), 8);
      return v;
    }
    std::uint32_t u32(Check& c, std::uint64_t at, const char* name) const {
      const auto it = values.find(name);
      if (it == values.end() || it->second.size() != 4) c.fail(at, std::string("record without a 4-byte ") + name);
      std::uint32_t v;
      std::memcpy(&v, it->second.data(), 4);
      return v;
    }
    std::string text(const char* name) const {
      const auto it = values.find(name);
      return it == values.end() ? std::string() : it->second;
    }
  };

  [[noreturn]] void fail(std::uint64_t at, const std::string& what) {
    throw InputError(path_.string(), 0,
                     "not a readable ROS 1 bag: byte " + std::to_string(at) + ": " + what +
                         (what.find("past the end") != std::string::npos ? " (a truncated file?)" : ""));
  }

  std::vector<char> bytes(std::uint64_t pos, std::uint64_t n) {
    if (n > size_ || pos > size_ - n) fail(pos, std::to_string(n) + " bytes run past the end");
    std::vector<char> out(n);
    in_.seekg(static_cast<std::streamoff>(pos));
    if (!in_.read(out.data(), static_cast<std::streamsize>(n))) fail(pos, "cannot read");
    return out;
  }
  std::uint32_t u32_at(std::uint64_t pos) {
    const std::vector<char> b = bytes(pos, 4);
    std::uint32_t v;
    std::memcpy(&v, b.data(), 4);
    return v;
  }

  // Fields of the record header at pos (advanced past it).
  Fields read_header(std::uint64_t& pos) {
    const std::uint64_t start = pos;
    const std::uint32_t len = u32_at(pos);
    pos += 4;
    if (len > size_ - pos) fail(start, "record header of " + std::to_string(len) + " bytes runs past the end");
    const std::vector<char> h = bytes(pos, len);
    pos += len;
    return parse_fields(h.data(), len, start);
  }

  Fields parse_fields(const char* p, std::uint64_t len, std::uint64_t at) {
    Fields f;
    std::uint64_t i = 0;
    while (i < len) {
      if (len - i < 4) fail(at, "record header field length runs past the header");
      std::uint32_t n;
      std::memcpy(&n, p + i, 4);
      i += 4;
      if (n > len - i) fail(at, "record header field of " + std::to_string(n) + " bytes runs past the header");
      const std::string field(p + i, n);
      const auto eq = field.find('=');
      if (eq == std::string::npos) fail(at, "record header field without '='");
      f.values[field.substr(0, eq)] = field.substr(eq + 1);
      i += n;
    }
    return f;
  }

  // Decompresses a chunk and walks its records; returns the offsets of its message records.
  std::set<std::uint32_t> check_chunk(const Fields& f, std::uint64_t start, std::uint64_t pos, std::uint32_t data_len) {
    const std::string compression = f.text("compression");
    const std::uint32_t size = f.u32(*this, start, "size");
    if (size > kMaxChunkBytes) fail(start, "chunk claims " + std::to_string(size) + " bytes uncompressed");
    std::vector<char> data = bytes(pos, data_len);
    std::vector<char> plain;
    if (compression == "none") {
      if (size != data_len)
        fail(start, "uncompressed chunk of " + std::to_string(data_len) + " bytes claims " + std::to_string(size));
      plain = std::move(data);
    } else if (compression == "bz2" || compression == "lz4") {
      plain.resize(size);
      unsigned int out = size;
      const int rc = compression == "bz2" ? BZ2_bzBuffToBuffDecompress(plain.data(), &out, data.data(), data_len, 0, 0)
                                          : roslz4_buffToBuffDecompress(data.data(), data_len, plain.data(), &out);
      const bool ok = compression == "bz2" ? rc == BZ_OK : rc == ROSLZ4_OK;
      if (!ok || out != size) {
        fail(start, compression + " chunk does not decompress to the " + std::to_string(size) + " bytes it claims");
      }
    } else {
      fail(start, "chunk compression \"" + printable(compression) + "\" (expected none, bz2 or lz4)");
    }
    std::set<std::uint32_t> offsets;
    std::uint64_t i = 0;
    while (i < plain.size()) {
      const std::uint64_t record = i;
      const auto need = [&](std::uint64_t n, const char* what) {
        if (n > plain.size() - i)
          fail(start, std::string("chunk record at ") + std::to_string(record) + ": " + what + " runs past the chunk");
      };
      need(4, "header length");
      std::uint32_t hlen;
      std::memcpy(&hlen, plain.data() + i, 4);
      i += 4;
      need(hlen, "header");
      const Fields rf = parse_fields(plain.data() + i, hlen, start);
      i += hlen;
      need(4, "data length");
      std::uint32_t dlen;
      std::memcpy(&dlen, plain.data() + i, 4);
      i += 4;
      need(dlen, "data");
      i += dlen;
      const std::uint8_t op = rf.op(*this, start);
      if (op == kOpMessageData) {
        offsets.insert(static_cast<std::uint32_t>(record));
      } else if (op != kOpConnection) {
        fail(start, "chunk record op " + std::to_string(op) + " (expected messages and connections)");
      }
    }
    return offsets;
  }

  std::filesystem::path path_;
  std::ifstream in_;
  std::uint64_t size_ = 0;
};

}  // namespace

void check_ros1_bag_structure(const std::filesystem::path& path) { Check(path).run(); }

}  // namespace locbench::io
