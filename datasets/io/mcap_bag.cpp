// ROS 2 bags in MCAP storage: one .mcap file, or a ROS 2 bag folder whose files are .mcap. Read
// and written with the MCAP project's own C++ library (third_party/mcap, header-only, MIT; chunks
// compressed with zstd or lz4 through Debian's libzstd and liblz4), the messages decoded and
// serialized as CDR by ros2_cdr.h, as in sqlite3 storage.
#define MCAP_IMPLEMENTATION
#include <mcap/reader.hpp>
#include <mcap/writer.hpp>

#include <algorithm>
#include <cstring>
#include <fstream>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "core/ascii.h"
#include "core/errors.h"
#include "datasets/io/bag_messages.h"
#include "datasets/io/ros2_cdr.h"

namespace locbench::io {
namespace {

// The MCAP files of a bag: `path` itself, or the folder's *.mcap files in name order.
std::vector<std::filesystem::path> mcap_files(const std::filesystem::path& path) {
  if (!std::filesystem::is_directory(path)) return {path};
  std::vector<std::filesystem::path> files;
  for (const auto& e : std::filesystem::directory_iterator(path)) {
    const std::string name = ascii_lowercase(e.path().filename().string());
    if (name.ends_with(".mcap")) files.push_back(e.path());
    if (name.ends_with(".mcap.zstd") || name.ends_with(".mcap.lz4")) {
      throw InputError(e.path().string(), 0,
                       "a ROS 2 bag compressed file by file: not read (expected .mcap files, whose chunks may be "
                       "compressed; `ros2 bag convert` or `mcap compress` writes them)");
    }
  }
  if (files.empty()) throw InputError(path.string(), 0, "no .mcap file (expected a ROS 2 bag folder in MCAP storage)");
  std::sort(files.begin(), files.end());
  return files;
}

// An MCAP file is checked before the library reads it, in one pass over its top-level records
// (opcode and length; a chunk's size fields). The library allocates what a chunk says its records
// take uncompressed before it decompresses them, so a chunk that lies (a damaged or hostile file)
// could ask for exabytes: a claim over this is refused, as is an uncompressed chunk whose records
// disagree with its claim (which the library asserts). Writers make chunks of about 1–4 MB (the
// library's default 768 kB). Then the file must end with the closing magic.
constexpr std::uint64_t kMaxChunkBytes = std::uint64_t{256} << 20;
constexpr std::uint8_t kOpChunk = 0x06, kOpFooter = 0x02;

void check_file(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  in.seekg(0, std::ios::end);
  const auto size = static_cast<std::uint64_t>(std::max<std::streamoff>(in.tellg(), 0));
  const auto fail = [&](std::uint64_t at, const std::string& what) {
    throw InputError(path.string(), 0, "byte " + std::to_string(at) + ": " + what + " (a damaged file?)");
  };
  std::uint64_t at = sizeof(mcap::Magic);
  while (at + 9 <= size) {
    // opcode, length; a chunk's message start and end times, uncompressed size and CRC,
    // compression (a length-prefixed string) and, when that is empty, the length of its records.
    unsigned char head[9 + 24 + 4 + 4 + 8] = {};
    in.clear();
    in.seekg(static_cast<std::streamoff>(at));
    const std::uint64_t got = std::min<std::uint64_t>(sizeof(head), size - at);
    if (!in.read(reinterpret_cast<char*>(head), static_cast<std::streamsize>(got))) break;  // the library says why
    const auto u64 = [&](std::size_t k) {
      std::uint64_t v = 0;
      std::memcpy(&v, head + k, 8);  // little-endian, as MCAP and x86 are
      return v;
    };
    const std::uint64_t length = u64(1);
    if (head[0] == kOpFooter) break;
    if (length > size - at - 9) break;  // runs past the end: the library reports it
    if (head[0] == kOpChunk && length >= 24 + 4 + 4) {
      const std::uint64_t uncompressed = u64(9 + 16);
      if (uncompressed > kMaxChunkBytes) {
        fail(at, "a chunk claims " + std::to_string(uncompressed) + " bytes uncompressed (expected at most " +
                     std::to_string(kMaxChunkBytes) + ")");
      }
      std::uint32_t name_length = 0;
      std::memcpy(&name_length, head + 9 + 28, 4);
      if (name_length == 0 && 9 + 32 + 8 <= got) {  // no compression: the records are the claim
        const std::uint64_t records = u64(9 + 32);
        if (records != uncompressed) {
          fail(at,
               "an uncompressed chunk of " + std::to_string(records) + " bytes claims " + std::to_string(uncompressed));
        }
      }
    }
    at += 9 + length;
  }
  // A file cut short (a recorder killed) lacks the closing magic; the library would read the
  // messages before the cut and say nothing.
  char tail[sizeof(mcap::Magic)] = {};
  in.clear();
  in.seekg(-static_cast<std::streamoff>(sizeof(tail)), std::ios::end);
  if (!in.read(tail, sizeof(tail)) || std::memcmp(tail, mcap::Magic, sizeof(tail)) != 0) {
    throw InputError(path.string(), 0,
                     "does not end with MCAP's closing magic bytes: cut short (a recording that did not finish?) "
                     "or followed by other data (expected a complete MCAP file)");
  }
}

// Opens one MCAP file for reading; every problem the library reports becomes an InputError
// naming the file.
class McapFile {
 public:
  explicit McapFile(std::filesystem::path path) : path_(std::move(path)) {
    check(reader_.open(path_.string()), "opening");
    check_file(path_);
    check(reader_.readSummary(mcap::ReadSummaryMethod::AllowFallbackScan, [&](const mcap::Status& s) { note(s); }),
          "reading its summary");
    rethrow("reading its summary");
  }
  ~McapFile() { reader_.close(); }
  McapFile(const McapFile&) = delete;
  McapFile& operator=(const McapFile&) = delete;

  // Calls f(topic, type, log time [ns], data, size) for each message of the topics `wanted`
  // accepts.
  template <class Wanted, class F>
  void for_each_message(Wanted&& wanted, F&& f) {
    mcap::ReadMessageOptions options;
    // In log-time order where the summary indexes the chunks; else (no summary: a file cut short,
    // or written without one) in file order, which the stamps' order check then judges.
    const auto& chunks = reader_.chunkIndexes();
    const bool indexed = !chunks.empty() && std::all_of(chunks.begin(), chunks.end(), [](const mcap::ChunkIndex& c) {
      return !c.messageIndexOffsets.empty();
    });
    options.readOrder =
        indexed ? mcap::ReadMessageOptions::ReadOrder::LogTimeOrder : mcap::ReadMessageOptions::ReadOrder::FileOrder;
    options.topicFilter = [&](std::string_view topic) { return wanted(std::string(topic)); };
    const auto on_problem = [&](const mcap::Status& s) { note(s); };
    for (const mcap::MessageView& m : reader_.readMessages(on_problem, options)) {
      if (problem_) break;
      const std::string type = m.schema ? ros1_type_name(printable(m.schema->name)) : std::string("(no schema)");
      f(printable(m.channel->topic), type, static_cast<std::int64_t>(m.message.logTime),
        reinterpret_cast<const char*>(m.message.data), static_cast<std::size_t>(m.message.dataSize));
    }
    rethrow("reading its messages");
  }

  // Per topic: the messages' count and first and last log time [ns], from the chunks' message
  // indexes (small records; no chunk is decompressed). False when the file has no such index or
  // the index does not account for every message the statistics count (then the caller counts the
  // messages themselves).
  struct Counted {
    std::size_t count = 0;
    std::int64_t first = 0, last = 0;
  };
  bool count_from_index(std::map<std::string, Counted>& out) {
    const auto& stats = reader_.statistics();
    const auto& chunks = reader_.chunkIndexes();
    if (!stats || chunks.empty() || reader_.dataSource() == nullptr) return false;
    for (const mcap::ChunkIndex& chunk : chunks) {
      if (chunk.messageIndexOffsets.empty()) return false;  // a summary made by scanning the chunks
    }
    const auto channels = reader_.channels();
    std::uint64_t indexed = 0;
    for (const mcap::ChunkIndex& chunk : chunks) {
      for (const auto& [id, offset] : chunk.messageIndexOffsets) {
        const auto channel = channels.find(id);
        mcap::Record record;
        mcap::MessageIndex index;
        if (channel == channels.end() || !mcap::McapReader::ReadRecord(*reader_.dataSource(), offset, &record).ok() ||
            record.opcode != mcap::OpCode::MessageIndex || !mcap::McapReader::ParseMessageIndex(record, &index).ok()) {
          return false;
        }
        Counted& c = out[printable(channel->second->topic)];
        for (const auto& [time, at] : index.records) {
          const auto t = static_cast<std::int64_t>(time);
          c.first = c.count == 0 ? t : std::min(c.first, t);
          c.last = c.count == 0 ? t : std::max(c.last, t);
          ++c.count;
          ++indexed;
        }
      }
    }
    return indexed == stats->messageCount;
  }

  // Each channel: topic, type (the schema's name in the ROS 1 form) and message encoding.
  struct ChannelInfo {
    std::string topic, type, encoding;
  };
  std::vector<ChannelInfo> channels() const {
    std::vector<ChannelInfo> out;
    const auto schemas = reader_.schemas();  // (the library returns the maps by value)
    for (const auto& [id, c] : reader_.channels()) {
      const auto schema = schemas.find(c->schemaId);
      out.push_back({printable(c->topic),
                     schema != schemas.end() ? ros1_type_name(printable(schema->second->name)) : "",
                     printable(c->messageEncoding)});
    }
    std::sort(out.begin(), out.end(), [](const ChannelInfo& a, const ChannelInfo& b) { return a.topic < b.topic; });
    return out;
  }

 private:
  void note(const mcap::Status& s) {
    if (!s.ok() && !problem_) problem_ = s.message;
  }
  void check(const mcap::Status& s, const char* doing) {
    note(s);
    rethrow(doing);
  }
  void rethrow(const char* doing) {
    if (!problem_) return;
    throw InputError(path_.string(), 0,
                     std::string(doing) + ": " + printable(*problem_) + " (expected an MCAP file of ROS 2 messages)");
  }

  std::filesystem::path path_;
  mcap::McapReader reader_;
  std::optional<std::string> problem_;
};

mcap::Compression compression_of(const std::string& name) {
  if (name == "zstd") return mcap::Compression::Zstd;
  if (name == "lz4") return mcap::Compression::Lz4;
  if (name == "none") return mcap::Compression::None;
  throw UsageError("MCAP compression must be zstd, lz4 or none, not " + name);
}

}  // namespace

BagMessages read_mcap_bag(const std::filesystem::path& path, const BagRoleChooser& choose) {
  const std::vector<std::filesystem::path> files = mcap_files(path);
  std::vector<std::unique_ptr<McapFile>> opened;
  std::map<std::string, BagTopic> topics;
  std::map<std::string, std::string> formats;
  // Every topic with its count and first and last record time: from the message indexes, or where
  // a file has none, by one pass over its messages.
  for (const auto& f : files) {
    opened.push_back(std::make_unique<McapFile>(f));
    for (const auto& c : opened.back()->channels()) {
      BagTopic& t = topics[c.topic];
      t.name = c.topic;
      if (t.type.empty()) t.type = c.type;
      formats.emplace(c.topic, c.encoding);
    }
    std::map<std::string, McapFile::Counted> counted;
    if (!opened.back()->count_from_index(counted)) {
      counted.clear();
      opened.back()->for_each_message(
          [](const std::string&) { return true; },
          [&](const std::string& topic, const std::string&, std::int64_t ns, const char*, std::size_t) {
            McapFile::Counted& c = counted[topic];
            c.first = c.count == 0 ? ns : std::min(c.first, ns);
            c.last = c.count == 0 ? ns : std::max(c.last, ns);
            ++c.count;
          });
    }
    for (const auto& [topic, c] : counted) {
      if (c.count == 0) continue;
      BagTopic& t = topics[topic];
      t.name = topic;
      const double first = nanoseconds_to_seconds(c.first), last = nanoseconds_to_seconds(c.last);
      t.first_record = t.count == 0 ? first : std::min(t.first_record, first);
      t.last_record = t.count == 0 ? last : std::max(t.last_record, last);
      t.count += c.count;
    }
  }
  BagMessages out;
  for (auto& [name, t] : topics) out.topics.push_back(t);
  out.roles = choose(out.topics);
  Ros2MessageDecoder decoder(out, files.front());
  for (const auto& [topic, format] : formats) decoder.check_format(topic, format);
  for (std::size_t i = 0; i < files.size(); ++i) {
    decoder.set_file(files[i]);
    opened[i]->for_each_message([&](const std::string& topic) { return decoder.wants(topic); },
                                [&](const std::string& topic, const std::string& type, std::int64_t ns,
                                    const char* data, std::size_t size) { decoder.add(topic, type, ns, data, size); });
  }
  return out;
}

void write_mcap_bag(const BagContents& contents, const std::filesystem::path& path, const std::string& compression) {
  mcap::McapWriterOptions options("ros2");
  options.compression = compression_of(compression);
  mcap::McapWriter writer;
  const mcap::Status opened = writer.open(path.string(), options);
  if (!opened.ok()) throw InputError(path.string(), 0, "cannot write: " + printable(opened.message));
  const Ros2Serialized serialized = serialize_ros2(contents);
  std::vector<mcap::ChannelId> channel(serialized.topics.size(), 0);
  for (std::size_t i = 0; i < serialized.topics.size(); ++i) {
    if (serialized.topics[i].count == 0) continue;  // as a recorder: only topics that had messages
    // The message definition is not embedded (readers of the type, ROS 2 and locbench, know it): a
    // comment stands in for it (an empty schema made the library fwrite from a null pointer).
    mcap::Schema schema(serialized.topics[i].type, "ros2msg",
                        "# " + serialized.topics[i].type + ": the definition is not embedded (written by locbench)\n");
    writer.addSchema(schema);
    mcap::Channel c(serialized.topics[i].name, "cdr", schema.id);
    writer.addChannel(c);
    channel[i] = c.id;
  }
  std::vector<std::uint32_t> sequence(serialized.topics.size(), 0);
  for (const Ros2Message& m : serialized.messages) {
    mcap::Message message;
    message.channelId = channel[m.topic];
    message.sequence = ++sequence[m.topic];
    message.logTime = message.publishTime = static_cast<mcap::Timestamp>(std::max<std::int64_t>(m.time, 0));
    message.data = reinterpret_cast<const std::byte*>(m.data.data());
    message.dataSize = m.data.size();
    const mcap::Status written = writer.write(message);
    if (!written.ok()) throw InputError(path.string(), 0, "cannot write: " + printable(written.message));
  }
  writer.close();
}

}  // namespace locbench::io
