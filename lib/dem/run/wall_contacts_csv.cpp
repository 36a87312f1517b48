#include "dem/run/wall_contacts_csv.hpp"

#include <algorithm>

#include <fmt/format.h>

#include "dem/cases/text.hpp"
#include "dem/run/fill_quantities.hpp"

namespace dem {

std::string wall_contacts_csv(const Simulation& sim, const OutputSpec& o) {
  std::string out = "wall,s [m],x [m],y [m],depth [m],fn [N],fs [N]\n";
  const double top = fill_top(sim);
  for (std::size_t k = 0; k < o.wall_contact_walls.size(); ++k) {
    auto contacts = sim.wall_contact_forces(o.wall_contact_walls[k]);
    std::stable_sort(contacts.begin(), contacts.end(), [](const auto& a, const auto& b) { return a.s < b.s; });
    for (const auto& c : contacts)
      out += fmt::format("{},{:.17g},{:.17g},{:.17g},{:.17g},{:.17g},{:.17g}\n", csv_field(o.wall_contacts[k]), c.s,
                         c.point.x, c.point.y, top - c.point.y, c.normal, c.tangential);
  }
  return out;
}

}  // namespace dem
