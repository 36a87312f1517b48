#include <cmath>
#include <numbers>
#include <sstream>

#include <fmt/format.h>

#include "engine/run_cache.hpp"
#include "engine/run_dispatch.hpp"
#include "engine/study_run.hpp"
#include "ref/registry.hpp"

// kind = "mode_map": block shapes × friction angles × slope angles, the mode read from the DEM's
// motion against Sagaseta's classification (refs §2.3), as a text map, a coloured chart and one check
// per block and friction angle.

namespace ver {

namespace {
bool disk_block(const Study& s) { return s.mode_block == Study::ModeBlock::rolling_disk; }
/// The reference's name: Sagaseta's block, or the rigid disk with rolling resistance (refs §7.4).
const char* reference_name(const Study& s) { return disk_block(s) ? "rigid disk" : "Sagaseta"; }
}  // namespace

nlohmann::json mode_chart(const Study& s, const std::vector<ModePoint>& pts) {
  const char* block_names[] = {"stable", "slide", "topple", "slide + topple"};
  const char* disk_names[] = {"stable", "slide", "roll", "roll + slide"};
  const char* const* names = disk_block(s) ? disk_names : block_names;
  const char* colours[] = {"#2ca02c", "#1f77b4", "#d62728", "#9467bd"};
  nlohmann::json curves = nlohmann::json::array(), yticks = nlohmann::json::array();
  std::vector<std::vector<double>> rx(4), ry(4), dx(4), dy(4);
  std::vector<double> ex, ey, fx, fy;
  for (const ModePoint& p : pts) {
    const double row = static_cast<double>(p.block * s.phis.size() + p.phi);
    const double a = s.alphas[p.alpha] * 180.0 / std::numbers::pi;
    rx[p.ref].push_back(a);
    ry[p.ref].push_back(row);
    if (p.dem >= 0) {
      dx[p.dem].push_back(a);
      dy[p.dem].push_back(row);
    } else {
      fx.push_back(a);
      fy.push_back(row);
    }
    if (p.near_boundary) {
      ex.push_back(a);
      ey.push_back(row);
    }
  }
  for (int m = 0; m < 4; ++m)
    curves.push_back({{"label", fmt::format("{}: {}", reference_name(s), names[m])}, {"x", rx[m]}, {"y", ry[m]},
                      {"style", "points"}, {"colour", colours[m]}, {"point", 6}, {"size", 1.5}});
  for (int m = 0; m < 4; ++m)
    curves.push_back({{"label", fmt::format("DEM: {}", names[m])}, {"x", dx[m]}, {"y", dy[m]},
                      {"style", "points"}, {"colour", colours[m]}, {"point", 7}, {"size", 0.75}});
  curves.push_back({{"label", "near a boundary: not checked"}, {"x", ex}, {"y", ey}, {"style", "points"},
                    {"colour", "#000000"}, {"point", 2}, {"size", 1.2}});
  curves.push_back({{"label", "DEM run failed"}, {"x", fx}, {"y", fy}, {"style", "points"},
                    {"colour", "#000000"}, {"point", 3}, {"size", 1.8}});
  for (std::size_t b = 0; b < s.blocks.size(); ++b)
    for (std::size_t f = 0; f < s.phis.size(); ++f)
      yticks.push_back({static_cast<double>(b * s.phis.size() + f),
                        fmt::format("{}×{}, φ={:.0f}°", s.blocks[b].first, s.blocks[b].second,
                                    s.phis[f] * 180.0 / std::numbers::pi)});
  const double rows_n = static_cast<double>(s.blocks.size() * s.phis.size());
  return {{"id", "mode_map"},
          {"title", fmt::format("Mode map: {} (ring) against the DEM (dot), same colour = agreement", reference_name(s))},
                {"xlabel", "slope angle α [deg]"}, {"ylabel", "block (columns × rows) and friction angle φ"},
                {"logx", false}, {"logy", false}, {"curves", curves}, {"yticks", yticks},
                {"yrange", {-0.7, rows_n - 0.3}}};
}

std::vector<std::string> mode_map_sets(const Study& s, std::size_t block, double phi, double alpha) {
  const auto [cols, rows] = s.blocks.at(block);
  std::vector<std::string> sets = s.set;
  if (s.mode_block == Study::ModeBlock::polygon) {  // one polygon b × h, its base on the slope from x = 0 to x = b
    const double bw = 2.0 * s.radius * cols, bh = 2.0 * s.radius * rows;
    sets.push_back(fmt::format("element.0.size=[{:.17g}, {:.17g}]", bw, bh));
    sets.push_back(fmt::format("element.0.position=[{:.17g}, {:.17g}]", 0.5 * bw, 0.5 * bh));
    sets.push_back("probe.0.quantity=e0.px(1,-1)");
    sets.push_back("probe.2.quantity=e0.px(1,-1)");
  } else if (disk_block(s)) {  // one disk of radius r touching the slope at x = 0, μ_r = b/h (refs §7.4)
    sets.push_back(fmt::format("element.0.radius={:.17g}", s.radius));
    sets.push_back(fmt::format("element.0.position=[0, {:.17g}]", s.radius));
    sets.push_back(fmt::format("contact.{}.rolling.friction={:.17g}", s.wall_contact, double(cols) / rows));
    sets.push_back("probe.0.quantity=e0.x");
    sets.push_back("probe.2.quantity=e0.x");
  } else {
    sets.push_back(fmt::format("lattice.0.columns={}", cols));
    sets.push_back(fmt::format("lattice.0.rows={}", rows));
  }
  sets.push_back(fmt::format("physics.gravity.direction={:.17g} deg", alpha * 180.0 / std::numbers::pi - 90.0));
  sets.push_back(fmt::format("contact.{}.friction_angle={:.17g} deg", s.wall_contact, phi * 180.0 / std::numbers::pi));
  if (s.mode_block == Study::ModeBlock::lattice) {
    sets.push_back(fmt::format("probe.0.quantity=e{}.px(1,-1)", cols - 1));
    sets.push_back(fmt::format("probe.2.quantity=e{}.px(1,-1)", cols - 1));
  }
  return sets;
}

void run_mode_map(StudyRun& run) {
  const Study& s = run.s;
  const StudyOptions& opt = run.opt;
  // Sagaseta's dynamic classification (refs §2.3) against the DEM's motion, per grid point.
  std::vector<ModePoint> pts;
  for (std::size_t b = 0; b < s.blocks.size(); ++b)
    for (std::size_t f = 0; f < s.phis.size(); ++f)
      for (std::size_t a = 0; a < s.alphas.size(); ++a) pts.push_back({b, f, a});
  auto mode_at = [&](const char* solver, double alpha, double phi, double bw, double bh) {
    return static_cast<int>(std::lround(ref::evaluate(solver, {{"alpha", alpha}, {"phi", phi}, {"b", bw}, {"h", bh}})));
  };
  // The reference: Sagaseta's block, or the rigid disk with μ_r = b/h; `gb` holds what it is compared with:
  // Goodman & Bray for a block, Sagaseta's block for the disk (what the block's corners add).
  auto reference_mode = [&](double alpha, double phi, double bw, double bh) {
    if (!disk_block(s)) return mode_at("incline.mode", alpha, phi, bw, bh);
    return static_cast<int>(std::lround(ref::evaluate("rolling.mode", {{"alpha", alpha}, {"phi", phi}, {"mu_r", bw / bh}})));
  };
  std::vector<Planned> plan(pts.size());
  parallel_for(pts.size(), opt.jobs, [&](std::size_t k) {
    ModePoint& p = pts[k];
    const auto [cols, rows] = s.blocks[p.block];
    const double bw = 2.0 * s.radius * cols, bh = 2.0 * s.radius * rows;
    const double phi = s.phis[p.phi], alpha = s.alphas[p.alpha];
    p.ref = reference_mode(alpha, phi, bw, bh);
    p.gb = mode_at(disk_block(s) ? "incline.mode" : "incline.mode_gb", alpha, phi, bw, bh);
    // Near a boundary in α or in φ (e.g. b/h = tan φ exactly is the slide / slide + topple boundary).
    p.near_boundary = reference_mode(alpha - s.margin, phi, bw, bh) != p.ref ||
                      reference_mode(alpha + s.margin, phi, bw, bh) != p.ref ||
                      reference_mode(alpha, phi - s.margin, bw, bh) != p.ref ||
                      reference_mode(alpha, phi + s.margin, bw, bh) != p.ref;
    plan[k].sets = mode_map_sets(s, p.block, phi, alpha);
  });
  const std::vector<RunOut> mode_runs = run.run_many(plan, opt.jobs);
  for (std::size_t k = 0; k < pts.size(); ++k) {
    ModePoint& p = pts[k];
    const RunOut& r = mode_runs[k];
    auto get = [&](const char* name) { return r.probes.count(name) ? r.probes.at(name) : std::nullopt; };
    if (r.status == "blow-up" || !get("pivot_x") || !get("rotation") || !get("pivot_x_start") || !get("rotation_start")) continue;
    // The motion after the start-up transient: from `pivot_x_start` / `rotation_start` to the end.
    p.slide = *get("pivot_x") - *get("pivot_x_start");
    p.rotation = std::abs(*get("rotation") - *get("rotation_start"));
    // A disk's pivot is its contact point: the slip is the centre's travel less what rolling explains (down
    // the slope is +x, rolling down turns clockwise: Δx = −r Δφ without slip).
    if (disk_block(s)) p.slide += s.radius * (*get("rotation") - *get("rotation_start"));
    const bool slides = p.slide > s.slide_threshold, rotates = p.rotation > s.rotation_threshold;
    p.dem = slides ? (rotates ? 3 : 1) : (rotates ? 2 : 0);
  }
  const char code[] = {'.', 'S', 'T', 'X'};
  std::ostringstream map;
  map << "alpha (deg):          ";
  for (double a : s.alphas) map << fmt::format("{:>3.0f}", a * 180.0 / std::numbers::pi);
  map << "\n";
  nlohmann::json rows = nlohmann::json::array();
  int total_checked = 0, total_agree = 0, total_excluded = 0, total_unlike_block = 0;
  for (std::size_t b = 0; b < s.blocks.size(); ++b)
    for (std::size_t f = 0; f < s.phis.size(); ++f) {
      std::string ref_row, dem_row, gb_row, marks;
      int checked = 0, agree = 0, excluded = 0, unlike_block = 0;
      for (const ModePoint& p : pts) {
        if (p.block != b || p.phi != f) continue;
        ref_row += fmt::format("{:>3}", code[p.ref]);
        gb_row += code[p.gb];
        unlike_block += p.gb != p.ref;
        dem_row += fmt::format("{:>3}", p.dem < 0 ? '?' : code[p.dem]);
        if (p.near_boundary) {
          ++excluded;
          marks += "  ~";
        } else {
          ++checked;
          const bool ok = p.dem == p.ref;
          agree += ok;
          marks += ok ? "   " : "  !";
        }
      }
      const auto [cols, rows_n] = s.blocks[b];
      const std::string shape = fmt::format("{}x{} (b/h={:.3g})", cols, rows_n, double(cols) / rows_n);
      const double phi_deg = s.phis[f] * 180.0 / std::numbers::pi;
      map << fmt::format("{:<17} phi={:<3.0f} ref {}\n", shape, phi_deg, ref_row);
      map << fmt::format("{:<17}         DEM {}\n", "", dem_row);
      map << fmt::format("{:<17}             {}   [{}: {}]\n", "", marks, disk_block(s) ? "block" : "G&B", gb_row);
      rows.push_back({shape, fmt::format("{:.0f}", phi_deg), fmt::format("{}/{}", agree, checked), excluded});
      if (disk_block(s)) rows.back().push_back(unlike_block);
      total_unlike_block += unlike_block;
      total_checked += checked;
      total_agree += agree;
      total_excluded += excluded;
      Check c = s.checks.front();
      run.add_check(fmt::format("{}, φ = {:.0f}°: grid points where DEM ≠ {}", shape, phi_deg, reference_name(s)), 0.0,
                static_cast<double>(checked - agree), c, std::nullopt,
                fmt::format("{} points checked, {} within {:.1f}° (in α or φ) of a boundary not checked", checked, excluded,
                            s.margin * 180.0 / std::numbers::pi));
    }
  map << (disk_block(s) ? "(. stable, S slide, T roll (block: topple), X roll + slide (block: slide + topple); block: Sagaseta's "
                          "mode of the b × h block; ~ within the margin of a mode boundary, not checked; ! disagrees)\n"
                        : "(. stable, S slide, T topple, X slide + topple; ~ within the margin of a mode boundary, not checked; "
                          "! disagrees)\n");
  run.mode_chart = mode_chart(s, pts);
  run.tables.push_back({{"title", fmt::format("Mode map: {} (ref) against the DEM", reference_name(s))}, {"preformatted", map.str()}});
  nlohmann::json columns = {"block", "phi [deg]", "agree / checked", "excluded (near a boundary)"};
  if (disk_block(s)) columns.push_back("grid points where the disk's mode is not the block's");
  run.tables.push_back({{"title", "Agreement per block and friction angle"}, {"columns", columns}, {"rows", rows}});
  if (disk_block(s)) run.setup_extra["points where the rigid disk's mode is not the block's"] = total_unlike_block;
  run.setup_extra["points checked"] = total_checked;
  run.setup_extra["points agreeing"] = total_agree;
  run.setup_extra["points excluded"] = total_excluded;
  if (opt.print) fmt::print("{}", map.str());
}

}  // namespace ver
