#pragma once
// A resolved case in words for `dem2d check`: each contact law's settings, defaults included, and what
// limits Δt. The words re-state the branches of the stability limit (core/stability.hpp, refs §1.5),
// so they live beside the run library rather than in the command line.
#include <string>

#include <nlohmann/json.hpp>

#include "dem/core/model.hpp"
#include "dem/core/stability.hpp"

namespace dem {

/// One contact law's resolved settings in words, defaults included (`l`: an entry of
/// resolved_case_si()["contacts"]); check prints every one.
std::string law_in_words(const nlohmann::json& l);

/// What limits Δt, in words: the element, its contacts, the mode and the scheme's branch (refs §1.5).
std::string limit_in_words(const Model& m, const StabilityBound& b, double limit);

}  // namespace dem
