// Censi's calibration data: wheel-speed tuples, published results, tick motions. Tuples that
// parse are calibrated as `calibrate ml` does: too few or motionless samples must be an
// InputError, never another exception (an internal error, exit 3).
#include "algorithms/calibration/calibration_data.h"
#include "algorithms/calibration/ml_calibration.h"
#include "datasets/io/censi_results_reader.h"
#include "datasets/io/censi_tuple_reader.h"
#include "datasets/io/relative_motion_reader.h"
#include "fuzz/fuzz_input.h"

namespace {

// Tuples calibrated per input (the Ceres solve grows with them; Censi's logs have ~1,000).
constexpr std::size_t kMaxCalibratedTuples = 200;

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace locbench;
  const std::string t = fuzz::text(data, size);
  fuzz::accept_or_reject([&] {
    const auto tuples = io::parse_censi_tuples(t, "fuzz.tuple");
    if (tuples.size() > kMaxCalibratedTuples) return;
    calibration::MlCalibrationOptions o;
    o.noise.kind = calibration::NoiseModelKind::kPerComponent;  // as `calibrate ml` on a .tuple file
    o.outliers = {4, 0.01};
    (void)calibration::calibrate_ml(calibration::calibration_data_from_wheel_speed_tuples(tuples), o);
  });
  fuzz::accept_or_reject([&] { io::parse_censi_results(t, "fuzz.results"); });
  return fuzz::accept_or_reject([&] { io::parse_tick_motions(t, "fuzz.ticks"); });
}
