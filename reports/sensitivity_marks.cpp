#include "sensitivity_marks.hpp"

#include <limits>

#include "study_result.hpp"

namespace report {

void add_sensitivity_marks(const nlohmann::json& figure, Plot& plot) {
  for (const auto& tick : array_field(figure, "xticks"))
    if (tick.is_array() && tick.size() == 2 && tick[0].is_number() && tick[1].is_string())
      plot.xticks.emplace_back(tick[0].get<double>(), tick[1].get<std::string>());
  for (const auto& label : array_field(figure, "labels")) {
    const auto x = number_field(label, "x"), y = number_field(label, "y");
    const auto text = text_field(label, "text");
    if (x && y && !text.empty()) plot.labels.push_back({*x, *y, text});
  }
}

void add_interval(const nlohmann::json& entry, Curve& curve) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  for (const auto& [key, out] : {std::pair{"ylow", &curve.ylow}, std::pair{"yhigh", &curve.yhigh}})
    for (const auto& v : number_array(entry, key)) out->push_back(v.value_or(nan));
  if (const auto w = number_field(entry, "width"); w && *w > 0.0) curve.box_width = *w;
}

}  // namespace report
