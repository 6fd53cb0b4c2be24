#pragma once
// The records of a ROS 1 bag file (format 2.0): its connections (topic, type, md5 sum, message
// count) from the index section, then every message record in file order, from chunks stored
// plain or compressed with bz2 or lz4. No ROS headers: ros1_bag.cpp deserializes the messages.
// Every length is checked against the file or chunk it lies in; a bag that is not well formed is
// an InputError naming the byte where it went wrong.
#include <cstdint>
#include <filesystem>
#include <functional>
#include <map>
#include <string>

namespace locbench::io {

struct Ros1Connection {
  std::string topic;
  std::string type;
  std::string md5sum;
  std::uint64_t count = 0;  // messages, from the chunk info records
  double first_record = 0.0, last_record = 0.0;
};

// Called with the connections by id before any message is read; false: read no message.
using Ros1ConnectionChooser = std::function<bool(const std::map<std::uint32_t, Ros1Connection>&)>;
// One message record: its connection, record time (sec, nsec) and serialized bytes.
using Ros1MessageVisitor = std::function<void(std::uint32_t connection, std::uint32_t sec, std::uint32_t nsec,
                                              const std::uint8_t* data, std::uint32_t size)>;

void read_ros1_records(const std::filesystem::path& path, const Ros1ConnectionChooser& choose,
                       const Ros1MessageVisitor& visit);

}  // namespace locbench::io
