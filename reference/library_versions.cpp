#include "ref/library_versions.hpp"

#include <string>

#include <Eigen/Core>
#include <boost/version.hpp>
#include <gsl/gsl_version.h>

namespace ref {

std::string library_versions() {
  return "GSL " + std::string(GSL_VERSION) + ", Boost " + std::to_string(BOOST_VERSION / 100000) + "." +
         std::to_string(BOOST_VERSION / 100 % 1000) + "." + std::to_string(BOOST_VERSION % 100) + ", Eigen " +
         std::to_string(EIGEN_WORLD_VERSION) + "." + std::to_string(EIGEN_MAJOR_VERSION) + "." +
         std::to_string(EIGEN_MINOR_VERSION);
}

}  // namespace ref
