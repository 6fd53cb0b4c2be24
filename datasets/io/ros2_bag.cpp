// ROS 2 bags in sqlite3 storage: the topics and messages tables read with sqlite3 (read-only,
// immutable: nothing is written beside the data), the messages decoded by ros2_cdr.h.
#include <sqlite3.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <fstream>
#include <map>
#include <set>
#include <sstream>
#include <string>
#include <utility>

#include "core/ascii.h"
#include "core/errors.h"
#include "datasets/io/bag_messages.h"
#include "datasets/io/ros2_cdr.h"

namespace locbench::io {
namespace {

// ---- sqlite3 -------------------------------------------------------------------------------

// "file:" URI of a path: the characters a URI gives a meaning to, percent-encoded.
std::string file_uri(const std::filesystem::path& path) {
  std::string out = "file:";
  for (const char c : std::filesystem::absolute(path).string()) {
    if (c == '%' || c == '?' || c == '#') {
      constexpr const char* kHex = "0123456789ABCDEF";
      out += '%';
      out += kHex[(static_cast<unsigned char>(c) >> 4) & 0xF];
      out += kHex[static_cast<unsigned char>(c) & 0xF];
    } else {
      out += c;
    }
  }
  return out;
}

class Database {
 public:
  Database(const std::filesystem::path& path, bool write) : path_(path) {
    const int flags = write ? (SQLITE_OPEN_READWRITE | SQLITE_OPEN_CREATE) : (SQLITE_OPEN_READONLY | SQLITE_OPEN_URI);
    const std::string name = write ? path.string() : file_uri(path) + "?immutable=1";
    if (sqlite3_open_v2(name.c_str(), &db_, flags, nullptr) != SQLITE_OK) fail("cannot open");
  }
  ~Database() { sqlite3_close(db_); }
  Database(const Database&) = delete;
  Database& operator=(const Database&) = delete;

  sqlite3* get() const { return db_; }
  [[noreturn]] void fail(const std::string& doing) const {
    throw InputError(path_.string(), 0,
                     doing + ": " + printable(db_ ? sqlite3_errmsg(db_) : "out of memory") +
                         " (expected a ROS 2 bag's sqlite3 database with tables topics and messages)");
  }
  void exec(const std::string& sql) const {
    if (sqlite3_exec(db_, sql.c_str(), nullptr, nullptr, nullptr) != SQLITE_OK) fail(sql);
  }

 private:
  std::filesystem::path path_;
  sqlite3* db_ = nullptr;
};

class Statement {
 public:
  Statement(const Database& db, const std::string& sql) : db_(db) {
    if (sqlite3_prepare_v2(db.get(), sql.c_str(), -1, &stmt_, nullptr) != SQLITE_OK) db.fail("reading the bag");
  }
  ~Statement() { sqlite3_finalize(stmt_); }
  Statement(const Statement&) = delete;
  Statement& operator=(const Statement&) = delete;

  // True while there is a row.
  bool step() {
    const int rc = sqlite3_step(stmt_);
    if (rc == SQLITE_ROW) return true;
    if (rc == SQLITE_DONE) return false;
    db_.fail("reading the bag");
  }
  void reset() {
    sqlite3_reset(stmt_);
    sqlite3_clear_bindings(stmt_);
  }
  std::int64_t integer(int column) const { return sqlite3_column_int64(stmt_, column); }
  std::string text(int column) const {
    const auto* p = sqlite3_column_text(stmt_, column);
    return p ? std::string(reinterpret_cast<const char*>(p),
                           static_cast<std::size_t>(sqlite3_column_bytes(stmt_, column)))
             : std::string();
  }
  std::pair<const char*, std::size_t> blob(int column) const {
    const void* p = sqlite3_column_blob(stmt_, column);
    return {static_cast<const char*>(p), static_cast<std::size_t>(sqlite3_column_bytes(stmt_, column))};
  }
  void bind(int i, std::int64_t v) {
    if (sqlite3_bind_int64(stmt_, i, v) != SQLITE_OK) db_.fail("writing the bag");
  }
  void bind(int i, const std::string& v) {
    if (sqlite3_bind_text(stmt_, i, v.data(), static_cast<int>(v.size()), SQLITE_TRANSIENT) != SQLITE_OK) {
      db_.fail("writing the bag");
    }
  }
  void bind_blob(int i, const char* data, std::size_t size) {
    if (sqlite3_bind_blob64(stmt_, i, data, size, SQLITE_TRANSIENT) != SQLITE_OK) db_.fail("writing the bag");
  }

 private:
  const Database& db_;
  sqlite3_stmt* stmt_ = nullptr;
};

// The bag's database files: `path` itself if it is a .db3 file, else the folder's *.db3 files in
// name order. Compressed and MCAP storage are refused by name.
std::vector<std::filesystem::path> database_files(const std::filesystem::path& path) {
  if (!std::filesystem::is_directory(path)) return {path};
  const std::filesystem::path metadata = path / "metadata.yaml";
  if (std::filesystem::is_regular_file(metadata)) {
    std::ifstream in(metadata);
    std::string line;
    for (std::size_t n = 1; std::getline(in, line) && n <= 10000; ++n) {
      const auto at = line.find("compression_format:");
      if (at == std::string::npos) continue;
      std::string value = line.substr(at + 19);
      value.erase(std::remove_if(value.begin(), value.end(), [](char c) { return c == ' ' || c == '"' || c == '\''; }),
                  value.end());
      if (!value.empty()) {
        throw InputError(metadata.string(), n,
                         "compression_format " + value +
                             ": compressed ROS 2 bags are not read (expected an uncompressed sqlite3 bag; "
                             "`ros2 bag convert` writes one)");
      }
    }
  }
  std::vector<std::filesystem::path> files;
  bool mcap = false;
  for (const auto& e : std::filesystem::directory_iterator(path)) {
    const std::string ext = ascii_lowercase(e.path().extension().string());
    if (ext == ".db3") files.push_back(e.path());
    if (ext == ".mcap") mcap = true;
  }
  if (files.empty()) {
    throw InputError(path.string(), 0,
                     mcap ? "a ROS 2 bag in MCAP storage: not read yet (expected sqlite3 storage, *.db3)"
                          : "no .db3 file (expected a ROS 2 bag folder: metadata.yaml and sqlite3 *.db3 files)");
  }
  std::sort(files.begin(), files.end());
  return files;
}

struct TopicRow {
  std::string name, type, format;
};

std::map<std::int64_t, TopicRow> topic_rows(const Database& db) {
  std::map<std::int64_t, TopicRow> out;
  Statement s(db, "SELECT id, name, type, serialization_format FROM topics");
  while (s.step())
    out[s.integer(0)] = {printable(s.text(1)), printable(ros1_type_name(s.text(2))), printable(s.text(3))};
  return out;
}

void add_topic_counts(const Database& db, const std::map<std::int64_t, TopicRow>& rows,
                      std::map<std::string, BagTopic>& topics) {
  for (const auto& [id, row] : rows) {
    BagTopic& t = topics[row.name];
    t.name = row.name;
    if (t.type.empty()) t.type = row.type;
  }
  Statement s(db, "SELECT topic_id, COUNT(*), MIN(timestamp), MAX(timestamp) FROM messages GROUP BY topic_id");
  while (s.step()) {
    const auto row = rows.find(s.integer(0));
    if (row == rows.end()) continue;
    BagTopic& t = topics[row->second.name];
    const double first = nanoseconds_to_seconds(s.integer(2)), last = nanoseconds_to_seconds(s.integer(3));
    t.first_record = t.count == 0 ? first : std::min(t.first_record, first);
    t.last_record = t.count == 0 ? last : std::max(t.last_record, last);
    t.count += static_cast<std::size_t>(s.integer(1));
  }
}

void read_messages(const Database& db, const std::map<std::int64_t, TopicRow>& rows, Ros2MessageDecoder& decoder) {
  std::string ids;
  for (const auto& [id, row] : rows) {
    if (!decoder.wants(row.name)) continue;
    decoder.check_format(row.name, row.format);
    ids += (ids.empty() ? "" : ",") + std::to_string(id);
  }
  if (ids.empty()) return;
  Statement s(db,
              "SELECT topic_id, timestamp, data FROM messages WHERE topic_id IN (" + ids + ") ORDER BY timestamp, id");
  while (s.step()) {
    const TopicRow& row = rows.at(s.integer(0));
    const auto [data, size] = s.blob(2);
    decoder.add(row.name, row.type, s.integer(1), data, size);
  }
}

// ---- writing --------------------------------------------------------------------------------

}  // namespace

BagMessages read_ros2_bag(const std::filesystem::path& path, const BagRoleChooser& choose) {
  const std::vector<std::filesystem::path> files = database_files(path);
  std::vector<std::unique_ptr<Database>> dbs;
  std::vector<std::map<std::int64_t, TopicRow>> rows;
  std::map<std::string, BagTopic> topics;
  for (const auto& f : files) {
    dbs.push_back(std::make_unique<Database>(f, false));
    rows.push_back(topic_rows(*dbs.back()));
    add_topic_counts(*dbs.back(), rows.back(), topics);
  }
  BagMessages out;
  for (auto& [name, t] : topics) out.topics.push_back(t);
  out.roles = choose(out.topics);
  Ros2MessageDecoder decoder(out, files.front());
  for (std::size_t i = 0; i < files.size(); ++i) {
    decoder.set_file(files[i]);
    read_messages(*dbs[i], rows[i], decoder);
  }
  return out;
}

void write_ros2_bag(const BagContents& c, const std::filesystem::path& folder, const std::string& name) {
  std::filesystem::create_directories(folder);
  const std::string file_name = name + "_0.db3";
  const std::filesystem::path file = folder / file_name;
  std::filesystem::remove(file);
  const Ros2Serialized serialized = serialize_ros2(c);
  const std::vector<Ros2Topic>& topics = serialized.topics;
  const std::vector<Ros2Message>& messages = serialized.messages;
  {
    Database db(file, true);
    db.exec(
        "CREATE TABLE schema(schema_version INTEGER PRIMARY KEY,ros_distro TEXT NOT NULL);"
        "INSERT INTO schema VALUES(3,'humble');"
        "CREATE TABLE topics(id INTEGER PRIMARY KEY,name TEXT NOT NULL,type TEXT NOT NULL,"
        "serialization_format TEXT NOT NULL,offered_qos_profiles TEXT NOT NULL);"
        "CREATE TABLE messages(id INTEGER PRIMARY KEY,topic_id INTEGER NOT NULL,timestamp INTEGER NOT NULL,"
        "data BLOB NOT NULL);"
        "CREATE INDEX timestamp_idx ON messages (timestamp ASC);"
        "BEGIN");
    Statement topic(db, "INSERT INTO topics VALUES(?,?,?,'cdr','')");
    for (std::size_t i = 0; i < topics.size(); ++i) {
      if (topics[i].count == 0) continue;  // as a recorder: only topics that had messages
      topic.bind(1, static_cast<std::int64_t>(i + 1));
      topic.bind(2, topics[i].name);
      topic.bind(3, topics[i].type);
      topic.step();
      topic.reset();
    }
    Statement message(db, "INSERT INTO messages(topic_id,timestamp,data) VALUES(?,?,?)");
    for (const Ros2Message& m : messages) {
      message.bind(1, static_cast<std::int64_t>(m.topic + 1));
      message.bind(2, m.time);
      message.bind_blob(3, m.data.data(), m.data.size());
      message.step();
      message.reset();
    }
    db.exec("COMMIT");
  }
  const std::int64_t t0 = messages.empty() ? 0 : messages.front().time;
  const std::int64_t t1 = messages.empty() ? 0 : messages.back().time;
  std::ostringstream yaml;
  yaml << "rosbag2_bagfile_information:\n  version: 5\n  storage_identifier: sqlite3\n"
       << "  duration:\n    nanoseconds: " << t1 - t0 << "\n  starting_time:\n    nanoseconds_since_epoch: " << t0
       << "\n  message_count: " << messages.size() << "\n  topics_with_message_count:\n";
  for (const Ros2Topic& t : topics) {
    if (t.count == 0) continue;
    yaml << "    - topic_metadata:\n        name: " << t.name << "\n        type: " << t.type
         << "\n        serialization_format: cdr\n        offered_qos_profiles: \"\"\n      message_count: " << t.count
         << "\n";
  }
  yaml << "  compression_format: \"\"\n  compression_mode: \"\"\n  relative_file_paths:\n    - " << file_name
       << "\n  files:\n    - path: " << file_name << "\n      starting_time:\n        nanoseconds_since_epoch: " << t0
       << "\n      duration:\n        nanoseconds: " << t1 - t0 << "\n      message_count: " << messages.size() << "\n";
  std::ofstream out(folder / "metadata.yaml");
  out << yaml.str();
  if (!out) throw InputError((folder / "metadata.yaml").string(), 0, "cannot write");
}

}  // namespace locbench::io
