// OdometryModel as JSON: the fitted model a report hands to a filter (`"models": {"odometry": …}`).
#include "algorithms/diagnosis/odometry_model.h"
#include "core/option_fields.h"

namespace locbench::diagnosis {

// OdometryModel's fields, stated once (odometry_model.h gives the equations). The σ are per
// window of the report's `models.odometry_window_s` seconds.
template <class V>
void visit_fields(V& v, OdometryModel& m) {
  v.field("E_d", m.E_d, "", positive(), "wheel diameter ratio D_R/D_L (eq. 2.1), encoder odometry");
  v.field("E_b", m.E_b, "", positive(), "effective / nominal wheelbase (eq. 2.2), encoder odometry");
  v.field("E_o", m.E_o, "", positive(), "mean wheel diameter scale (eq. 2.15), encoder odometry");
  v.field("velocity_scale", m.velocity_scale, "", positive(), "true / logged distance, velocity odometry");
  v.field("turn_rate_scale", m.turn_rate_scale, "", positive(), "true / logged turn, velocity odometry");
  v.field("turn_rate_bias_rad_s", m.turn_rate_bias, "rad/s", any_finite(), "added to the logged turn rate");
  v.field("speed_slope_s_per_m", m.speed_slope, "s/m", any_finite(), "distance scale change per m/s of speed");
  v.field("drive_tau_s", m.drive_tau, "s", non_negative(), "first-order drive response time constant; 0 none");
  v.field("time_offset_s", m.time_offset, "s", closed(-10.0, 10.0), "odometry logged time − true time");
  v.field("dof", m.dof, "", non_negative(), "Student-t degrees of freedom of the window noise; 0 = normal");
  v.field("sigma_x_m", m.sigma_x, "m", positive(), "white noise floor per window, along the start heading");
  v.field("sigma_y_m", m.sigma_y, "m", positive(), "white noise floor per window, left of it");
  v.field("sigma_theta_rad", m.sigma_theta, "rad", positive(), "white noise floor per window, heading");
  v.field("k2_m", m.k2, "m", non_negative(), "wheel-travel variance per metre of travel (eq. 4.16)");
  v.field("slip_rate_per_m", m.slip_rate, "1/m", non_negative(), "slip events per metre of wheel travel");
  v.field("slip_loss", m.slip_loss, "", closed(-1.0, 1.0), "fraction of one sample's travel a slip loses");
  v.field("stall_rate_per_s", m.stall_rate, "1/s", non_negative(), "drive stall episodes per second");
  v.field("stall_duration_s", m.stall_duration, "s", non_negative(), "length of a stall episode");
}

void validate(const OdometryModel& m) { validate_fields(m, "OdometryModel"); }

LOCBENCH_OPTIONS_JSON(OdometryModel)

}  // namespace locbench::diagnosis
