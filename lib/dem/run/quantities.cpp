#include "dem/run/quantities.hpp"
#include "dem/run/fill_quantities.hpp"

#include "dem/cases/text.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <limits>
#include <stdexcept>

#include <fmt/format.h>

namespace dem {

namespace {

/// "e12" → 12, else −1.
long element_ref(const std::string& s, const Model& m) {
  if (s.size() < 2 || s[0] != 'e' || s.find_first_not_of("0123456789", 1) != std::string::npos) return -1;
  const long i = std::stol(s.substr(1));
  if (i < 0 || static_cast<std::size_t>(i) >= m.elements.size())
    throw std::invalid_argument(fmt::format("element {} does not exist (the case has {})", i, m.elements.size()));
  return i;
}

long wall_ref(const std::string& s, const Model& m) {
  for (std::size_t k = 0; k < m.walls.size(); ++k)
    if (m.walls[k].name == s) return static_cast<long>(k);
  return -1;
}

/// (M23, M24): slide of the lower corner of element u down a slope inclined at α,
/// δ = (x_c0 − x_c) cos α + (y_c0 − y_c) sin α, with the corner at x + √2 r cos(5π/4 + φ) (φ = α + θ is
/// the element's absolute rotation: the corner (−1, −1) of its square) and x_c0, y_c0 its start.
QuantityFn corner_slide(std::size_t id, double alpha, const Model& m) {
  auto corner = [](const Elements& e, std::size_t u) {
    const double a = 1.25 * std::numbers::pi + e.phi[u], d = std::sqrt(2.0) * e.radius[u];
    return Vec2{e.x[u] + d * std::cos(a), e.y[u] + d * std::sin(a)};
  };
  const Vec2 c0 = corner(m.elements, index_of_id(m.elements, static_cast<std::uint32_t>(id)));
  const double ca = std::cos(alpha), sa = std::sin(alpha);
  return [id, c0, ca, sa, corner](const Simulation& s) {
    const Vec2 c = corner(s.model().elements, s.index_of(static_cast<std::uint32_t>(id)));
    return (c0.x - c.x) * ca + (c0.y - c.y) * sa;
  };
}

/// The error for a quantity name: `quantity "name": why`.
std::invalid_argument bad_quantity(const std::string& name, const std::string& why) {
  return std::invalid_argument(fmt::format("quantity \"{}\": {}", name, why));
}

/// e<i>.<field>, e<i>.gap|fn|fs|links.<other>: a quantity of element u (`p`: the name split on '.').
QuantityFn element_quantity(const std::string& name, std::size_t u, const std::vector<std::string>& p, const Model& m) {
  auto bad = [&](const std::string& why) { return bad_quantity(name, why); };
  if (p.size() == 2) {
    const std::string& f = p[1];
    if (f == "x") return [u](const Simulation& s) { return s.model().elements.x[s.index_of(u)]; };
    if (f == "y") return [u](const Simulation& s) { return s.model().elements.y[s.index_of(u)]; };
    if (f == "phi") return [u](const Simulation& s) { return s.model().elements.phi[s.index_of(u)]; };
    if (f == "vx") return [u](const Simulation& s) { return s.model().elements.vx[s.index_of(u)]; };
    if (f == "vy") return [u](const Simulation& s) { return s.model().elements.vy[s.index_of(u)]; };
    if (f == "omega") return [u](const Simulation& s) { return s.model().elements.omega[s.index_of(u)]; };
    if (f == "fx") return [u](const Simulation& s) { return s.model().elements.fx[s.index_of(u)]; };
    if (f == "fy") return [u](const Simulation& s) { return s.model().elements.fy[s.index_of(u)]; };
    if (f == "moment") return [u](const Simulation& s) { return s.model().elements.moment[s.index_of(u)]; };
    // px(a,b), py(a,b): a body point at the offset (a r, b r) in the element's own frame, e.g. the
    // corner (1,-1) of a PRE's square; for a polygon (a w/2, b h/2), with w × h the box of its corners in its
    // own frame about the centroid (the corner (1,-1) of a rectangle)
    if ((f.rfind("px(", 0) == 0 || f.rfind("py(", 0) == 0) && f.back() == ')') {
      const auto comma = f.find(',');
      if (comma == std::string::npos) throw bad("expected px(a,b) or py(a,b)");
      double a = 0.0, b = 0.0;
      try {
        a = std::stod(f.substr(3, comma - 3));
        b = std::stod(f.substr(comma + 1, f.size() - comma - 2));
      } catch (const std::exception&) {
        throw bad("expected numbers in px(a,b) / py(a,b)");
      }
      const bool want_x = f[1] == 'x';
      return [id = u, a, b, want_x](const Simulation& s) {
        const Elements& e = s.model().elements;
        const std::size_t u = s.index_of(id);
        const double c = std::cos(e.phi[u]), sn = std::sin(e.phi[u]), r = e.radius[u];
        double ra = r, rb = r;
        if (e.shape[u] == Shape::polygon) {
          ra = rb = 0.0;
          for (const Vec2& v : s.model().polygons[static_cast<std::size_t>(s.model().polygon_of[u])].vertices)
            ra = std::max(ra, std::abs(v.x)), rb = std::max(rb, std::abs(v.y));
        }
        return want_x ? e.x[u] + (c * a * ra - sn * b * rb) : e.y[u] + (sn * a * ra + c * b * rb);
      };
    }
    throw bad("unknown element field (x, y, phi, vx, vy, omega, fx, fy, moment, px(a,b), py(a,b), gap.<other>, fn.<other>, fs.<other>)");
  }
  if (p.size() == 3 && (p[1] == "gap" || p[1] == "fn" || p[1] == "fs" || p[1] == "mr" || p[1] == "links" || p[1] == "mobilised")) {
    long j = -1;
    try {
      j = element_ref(p[2], m);
    } catch (const std::invalid_argument& e) {
      throw bad(e.what());
    }
    const long w = j < 0 ? wall_ref(p[2], m) : -1;
    if (j < 0 && w < 0) throw bad(fmt::format("\"{}\" is neither an element (e<i>) nor a wall name", p[2]));
    const bool wall = j < 0;
    const auto o = static_cast<std::uint32_t>(wall ? w : j);
    if (p[1] == "gap" && (m.elements.shape.at(u) == Shape::polygon || (!wall && m.elements.shape.at(o) == Shape::polygon)))
      throw bad("gap is the distance of centres less the radii, not defined for a polygon element (docs/model.md §5); "
                "use fn.<other> or links.<other>");
    if (p[1] == "gap")
      return [id = u, other = o, wall](const Simulation& s) {
        const Elements& e = s.model().elements;
        const std::size_t u = s.index_of(id);
        const std::uint32_t o = wall ? other : s.index_of(other);
        const Vec2 c{e.x[u], e.y[u]};
        if (wall) return norm(closest_point(s.model().walls[o], c) - c) - e.radius[u];
        return std::hypot(e.x[o] - e.x[u], e.y[o] - e.y[u]) - e.radius[u] - e.radius[o];
      };
    if (p[1] == "links")
      return [u, o, wall](const Simulation& s) {
        return static_cast<double>(s.contact(s.index_of(static_cast<std::uint32_t>(u)), wall ? o : s.index_of(o), wall).links);
      };
    if (p[1] == "mobilised")  // |Q| / P: the friction the contact uses; tan φ at the Coulomb limit (M11)
      return [u, o, wall](const Simulation& s) {
        const ContactView c = s.contact(s.index_of(static_cast<std::uint32_t>(u)), wall ? o : s.index_of(o), wall);
        return c.fn > 0.0 ? std::abs(c.fs) / c.fn : 0.0;
      };
    if (p[1] == "mr")  // the rolling moment on element u (R6)
      return [u, o, wall](const Simulation& s) {
        return s.contact(s.index_of(static_cast<std::uint32_t>(u)), wall ? o : s.index_of(o), wall).mr *
               (!wall && s.index_of(o) < s.index_of(static_cast<std::uint32_t>(u)) ? -1.0 : 1.0);
      };
    const bool normal = p[1] == "fn";
    return [u, o, wall, normal](const Simulation& s) {
      const ContactView c = s.contact(s.index_of(static_cast<std::uint32_t>(u)), wall ? o : s.index_of(o), wall);
      return normal ? c.fn : c.fs;
    };
  }
  throw bad("expected e<i>.<field> or e<i>.gap|fn|fs|mr|links|mobilised.<other>");
}

/// Parses "f(a,b,...)"'s comma-separated numbers (exactly `count` of them); throws std::invalid_argument.
std::vector<double> call_numbers(const std::string& name, std::size_t open, std::size_t count) {
  if (name.back() != ')') throw std::invalid_argument(name);
  const auto parts = split(name.substr(open, name.size() - open - 1), ',');
  if (parts.size() != count) throw std::invalid_argument(name);
  std::vector<double> out;
  for (const auto& a : parts) {
    std::size_t used = 0;
    out.push_back(std::stod(a, &used));
    if (used != a.size() || !std::isfinite(out.back())) throw std::invalid_argument(a);
  }
  return out;
}

/// box.vx|vy(x0,x1,y0,y1): the mean velocity component of the active free elements whose centre lies in
/// the box [x0,x1] × [y0,y1] [m] now (0 when none does). A silo's flow pattern: which parts of the fill
/// move, and how fast, against the column over the slit (K Figs. 8, 9).
QuantityFn box_velocity(const std::string& name, const Model&) {
  const bool vx = name.rfind("box.vx(", 0) == 0;
  std::vector<double> a;
  try {
    a = call_numbers(name, std::string("box.vx(").size(), 4);
  } catch (const std::exception&) {
    throw bad_quantity(name, "expected box.vx(x0,x1,y0,y1) or box.vy(x0,x1,y0,y1) with finite numbers in metres");
  }
  if (!(a[0] < a[1] && a[2] < a[3])) throw bad_quantity(name, "expected x0 < x1 and y0 < y1 in box.vx|vy(x0,x1,y0,y1)");
  return [a, vx](const Simulation& s) {
    const Elements& e = s.model().elements;
    double sum = 0.0;
    std::size_t n = 0;
    for (std::size_t i = 0; i < e.size(); ++i)
      if (e.active[i] && e.motion[i] == Motion::free && e.x[i] >= a[0] && e.x[i] <= a[1] && e.y[i] >= a[2] && e.y[i] <= a[3]) {
        sum += vx ? e.vx[i] : e.vy[i];
        ++n;
      }
    return n ? sum / static_cast<double>(n) : 0.0;
  };
}

}  // namespace

double mean_increment(const Simulation& s) {
  const Elements& e = s.model().elements;
  double sum = 0.0;
  std::size_t n = 0;
  for (std::size_t i = 0; i < e.size(); ++i)
    if (e.active[i] && e.motion[i] == Motion::free) {
      sum += std::abs(e.dx[i]) + std::abs(e.dy[i]);
      n += 2;
    }
  return n ? sum / static_cast<double>(n) : 0.0;
}

bool reads_contact_forces(const std::string& name) {
  const auto p = split(name, '.');
  return name == "unbalanced_force_ratio" ||
         (p.size() == 3 && (p[1] == "fn" || p[1] == "fs" || p[1] == "mr" || p[1] == "links" || p[1] == "mobilised"));
}

double unbalanced_force_ratio(const Simulation& s) {
  const Elements& e = s.model().elements;
  double sum = 0.0;
  std::size_t n = 0;
  for (std::size_t i = 0; i < e.size(); ++i)
    if (e.active[i] && e.motion[i] == Motion::free) {
      sum += std::hypot(e.fx[i], e.fy[i]);
      ++n;
    }
  const auto [contact_sum, contacts] = s.contact_force_sum();
  if (contacts == 0 || n == 0) return std::numeric_limits<double>::infinity();
  return (sum / static_cast<double>(n)) / (contact_sum / static_cast<double>(contacts));
}

QuantityFn compile_quantity(const std::string& name, const Model& m) {
  const auto p = split(name, '.');
  auto bad = [&](const std::string& why) { return bad_quantity(name, why); };
  if (name == "t") return [](const Simulation& s) { return s.time(); };
  if (name == "step") return [](const Simulation& s) { return static_cast<double>(s.steps()); };
  if (name == "contacts") return [](const Simulation& s) { return static_cast<double>(s.contact_count()); };
  if (name == "energy.kinetic") return [](const Simulation& s) { return s.energies().kinetic; };
  if (name == "energy.potential") return [](const Simulation& s) { return s.energies().potential; };
  if (name == "energy.elastic") return [](const Simulation& s) { return s.energies().elastic; };
  if (name == "energy.total") return [](const Simulation& s) { return s.energies().total(); };
  if (name == "mean_increment") return mean_increment;
  if (name == "gap_springs.intact" || name == "gap_springs.broken") {  // (B1, B4): bonds formed at the start, intact or broken
    if (std::none_of(m.laws.begin(), m.laws.end(), [](const PairLaw& l) { return l.gap.enabled; }))
      throw bad("needs gap springs (a `gap = { … }` in a linear [[contact]])");
    if (name == "gap_springs.intact") return [](const Simulation& s) { return static_cast<double>(s.gap_springs_intact()); };
    return [](const Simulation& s) { return static_cast<double>(s.gap_springs().size() - s.gap_springs_intact()); };
  }
  try {  // active.top, active.area_fraction(x0,x1,y0,y1): fill_quantities.hpp
    if (auto fill = compile_fill_quantity(name)) return *fill;
  } catch (const std::invalid_argument& e) {
    throw bad(e.what());
  }
  // base plate (M21): travel δ_B = ∫|v_B| dt and displacement since the start; only with a base plate
  // (without one they would be a column of zeros)
  if ((name == "plate_travel" || name == "plate_dx" || name == "plate_dy") && !m.base_plate.enabled)
    throw bad("needs a base plate (a [base_friction] table in the case)");
  if (name == "plate_travel") return [](const Simulation& s) { return s.plate_travel().travel; };
  if (name == "plate_dx") return [](const Simulation& s) { return s.plate_travel().displacement.x; };
  if (name == "plate_dy") return [](const Simulation& s) { return s.plate_travel().displacement.y; };
  // e<i>.corner_slide(α): read before splitting on '.', so that α may have decimals
  if (const auto dot = name.find('.'); dot != std::string::npos && name.compare(dot + 1, 13, "corner_slide(") == 0) {
    long i = -1;
    try {
      i = element_ref(name.substr(0, dot), m);
    } catch (const std::invalid_argument& e) {
      throw bad(e.what());
    }
    if (i < 0 || name.back() != ')') throw bad("expected e<i>.corner_slide(alpha), alpha in degrees");
    double alpha_deg = 0.0;
    try {
      std::size_t used = 0;
      const std::string arg = name.substr(dot + 14, name.size() - dot - 15);
      alpha_deg = std::stod(arg, &used);
      if (used != arg.size()) throw std::invalid_argument(arg);
    } catch (const std::exception&) {
      throw bad("expected a number (degrees) in corner_slide(alpha)");
    }
    return corner_slide(static_cast<std::size_t>(i), alpha_deg * std::numbers::pi / 180.0, m);
  }
  // <wall>.fn(s0,s1), <wall>.fs(s0,s1), <wall>.fn_max(s0,s1): the wall's contacts in a band along it (s in
  // metres from its first end point); read before splitting on '.', so that the bounds may have decimals
  for (const char* field : {".fn(", ".fs(", ".fn_max("})
    if (const auto at = name.find(field); at != std::string::npos && at > 0 && name.back() == ')') {
      const long w = wall_ref(name.substr(0, at), m);
      if (w < 0) break;  // e<i>.fn(...) is not a band: handled (and refused) below
      const std::size_t open = at + std::string(field).size();
      const std::string args = name.substr(open, name.size() - open - 1);
      const auto comma = args.find(',');
      double s0 = 0.0, s1 = 0.0;
      try {
        if (comma == std::string::npos) throw std::invalid_argument(args);
        std::size_t u0 = 0, u1 = 0;
        const std::string a = args.substr(0, comma), b = args.substr(comma + 1);
        s0 = std::stod(a, &u0);
        s1 = std::stod(b, &u1);
        if (u0 != a.size() || u1 != b.size()) throw std::invalid_argument(args);
      } catch (const std::exception&) {
        throw bad("expected <wall>.fn(s0,s1), <wall>.fs(s0,s1) or <wall>.fn_max(s0,s1) with s0 < s1 in metres along the wall");
      }
      if (!(s0 < s1)) throw bad("expected s0 < s1 in <wall>.fn(s0,s1) / fs(s0,s1) / fn_max(s0,s1)");
      const auto k = static_cast<std::uint32_t>(w);
      if (field[3] == '_') return [k, s0, s1](const Simulation& s) { return s.wall_band_force(k, s0, s1).max_normal; };
      if (field[2] == 'n')
        return [k, s0, s1](const Simulation& s) { return s.wall_band_force(k, s0, s1).normal; };
      return [k, s0, s1](const Simulation& s) { return s.wall_band_force(k, s0, s1).tangential; };
    }
  if (name.rfind("box.vx(", 0) == 0 || name.rfind("box.vy(", 0) == 0) return box_velocity(name, m);
  // walls.fx, walls.fy: the force of the elements on all walls together (a settled silo: the weight)
  if (name == "walls.fx" || name == "walls.fy") {
    const bool x = name.back() == 'x';
    return [x](const Simulation& s) {
      double sum = 0.0;
      for (const Wall& w : s.model().walls) sum += x ? w.force.x : w.force.y;
      return sum;
    };
  }
  if (name == "unbalanced_force_ratio") return unbalanced_force_ratio;
  // a silo's discharge (core/discharge.hpp): the disks removed below the outlet line, their mass; the
  // active (remaining) disks and their mass [kg per thickness l]
  if (name == "discharged.count" || name == "discharged.mass") {
    if (!m.discharge.enabled) throw bad("needs a [discharge] table");
    const bool count = name.back() == 't';
    return [count](const Simulation& s) {
      const Discharged d = discharged(s.model());
      return count ? static_cast<double>(d.count) : d.mass;
    };
  }
  if (name == "active.count" || name == "active.mass") {
    const bool count = name.back() == 't';
    return [count](const Simulation& s) {
      const Elements& e = s.model().elements;
      double sum = 0.0;
      for (std::size_t i = 0; i < e.size(); ++i)
        if (e.active[i]) sum += count ? 1.0 : e.mass[i];
      return sum;
    };
  }
  long i = -1;
  try {
    i = p.empty() ? -1 : element_ref(p[0], m);
  } catch (const std::invalid_argument& e) {
    throw bad(e.what());
  }
  if (i >= 0) return element_quantity(name, static_cast<std::size_t>(i), p, m);
  if (p.size() == 2) {
    const long w = wall_ref(p[0], m);
    if (w >= 0) {
      const auto k = static_cast<std::size_t>(w);
      if (p[1] == "fx") return [k](const Simulation& s) { return s.model().walls[k].force.x; };
      if (p[1] == "fy") return [k](const Simulation& s) { return s.model().walls[k].force.y; };
      if (p[1] == "x") return [k](const Simulation& s) { return s.model().walls[k].a.x; };
      if (p[1] == "y") return [k](const Simulation& s) { return s.model().walls[k].a.y; };
      throw bad("unknown wall field (fx, fy, x, y)");
    }
  }
  throw bad("unknown quantity (see lib/dem/run/quantities.hpp for the names)");
}

std::string quantity_unit(const std::string& name) {
  if (name == "t") return "s";
  if (name == "step" || name == "contacts" || name == "unbalanced_force_ratio") return "1";
  if (name == "gap_springs.intact" || name == "gap_springs.broken") return "1";
  if (name.rfind("box.vx(", 0) == 0 || name.rfind("box.vy(", 0) == 0) return "m/s";
  if (name == "discharged.count" || name == "active.count") return "1";
  if (name == "discharged.mass" || name == "active.mass") return "kg";
  if (name == "active.top") return "m";
  if (name.rfind("active.area_fraction(", 0) == 0) return "1";
  if (name.rfind("energy.", 0) == 0) return "J";
  if (name == "mean_increment" || name == "plate_travel" || name == "plate_dx" || name == "plate_dy") return "m";
  const auto p = split(name, '.');
  if (p.size() >= 2 && p[1].rfind("corner_slide(", 0) == 0) return "m";
  if (const auto dot = name.find('.'); dot != std::string::npos &&
      (name.compare(dot + 1, 3, "fn(") == 0 || name.compare(dot + 1, 3, "fs(") == 0 ||
       name.compare(dot + 1, 7, "fn_max(") == 0))
    return "N";  // <wall>.fn(s0,s1), <wall>.fs(s0,s1): a band's force (the bounds may hold dots)
  if (p.size() == 3) {  // e<i>.gap|fn|fs|links.<other>
    if (p[1] == "gap") return "m";
    if (p[1] == "fn" || p[1] == "fs") return "N";
    if (p[1] == "mr") return "N*m";
    if (p[1] == "links" || p[1] == "mobilised") return "1";
  }
  const std::string f = p.size() >= 2 ? name.substr(name.find('.') + 1) : std::string();
  if (f == "x" || f == "y" || f.rfind("px(", 0) == 0 || f.rfind("py(", 0) == 0) return "m";
  if (f == "phi") return "rad";
  if (f == "vx" || f == "vy") return "m/s";
  if (f == "omega") return "rad/s";
  if (f == "fx" || f == "fy") return "N";
  if (f == "moment") return "N*m";
  return "unknown";  // a name compile_quantity accepts always has a unit above (tests/lib/run/run_tests.cpp)
}

std::string series_header(const std::string& name) { return name + " [" + quantity_unit(name) + "]"; }

std::string series_column_name(const std::string& header_cell) {
  const auto k = header_cell.rfind(" [");
  if (k == std::string::npos || header_cell.empty() || header_cell.back() != ']') return header_cell;
  return header_cell.substr(0, k);
}

}  // namespace dem
