// Fuzzing: valid files mutated at random (tokens dropped, duplicated or replaced, lines cut,
// random bytes) are either read or rejected with InputError — never a crash, never another
// exception (the tests run under ASan and UBSan).
#include <fmt/format.h>
#include <gtest/gtest.h>
#include <rapidcheck/gtest.h>

#include "datasets/io/carmen_reader.h"
#include "datasets/io/carmen_writer.h"
#include "datasets/io/censi_results_reader.h"
#include "datasets/io/censi_tuple_reader.h"
#include "datasets/io/relations_reader.h"
#include "datasets/io/relative_motion_reader.h"
#include "datasets/io/tum_reader.h"
#include "io_test_support.h"
#include "log_generators.h"
#include "tests/test_data.h"

namespace locbench::io {
namespace {

const std::string kSample =
    "# sample\n"
    "PARAM robot_front_laser_max 50 0 h 0\n"
    "PARAM robot_wheelbase 0.5\n"
    "ODOM 0.1 0.2 0.3 0.5 -0.25 0 1 h 1\n"
    "ENCODER -3 4 1 h 1\n"
    "COMPASS 1.25 2 h 2\n"
    "TRUEPOS 1 2 3 4 5 -1 2 h 2\n"
    "FLASER 5 1 2 3 4 5 0 0 0 0 0 0 2 h 2\n"
    "ROBOTLASER1 0 -1.57 3.14 0.01 81.9 0.01 0 3 1 1 1 0 0 0 0 0 0 0 0 0 0 0 0 0 2 h 2\n"
    "FLASER 4 1 2 3 50 0 0 0 0 0 0 3 h 3\n"
    "ODOM 0.1 0.2 0.3 0.5 -0.25 0 3 h 3\n";

// Valid samples of the other formats read here, mutated by the properties below: Freiburg
// relations, a TUM trajectory, Censi's tuples and published results, tick motions.
const std::string kRelationsSample =
    "# t1 t2 x y z roll pitch yaw\n90.239599 90.719599 0.422330 -0.000750 0 0 0 0.017260\n"
    "1 2 3 4 5 6 7 8\n";

const std::string kTumSample = "# tum\n1 0 0 0 0 0 0 1\n2 1 2 0 0 0 0.7071067811865476 0.7071067811865476\n";

const std::string kCensiTuplesSample =
    "{ \"T\": 7.943960e-01, \"phi_l\": 1.401765e-01, \"phi_r\": -1.373157e-01, \"sm\": [ "
    "1.092608e-03, -5.089714e-04, -2.748851e-02 ] }\n"
    "{ \"T\": 0.79, \"phi_l\": 0.49, \"phi_r\": -0.49, \"sm\": [ 0.0013, -9.7e-05, -0.18 ] }"
    "{ \"T\": 0.8, \"phi_l\": 0.5, \"phi_r\": 0.5, \"sm\": [ 0.01, 0, 0 ] }\n";

const std::string kCensiResultsSample =
    "{ \"axle\": 0.0878146, \"l_diam\": 0.0410529, \"r_diam\": 0.041384, \"l_x\": "
    "-0.00265427, \"l_y\": 0.00583491, \"l_theta\": -1.55197, \"E_d\": 1.00807, \"E_b\": "
    "0.975718,\n\"covariance\": [ [ 4, 0, 0, 0, 0, 0 ], [ 0, 9, 0, 0, 0, 0 ],\n[ 0, 0, 16, 0, 0, "
    "1 ], [ 0, 0, 0, 1, 0, 0 ], [ 0, 0, 0, 0, 1, 0 ], [ 0, 0, 1, 0, 0, 25 ] ] }\n";

const std::string kTickMotionsSample =
    "0 0 -0.000735349  1.50913e-05  0.000174196\n-0.0212839  0.0210924   0.0154077 0.000291585 "
    " -0.0023148\n";

const std::vector<std::string> kNastyTokens = {"",
                                               "nan",
                                               "-nan",
                                               "inf",
                                               "-inf",
                                               "1e999",
                                               "-1e999",
                                               "1e-999",
                                               "abc",
                                               "0x10",
                                               "+",
                                               "-",
                                               "1e",
                                               "#",
                                               "FLASER",
                                               "ODOM",
                                               "PARAM",
                                               "-1",
                                               "0",
                                               "99999999999999999999",
                                               "-9223372036854775809",
                                               "1.5.5",
                                               "--1",
                                               "+-1",
                                               "1,5",
                                               "\xff\xfe",
                                               std::string("1\0"
                                                           "2",
                                                           3),
                                               "\t",
                                               "\r",
                                               "\n"};

// Tokens of a line; joins with a single space.
std::vector<std::string> split(const std::string& line) {
  std::vector<std::string> out;
  std::string cur;
  for (char c : line) {
    if (c == ' ') {
      out.push_back(cur);
      cur.clear();
    } else {
      cur.push_back(c);
    }
  }
  out.push_back(cur);
  return out;
}

std::string join(const std::vector<std::string>& tokens) {
  std::string out;
  for (std::size_t i = 0; i < tokens.size(); ++i) out += (i ? " " : "") + tokens[i];
  return out;
}

// Applies 1–6 random mutations to `text`.
std::string mutate(std::string text) {
  const int count = *rc::gen::inRange(1, 7);
  for (int m = 0; m < count; ++m) {
    std::vector<std::string> lines;
    std::size_t start = 0;
    for (;;) {
      const auto nl = text.find('\n', start);
      lines.push_back(text.substr(start, nl == std::string::npos ? std::string::npos : nl - start));
      if (nl == std::string::npos) break;
      start = nl + 1;
    }
    const std::size_t li = *rc::gen::inRange<std::size_t>(0, lines.size());
    auto tokens = split(lines[li]);
    const std::size_t ti = *rc::gen::inRange<std::size_t>(0, tokens.size());
    switch (*rc::gen::inRange(0, 9)) {
      case 0:  // drop a token
        tokens.erase(tokens.begin() + static_cast<std::ptrdiff_t>(ti));
        lines[li] = join(tokens);
        break;
      case 1:  // duplicate a token
        tokens.insert(tokens.begin() + static_cast<std::ptrdiff_t>(ti), tokens[ti]);
        lines[li] = join(tokens);
        break;
      case 2:  // replace a token with a nasty one
        tokens[ti] = *rc::gen::elementOf(kNastyTokens);
        lines[li] = join(tokens);
        break;
      case 3:  // replace a token with random bytes
        tokens[ti] = *rc::gen::container<std::string>(rc::gen::arbitrary<char>());
        lines[li] = join(tokens);
        break;
      case 4:  // truncate the line
        lines[li] = lines[li].substr(0, *rc::gen::inRange<std::size_t>(0, lines[li].size() + 1));
        break;
      case 5:  // drop or duplicate a line
        if (*rc::gen::arbitrary<bool>()) {
          lines.erase(lines.begin() + static_cast<std::ptrdiff_t>(li));
        } else {
          lines.insert(lines.begin() + static_cast<std::ptrdiff_t>(li), lines[li]);
        }
        break;
      case 6: {  // swap two lines (breaks time order)
        const std::size_t lj = *rc::gen::inRange<std::size_t>(0, lines.size());
        std::swap(lines[li], lines[lj]);
        break;
      }
      case 7: {  // insert random bytes anywhere
        const std::string bytes = *rc::gen::container<std::string>(rc::gen::arbitrary<char>());
        lines[li].insert(*rc::gen::inRange<std::size_t>(0, lines[li].size() + 1), bytes);
        break;
      }
      default:  // replace a number with one of another magnitude
        tokens[ti] = std::to_string(*rc::gen::arbitrary<std::int64_t>());
        lines[li] = join(tokens);
        break;
    }
    text.clear();
    for (std::size_t i = 0; i < lines.size(); ++i) text += (i ? "\n" : "") + lines[i];
  }
  return text;
}

// Runs `read`; fails the property unless it returns or throws InputError.
using testing::reads_or_rejects;

// Mutates the valid `sample` and fails the property unless `parse(text, source_name)` reads the
// mutated text or throws InputError.
template <class Parse>
void mutation_is_read_or_rejected(const std::string& sample, Parse parse, const std::string& source_name) {
  const std::string text = mutate(sample);
  reads_or_rejects([&] { parse(text, source_name); });
}

RC_GTEST_PROP(CarmenFuzz, MutatedSampleLogIsReadOrRejectedWithInputError, ()) {
  mutation_is_read_or_rejected(kSample, parse_carmen_log, "fuzz.clf");
}

RC_GTEST_PROP(CarmenFuzz, MutatedRandomLogIsReadOrRejectedWithInputError, ()) {
  mutation_is_read_or_rejected(format_carmen_log(testing::random_carmen_log()), parse_carmen_log, "fuzz.clf");
}

RC_GTEST_PROP(CarmenFuzz, RandomBytesAreReadOrRejectedWithInputError, ()) {
  const auto text = *rc::gen::container<std::string>(rc::gen::arbitrary<char>());
  reads_or_rejects([&] { parse_carmen_log(text, "fuzz.clf"); });
}

RC_GTEST_PROP(RelationsFuzz, MutatedRelationsAreReadOrRejectedWithInputError, ()) {
  mutation_is_read_or_rejected(kRelationsSample, parse_relations, "fuzz.relations");
}

RC_GTEST_PROP(TumFuzz, MutatedTrajectoriesAreReadOrRejectedWithInputError, ()) {
  mutation_is_read_or_rejected(kTumSample, parse_tum, "fuzz.tum");
}

// Bytes of a valid .clf.gz flipped or cut: zlib errors surface as InputError.
TEST(CarmenFuzz, CorruptedGzipFilesAreReadOrRejectedWithInputError) {
  testing::ScratchDir dir;
  std::string text = kSample;
  for (int i = 0; i < 300; ++i) {
    text += fmt::format("ODOM 0.1 0.2 0.3 0.5 -0.25 0 {} h 0\n", 10 + i);
  }
  const std::string packed = testing::gzip(text);
  int run = 0;
  const auto result = rc::check("corrupt gzip", [&] {
    std::string bytes = packed;
    const int edits = *rc::gen::inRange(1, 4);
    for (int e = 0; e < edits; ++e) {
      const auto i = *rc::gen::inRange<std::size_t>(0, bytes.size());
      if (*rc::gen::arbitrary<bool>()) {
        bytes[i] = *rc::gen::arbitrary<char>();
      } else {
        bytes.resize(i);
      }
      if (bytes.empty()) break;
    }
    const auto path = dir.file(fmt::format("f{}.clf.gz", run++));
    testing::write_bytes(path, bytes);
    reads_or_rejects([&] { read_carmen_log(path); });
  });
  EXPECT_TRUE(result);
}

RC_GTEST_PROP(CensiTupleFuzz, MutatedTuplesAreReadOrRejectedWithInputError, ()) {
  mutation_is_read_or_rejected(kCensiTuplesSample, parse_censi_tuples, "fuzz.tuple");
}

RC_GTEST_PROP(CensiResultsFuzz, MutatedResultsAreReadOrRejectedWithInputError, ()) {
  mutation_is_read_or_rejected(kCensiResultsSample, parse_censi_results, "fuzz_results.json");
}

RC_GTEST_PROP(RelativeMotionFuzz, MutatedMotionPairsAreReadOrRejectedWithInputError, ()) {
  const std::string odom = mutate(" 0 0 0\n 0.113 -8.3e-05 0\n 0.115 -0.0001 0\n");
  const std::string ref = mutate(" 0 0 0\n 0.113001 -0.000942 0.003906\n 0.1108986065228533 0.0022428 0\n");
  reads_or_rejects([&] { parse_relative_motion_pairs(odom, "odom.txt", ref, "sm.txt"); });
}

RC_GTEST_PROP(RelativeMotionFuzz, MutatedTickMotionsAreReadOrRejectedWithInputError, ()) {
  mutation_is_read_or_rejected(kTickMotionsSample, parse_tick_motions, "dd.txt");
}

RC_GTEST_PROP(CalibrationFuzz, RandomBytesAreReadOrRejectedWithInputError, ()) {
  const auto text = *rc::gen::container<std::string>(rc::gen::arbitrary<char>());
  reads_or_rejects([&] { parse_censi_tuples(text, "fuzz.tuple"); });
  reads_or_rejects([&] { parse_censi_results(text, "fuzz_results.json"); });
  reads_or_rejects([&] { parse_tick_motions(text, "dd.txt"); });
}

}  // namespace
}  // namespace locbench::io
