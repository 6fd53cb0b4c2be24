// ROS 2 bags in sqlite3 storage: the topics and messages tables read with sqlite3 (read-only,
// immutable: nothing is written beside the data), messages decoded from CDR with eProsima Fast CDR.
#include <fastcdr/Cdr.h>
#include <fastcdr/FastBuffer.h>
#include <fastcdr/exceptions/BadParamException.h>
#include <fastcdr/exceptions/Exception.h>
#include <fastcdr/exceptions/NotEnoughMemoryException.h>
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

#include "core/errors.h"
#include "datasets/io/bag_messages.h"

namespace locbench::io {
namespace {

using eprosima::fastcdr::Cdr;
using eprosima::fastcdr::FastBuffer;

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

// ---- CDR ------------------------------------------------------------------------------------

// One serialized message: the encapsulation header first, then the fields in declaration order.
class CdrReader {
 public:
  CdrReader(const char* data, std::size_t size)
      : buffer_(const_cast<char*>(data), size), cdr_(buffer_, Cdr::DEFAULT_ENDIAN, Cdr::DDS_CDR) {
    cdr_.read_encapsulation();
  }
  double f64() {
    double v = 0.0;
    cdr_.deserialize(v);
    return v;
  }
  float f32() {
    float v = 0.0F;
    cdr_.deserialize(v);
    return v;
  }
  std::uint32_t u32() {
    std::uint32_t v = 0;
    cdr_.deserialize(v);
    return v;
  }
  std::string str() {
    std::string s;
    cdr_.deserialize(s);
    return s;
  }
  std::vector<float> floats() {
    std::vector<float> v;
    cdr_.deserialize(v);  // checks the length against the bytes left before allocating
    return v;
  }
  void skip_f64(std::size_t n) {
    for (std::size_t i = 0; i < n; ++i) f64();
  }
  std::size_t bytes_left() const { return buffer_.getBufferSize() - cdr_.getSerializedDataLength(); }
  // A message of another type may decode without running out of bytes: more than the last
  // field's alignment left over says it was not this type.
  void expect_end() const {
    if (bytes_left() > 7) {
      throw eprosima::fastcdr::exception::BadParamException("bytes left over after the last field");
    }
  }

  // std_msgs/Header: builtin_interfaces/Time stamp (int32 sec, uint32 nanosec), string frame_id.
  double header(std::string& frame_id) {
    std::int32_t sec = 0;
    cdr_.deserialize(sec);
    const double t = stamp_seconds(sec, u32());
    frame_id = str();
    return t;
  }
  // geometry_msgs/Pose (Point, Quaternion) or Transform (Vector3, Quaternion), in the plane.
  PlanarPose pose() {
    std::array<double, 7> v{};
    for (double& x : v) x = f64();
    return planar_pose(v[0], v[1], v[3], v[4], v[5], v[6]);
  }

 private:
  FastBuffer buffer_;
  Cdr cdr_;
};

class CdrWriter {
 public:
  CdrWriter() : cdr_(buffer_, Cdr::LITTLE_ENDIANNESS, Cdr::DDS_CDR) { cdr_.serialize_encapsulation(); }
  template <class T>
  CdrWriter& operator<<(const T& v) {
    cdr_ << v;
    return *this;
  }
  void header(double t, const std::string& frame_id) {
    double sec = std::floor(t);
    auto nsec = static_cast<std::int64_t>(std::llround((t - sec) * 1e9));
    if (nsec >= 1000000000) {
      sec += 1.0;
      nsec -= 1000000000;
    }
    cdr_ << static_cast<std::int32_t>(sec) << static_cast<std::uint32_t>(nsec) << frame_id;
  }
  void pose(const PlanarPose& p) {
    cdr_ << p.x << p.y << 0.0 << 0.0 << 0.0 << std::sin(p.yaw / 2.0) << std::cos(p.yaw / 2.0);
  }
  void zeros(std::size_t n) {
    for (std::size_t i = 0; i < n; ++i) cdr_ << 0.0;
  }
  std::pair<const char*, std::size_t> bytes() const { return {buffer_.getBuffer(), cdr_.getSerializedDataLength()}; }

 private:
  FastBuffer buffer_;
  Cdr cdr_;
};

// ---- decoding -------------------------------------------------------------------------------

BagPoseMessage decode_pose(CdrReader& r, const std::string& type) {
  BagPoseMessage m;
  m.time.stamp = r.header(m.frame_id);
  if (type == kOdometryType) {
    m.child_frame_id = r.str();
    m.pose = r.pose();
    r.skip_f64(36);  // covariance
    m.tv = r.f64();
    r.skip_f64(4);
    m.rv = r.f64();
    r.skip_f64(36);
  } else if (type == kPoseStampedType) {
    m.pose = r.pose();
  } else if (type == kPoseWithCovarianceStampedType) {
    m.pose = r.pose();
    r.skip_f64(36);
  } else {  // kTransformStampedType
    m.child_frame_id = r.str();
    m.pose = r.pose();
  }
  return m;
}

BagScanMessage decode_scan(CdrReader& r) {
  BagScanMessage m;
  m.time.stamp = r.header(m.frame_id);
  m.angle_min = r.f32();
  r.f32();  // angle_max
  m.angle_increment = r.f32();
  r.f32();  // time_increment
  r.f32();  // scan_time
  m.range_min = r.f32();
  m.range_max = r.f32();
  m.ranges = r.floats();
  r.floats();  // intensities
  return m;
}

void decode_transforms(CdrReader& r, std::set<std::pair<std::string, std::string>>& seen,
                       std::vector<BagTransform>& out) {
  const std::uint32_t n = r.u32();
  if (n > r.bytes_left()) throw eprosima::fastcdr::exception::NotEnoughMemoryException("transforms");
  for (std::uint32_t i = 0; i < n; ++i) {
    BagTransform t;
    r.header(t.parent);
    t.child = r.str();
    t.pose = r.pose();
    if (seen.emplace(t.parent, t.child).second) out.push_back(std::move(t));
  }
}

// "nav_msgs/msg/Odometry" → "nav_msgs/Odometry".
std::string ros1_type_name(std::string type) {
  const auto at = type.find("/msg/");
  if (at != std::string::npos) type.erase(at, 4);
  return type;
}

std::string lowercase(std::string s) {
  for (char& c : s) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return s;
}

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
    const std::string ext = lowercase(e.path().extension().string());
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

void read_messages(const Database& db, const std::filesystem::path& file, const std::map<std::int64_t, TopicRow>& rows,
                   BagMessages& out, std::map<std::string, std::size_t>& counts,
                   std::set<std::pair<std::string, std::string>>& seen) {
  const BagRoles& r = out.roles;
  std::string ids;
  for (const auto& [id, row] : rows) {
    const bool wanted = row.name == r.odom || row.name == r.truth || row.name == r.scan ||
                        std::find(r.tf.begin(), r.tf.end(), row.name) != r.tf.end();
    if (!wanted) continue;
    if (lowercase(row.format) != "cdr") {
      throw InputError(file.string(), 0,
                       "topic " + row.name + ": serialization format \"" + row.format + "\" (expected cdr)");
    }
    ids += (ids.empty() ? "" : ",") + std::to_string(id);
  }
  if (ids.empty()) return;
  Statement s(db,
              "SELECT topic_id, timestamp, data FROM messages WHERE topic_id IN (" + ids + ") ORDER BY timestamp, id");
  while (s.step()) {
    const TopicRow& row = rows.at(s.integer(0));
    const std::size_t index = ++counts[row.name];
    const BagStamp when{0.0, nanoseconds_to_seconds(s.integer(1)), index};
    const auto [data, size] = s.blob(2);
    try {
      if (row.name == r.odom) {
        if (row.type != kOdometryType) {
          throw InputError(file.string(), 0, "topic " + row.name + ": a " + row.type + ", expected " + kOdometryType);
        }
        CdrReader reader(data, size);
        out.odom.push_back(decode_pose(reader, kOdometryType));
        reader.expect_end();
        out.odom.back().time = {out.odom.back().time.stamp, when.record_time, index};
      }
      if (row.name == r.truth) {
        CdrReader reader(data, size);
        out.truth.push_back(decode_pose(reader, row.type));
        reader.expect_end();
        out.truth.back().time = {out.truth.back().time.stamp, when.record_time, index};
      }
      if (row.name == r.scan) {
        CdrReader reader(data, size);
        out.scans.push_back(decode_scan(reader));
        reader.expect_end();
        out.scans.back().time = {out.scans.back().time.stamp, when.record_time, index};
      }
      if (std::find(r.tf.begin(), r.tf.end(), row.name) != r.tf.end()) {
        CdrReader reader(data, size);
        decode_transforms(reader, seen, out.transforms);
        reader.expect_end();
      }
    } catch (const eprosima::fastcdr::exception::Exception& e) {
      throw InputError(file.string(), 0,
                       "topic " + row.name + ", message " + std::to_string(index) + ": not a CDR-serialized " +
                           row.type + " (" + std::to_string(size) + " bytes: " + printable(e.what()) + ")");
    }
  }
}

// ---- writing --------------------------------------------------------------------------------

std::int64_t nanoseconds(double t) { return std::llround(t * 1e9); }

struct Outgoing {
  std::int64_t topic;
  std::int64_t time;
  std::string data;
};

template <class F>
void add(std::vector<Outgoing>& out, std::int64_t topic, double time, F&& serialize) {
  CdrWriter w;
  serialize(w);
  const auto [p, n] = w.bytes();
  out.push_back({topic, nanoseconds(time), std::string(p, n)});
}

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
  std::map<std::string, std::size_t> counts;
  std::set<std::pair<std::string, std::string>> seen;
  for (std::size_t i = 0; i < files.size(); ++i) read_messages(*dbs[i], files[i], rows[i], out, counts, seen);
  return out;
}

void write_ros2_bag(const BagContents& c, const std::filesystem::path& folder, const std::string& name) {
  std::filesystem::create_directories(folder);
  const std::string file_name = name + "_0.db3";
  const std::filesystem::path file = folder / file_name;
  std::filesystem::remove(file);
  struct Topic {
    const char* name;
    const char* type;
    std::size_t count;
  };
  const std::array<Topic, 4> topics{{{"/tf_static", "tf2_msgs/msg/TFMessage", c.static_transforms.empty() ? 0u : 1u},
                                     {"/odom", "nav_msgs/msg/Odometry", c.odom.size()},
                                     {"/ground_truth", "geometry_msgs/msg/PoseStamped", c.truth.size()},
                                     {"/scan", "sensor_msgs/msg/LaserScan", c.scans.size()}}};
  std::vector<Outgoing> messages;
  if (!c.static_transforms.empty()) {
    add(messages, 1, 0.0, [&](CdrWriter& w) {
      w << static_cast<std::uint32_t>(c.static_transforms.size());
      for (const BagTransform& t : c.static_transforms) {
        w.header(0.0, t.parent);
        w << t.child;
        w.pose(t.pose);
      }
    });
  }
  for (const BagPoseMessage& m : c.odom) {
    add(messages, 2, m.time.record_time, [&](CdrWriter& w) {
      w.header(m.time.stamp, m.frame_id);
      w << m.child_frame_id;
      w.pose(m.pose);
      w.zeros(36);
      w << m.tv << 0.0 << 0.0 << 0.0 << 0.0 << m.rv;
      w.zeros(36);
    });
  }
  for (const BagPoseMessage& m : c.truth) {
    add(messages, 3, m.time.record_time, [&](CdrWriter& w) {
      w.header(m.time.stamp, m.frame_id);
      w.pose(m.pose);
    });
  }
  for (const BagScanMessage& m : c.scans) {
    add(messages, 4, m.time.record_time, [&](CdrWriter& w) {
      w.header(m.time.stamp, m.frame_id);
      const double n = static_cast<double>(m.ranges.size());
      w << static_cast<float>(m.angle_min) << static_cast<float>(m.angle_min + m.angle_increment * (n - 1))
        << static_cast<float>(m.angle_increment) << 0.0F << 0.0F << static_cast<float>(m.range_min)
        << static_cast<float>(m.range_max) << m.ranges << std::vector<float>{};
    });
  }
  std::stable_sort(messages.begin(), messages.end(),
                   [](const Outgoing& a, const Outgoing& b) { return a.time < b.time; });
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
      topic.bind(2, std::string(topics[i].name));
      topic.bind(3, std::string(topics[i].type));
      topic.step();
      topic.reset();
    }
    Statement message(db, "INSERT INTO messages(topic_id,timestamp,data) VALUES(?,?,?)");
    for (const Outgoing& m : messages) {
      message.bind(1, m.topic);
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
  for (const Topic& t : topics) {
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
