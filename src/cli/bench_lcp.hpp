// collide2d bench lcp: the cost of an island's complementarity problem
// (sim/lcp.hpp, sim/sparse_factor.hpp) on the matrices a pile makes, as CSV
// pile,balls,rows,nonzeros,mode,factor_us,fill,solve_us,rounds,weight_error.
// A pile is balls of two masses packed hexagonally in a box, every touching
// pair a contact (with each other, the floor, the side walls): A = J M⁻¹ Jᵀ
// as contact_graph.hpp forms it. factor_us: one elimination of an active
// set (the whole, then random sets of 85 % of the rows, as a pivoting
// solver meets them), fill:
// the entries the factor keeps (multipliers and row entries); solve_us and
// rounds: the pile's contact forces under gravity solved from scratch
// (Lcp::solve), the pivoting rounds it took; weight_error: how far the
// floor's forces are from the pile's weight, relative (a check of the
// answer that does not ask the solver).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace collide2d::cli {

struct BenchLcpOptions {
  std::vector<std::int64_t> widths{6, 8, 10, 14};  // balls of a long row; 2 width / 3 rows
  std::vector<std::string> modes;
  std::uint64_t seed = 2026;
};

int run_bench_lcp(const BenchLcpOptions& o);

}  // namespace collide2d::cli
