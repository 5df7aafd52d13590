// collide2d bench peers: collide2d against Box2D 2.4 and Chipmunk 7 on the
// same scenes (bench_peers.cpp). Built when both are installed
// (COLLIDE2D_HAVE_PEERS).
#pragma once

namespace collide2d::cli {

struct BenchPeersOptions {
  double gas_seconds = 5;   // simulated, of each dense gas
  double pile_seconds = 60; // simulated, of the settling pile
};

int run_bench_peers(const BenchPeersOptions& o);

}  // namespace collide2d::cli
