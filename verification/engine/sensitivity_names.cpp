#include "engine/sensitivity_names.hpp"

#include <array>
#include <cctype>
#include <string_view>
#include <utility>

namespace ver::sens {

namespace {

// Greek letters (UTF-8) and their ASCII names.
constexpr std::array<std::pair<std::string_view, std::string_view>, 34> kGreek{{
    {"Δ", "d"}, {"δ", "d"}, {"α", "alpha"}, {"β", "beta"}, {"γ", "gamma"}, {"Γ", "Gamma"}, {"ε", "eps"},
    {"ζ", "zeta"}, {"η", "eta"}, {"θ", "theta"}, {"Θ", "Theta"}, {"κ", "kappa"}, {"λ", "lambda"}, {"Λ", "Lambda"},
    {"μ", "mu"}, {"µ", "mu"}, {"ν", "nu"}, {"ξ", "xi"}, {"π", "pi"}, {"ρ", "rho"}, {"σ", "sigma"}, {"Σ", "Sigma"},
    {"τ", "tau"}, {"φ", "phi"}, {"ϕ", "phi"}, {"Φ", "Phi"}, {"χ", "chi"}, {"ψ", "psi"}, {"ω", "omega"},
    {"Ω", "Omega"}, {"ι", "iota"}, {"ο", "o"}, {"υ", "upsilon"}, {"ς", "sigma"}}};

constexpr std::array<std::pair<std::string_view, char>, 11> kSuperscript{{
    {"⁰", '0'}, {"¹", '1'}, {"²", '2'}, {"³", '3'}, {"⁴", '4'}, {"⁵", '5'}, {"⁶", '6'}, {"⁷", '7'}, {"⁸", '8'}, {"⁹", '9'}, {"⁻", '-'}}};

}  // namespace

std::string ascii_name(const std::string& label) {
  std::string out;
  for (std::size_t k = 0; k < label.size();) {
    bool matched = false;
    for (const auto& [greek, name] : kGreek)
      if (label.compare(k, greek.size(), greek) == 0) {
        out += name;
        k += greek.size();
        matched = true;
        break;
      }
    if (matched) continue;
    const auto c = static_cast<unsigned char>(label[k]);
    if (std::isalnum(c) || c == '_') out += static_cast<char>(c);
    else if (out.empty() || out.back() != '_') out += '_';
    ++k;
    if (c >= 0x80)  // the rest of an unknown UTF-8 character
      while (k < label.size() && (static_cast<unsigned char>(label[k]) & 0xC0) == 0x80) ++k;
  }
  while (!out.empty() && out.back() == '_') out.pop_back();
  while (!out.empty() && out.front() == '_') out.erase(out.begin());
  if (out.empty()) return "x";
  if (std::isdigit(static_cast<unsigned char>(out.front()))) out = "x" + out;
  return out;
}

std::string ascii_unit(const std::string& si_unit) {
  std::string out;
  bool in_power = false;
  for (std::size_t k = 0; k < si_unit.size();) {
    if (si_unit.compare(k, 2, "·") == 0) {
      out += '*';
      k += 2;
      in_power = false;
      continue;
    }
    bool sup = false;
    for (const auto& [s, c] : kSuperscript)
      if (si_unit.compare(k, s.size(), s) == 0) {
        if (!in_power) out += '^';
        out += c;
        k += s.size();
        in_power = sup = true;
        break;
      }
    if (sup) continue;
    in_power = false;
    out += si_unit[k++];
  }
  return out;
}

}  // namespace ver::sens
