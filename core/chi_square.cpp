#include "core/chi_square.h"

#include <boost/math/distributions/chi_squared.hpp>
#include <stdexcept>

namespace locbench {

ChiSquareDof::ChiSquareDof(double dof) : value(dof) {
  if (!(dof > 0.0)) throw std::invalid_argument("chi-square: degrees of freedom must be > 0");
}

double chi_square_quantile(ChiSquareDof dof, double probability) {
  if (!(probability >= 0.0 && probability < 1.0)) {
    throw std::invalid_argument("chi_square_quantile: probability must be in [0, 1)");
  }
  return boost::math::quantile(boost::math::chi_squared_distribution<double>(dof.value), probability);
}

double chi_square_upper_quantile(ChiSquareDof dof, double tail) {
  if (!(tail > 0.0 && tail <= 1.0)) {
    throw std::invalid_argument("chi_square_upper_quantile: tail must be in (0, 1]");
  }
  return boost::math::quantile(boost::math::complement(boost::math::chi_squared_distribution<double>(dof.value), tail));
}

double chi_square_upper_tail(ChiSquareDof dof, double x) {
  if (!(x > 0.0)) return 1.0;
  return boost::math::cdf(boost::math::complement(boost::math::chi_squared_distribution<double>(dof.value), x));
}

}  // namespace locbench
