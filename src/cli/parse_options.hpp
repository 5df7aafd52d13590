// Option values shared by several commands.
#pragma once

#include <map>
#include <string>

#include <CLI/CLI.hpp>

#include "collide2d/toi/query.hpp"

namespace collide2d::cli {

inline const std::map<std::string, ToiMethod> method_names{
    {"analytic", ToiMethod::analytic}, {"bisection", ToiMethod::bisection}, {"seed", ToiMethod::seed}};
inline const std::map<std::string, NumberMode> mode_names{{"strict", NumberMode::strict}, {"fixed", NumberMode::fixed}};
static_assert(static_cast<int>(NumberMode::fixed) == 1, "a new NumberMode needs its name in mode_names");

// Options are read as names and mapped after parsing: --method and --mode.
struct MethodModeEps {
  std::string method = "analytic";
  std::string mode = "strict";
  double eps = 1e-9;
  ToiMethod toi_method() const { return method_names.at(method); }
  NumberMode number_mode() const { return mode_names.at(mode); }
};

inline void add_method_mode_eps(CLI::App& cmd, MethodModeEps& o) {
  cmd.add_option("--method", o.method, "analytic (robust roots of the exact model), bisection (the article's "
                                       "step-and-bisect, tolerance --eps), seed (the article's wall method)")
      ->check(CLI::IsMember({"analytic", "bisection", "seed"}))
      ->capture_default_str();
  cmd.add_option("--mode", o.mode, "strict (IEEE double, bit reproducible) or fixed (Q63.64 integers)")
      ->check(CLI::IsMember({"strict", "fixed"}))
      ->capture_default_str();
  cmd.add_option("--eps", o.eps, "distance tolerance of the bisection method (length units)")
      ->check(CLI::PositiveNumber)
      ->capture_default_str();
}

}  // namespace collide2d::cli
