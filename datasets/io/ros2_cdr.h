#pragma once
// ROS 2 messages as CDR bytes, whatever the storage (sqlite3: ros2_bag.cpp, MCAP: mcap_bag.cpp):
// the chosen topics' messages decoded into BagMessages with eProsima Fast CDR, and BagContents
// serialized for a writer.
#include <cstdint>
#include <filesystem>
#include <map>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include "datasets/io/bag_messages.h"

namespace locbench::io {

// "nav_msgs/msg/Odometry" → "nav_msgs/Odometry" (the names bag_messages.h uses).
std::string ros1_type_name(std::string type);

// Decodes the messages of a bag's chosen topics (out.roles) into `out`, one at a time in record
// order. Errors are InputErrors naming `file`, the topic and the message's number on it.
class Ros2MessageDecoder {
 public:
  Ros2MessageDecoder(BagMessages& out, std::filesystem::path file) : out_(out), file_(std::move(file)) {}
  void set_file(std::filesystem::path file) { file_ = std::move(file); }
  // Is the topic one of the chosen ones?
  bool wants(const std::string& topic) const;
  // Throws unless a chosen topic's serialization format is CDR.
  void check_format(const std::string& topic, const std::string& format) const;
  // One message of `topic` (type in the ROS 1 form) recorded at `record_ns`.
  void add(const std::string& topic, const std::string& type, std::int64_t record_ns, const char* data,
           std::size_t size);

 private:
  BagMessages& out_;
  std::filesystem::path file_;
  std::map<std::string, std::size_t> counts_;
  std::set<std::pair<std::string, std::string>> seen_;
};

// A bag's contents as CDR messages on the default topics, for a writer: the topics that have
// messages (ROS 2 type names), and every message in record order.
struct Ros2Topic {
  std::string name, type;
  std::size_t count = 0;
};
struct Ros2Message {
  std::size_t topic = 0;  // into Ros2Serialized::topics
  std::int64_t time = 0;  // record time [ns]
  std::string data;
};
struct Ros2Serialized {
  std::vector<Ros2Topic> topics;
  std::vector<Ros2Message> messages;
};
Ros2Serialized serialize_ros2(const BagContents& contents);

}  // namespace locbench::io
