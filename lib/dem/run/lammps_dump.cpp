#include "dem/run/lammps_dump.hpp"

#include <algorithm>
#include <iterator>
#include <limits>

#include <fmt/format.h>

namespace dem {

std::string lammps_dump_frame(const Simulation& sim) {
  const Model& m = sim.model();
  const Elements& e = m.elements;
  std::vector<std::size_t> shown;  // active elements, by id
  double xlo = std::numeric_limits<double>::infinity(), ylo = xlo, xhi = -xlo, yhi = -xlo;
  for (std::size_t id = 0; id < e.size(); ++id)
    if (const std::size_t i = sim.index_of(static_cast<std::uint32_t>(id)); e.active[i]) {
      shown.push_back(i);
      xlo = std::min(xlo, e.x[i] - e.radius[i]), xhi = std::max(xhi, e.x[i] + e.radius[i]);
      ylo = std::min(ylo, e.y[i] - e.radius[i]), yhi = std::max(yhi, e.y[i] + e.radius[i]);
    }
  if (shown.empty()) xlo = xhi = ylo = yhi = 0.0;
  fmt::memory_buffer out;
  auto to = std::back_inserter(out);
  fmt::format_to(to, "ITEM: TIMESTEP\n{}\nITEM: NUMBER OF ATOMS\n{}\nITEM: BOX BOUNDS ff ff pp\n", sim.steps(), shown.size());
  fmt::format_to(to, "{:.17g} {:.17g}\n{:.17g} {:.17g}\n{:.17g} {:.17g}\n", xlo, xhi, ylo, yhi, -0.5 * m.thickness, 0.5 * m.thickness);
  fmt::format_to(to, "ITEM: ATOMS id type x y vx vy omegaz radius fx fy\n");
  for (std::size_t i : shown)
    fmt::format_to(to, "{} {} {:.17g} {:.17g} {:.17g} {:.17g} {:.17g} {:.17g} {:.17g} {:.17g}\n", sim.id_of(i) + 1, e.material[i] + 1,
        e.x[i], e.y[i], e.vx[i], e.vy[i], e.omega[i], e.radius[i], e.fx[i], e.fy[i]);
  return {out.data(), out.size()};
}

}  // namespace dem
