#pragma once
// SI inside: metres, radians, seconds. Conversions happen only at the edges, through these.
#include <numbers>

namespace locbench {

constexpr double kPi = std::numbers::pi;

constexpr double deg(double degrees) { return degrees * kPi / 180.0; }     // degrees → rad
constexpr double to_deg(double radians) { return radians * 180.0 / kPi; }  // rad → degrees
constexpr double mm(double millimetres) { return millimetres * 1e-3; }     // mm → m
constexpr double to_mm(double metres) { return metres * 1e3; }             // m → mm

}  // namespace locbench
