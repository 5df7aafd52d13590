// Option values shared by several commands.
#pragma once

#include <map>
#include <stdexcept>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "cli/option_checks.hpp"
#include "collide2d/toi/query.hpp"

namespace collide2d::cli {

inline const std::map<std::string, ToiMethod> method_names{
    {"analytic", ToiMethod::analytic}, {"bisection", ToiMethod::bisection}, {"seed", ToiMethod::seed}};
// The names of every number mode ("strict", "fixed"), for option checks and
// defaults.
inline std::vector<std::string> number_mode_names() {
  std::vector<std::string> names;
  for (NumberMode m : all_number_modes) names.emplace_back(to_string(m));
  return names;
}

// The mode of a name that an option check (or a run file) has let through.
inline NumberMode number_mode_of(const std::string& name) {
  if (const auto mode = number_mode_named(name)) return *mode;
  throw std::invalid_argument("unknown number mode \"" + name + "\" (known: " + CLI::detail::join(number_mode_names(), ", ") + ")");
}

// Options are read as names and mapped after parsing: --method and --mode.
struct MethodModeEps {
  std::string method = "analytic";
  std::string mode = "strict";
  double eps = 1e-9;
  ToiMethod toi_method() const { return method_names.at(method); }
  NumberMode number_mode() const { return number_mode_of(mode); }
};

inline void add_method_mode_eps(CLI::App& cmd, MethodModeEps& o) {
  cmd.add_option("--method", o.method, "analytic (robust roots of the exact model), bisection (the article's "
                                       "step-and-bisect, tolerance --eps), seed (the article's wall method)")
      ->check(CLI::IsMember({"analytic", "bisection", "seed"}))
      ->capture_default_str();
  cmd.add_option("--mode", o.mode, "strict (IEEE double, bit reproducible) or fixed (Q63.64 integers)")
      ->check(CLI::IsMember(number_mode_names()))
      ->capture_default_str();
  cmd.add_option("--eps", o.eps, "distance tolerance of the bisection method (length units)")
      ->check(finite_positive())
      ->capture_default_str();
}

}  // namespace collide2d::cli
