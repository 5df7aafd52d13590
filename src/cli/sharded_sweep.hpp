// A sweep's items shared among the ranks (issue 16): rank r of K takes
// items[r], items[r + K], items[r + 2K], ... of the list every rank computes
// alike, so the sharding is a function of the list and K alone.
//
// Rank 0 keeps the books: every finished item's result (one line of text)
// reaches it, its own through a queue from a worker thread that runs its
// share, the other ranks' as MPI messages. Its main thread only receives,
// records and ticks, so it answers a signal within a tick: when one rank
// dies, mpirun sends the others SIGTERM and, about a second later, SIGKILL,
// and rank 0 must have its files on disk by then.
#pragma once

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "cli/ranks.hpp"
#include "lab/table_file.hpp"

namespace collide2d::cli {

// This rank's share of `items`.
std::vector<std::int64_t> share_of(const std::vector<std::int64_t>& items, int rank, int size);

struct ShardedSweep {
  // Any rank, on its worker: the result of one item, as one line.
  std::function<std::string(std::int64_t item)> run;
  // Rank 0, main thread: a finished item, from `rank`, in arrival order.
  std::function<void(std::int64_t item, const std::string& line, int rank)> record;
  // Rank 0, main thread: called about fifty times a second (progress, snapshots).
  std::function<void()> tick;
  // Rank 0, main thread: a signal has arrived; called before waiting for the
  // worker's item in progress (save what is known now: SIGKILL may follow).
  std::function<void()> stopping;
};

struct SweepStop {
  int signal = 0;               // the SIGINT/SIGTERM that stopped this rank, or 0
  std::vector<std::string> errors;  // a rank whose worker threw: "rank 1: ..."
  bool finished() const { return signal == 0 && errors.empty(); }
};

// Runs the sweep on every rank and returns when this rank is done: rank 0
// when every rank has reported the end of its share (or a signal came), the
// others when their share is done. On a signal, rank 0 returns at once after
// the worker's item in progress (it is recorded if it finishes).
SweepStop run_sharded_sweep(const Ranks& ranks, const std::vector<std::int64_t>& items, const ShardedSweep& sweep);

// How a sweeping command starts on every rank: `on_every_rank` (reading the
// inputs every rank needs), then `on_root` on rank 0 (checking outputs,
// reading what an interrupted sweep finished: the items to run), and rank
// 0's decision reaches every rank. An exception is a refusal (exit 2), said
// once, by rank 0, as "collide2d COMMAND: MESSAGE". After a refusal MPI is
// finalized and the command returns decision.refusal.
RootDecision agree_on_items(const Ranks& ranks, const std::string& command, const std::function<void()>& on_every_rank,
                            const std::function<RootDecision()>& on_root);

// The exit code of a rank other than 0 once its share is done (finalizing
// MPI after a normal end).
int non_root_exit(const Ranks& ranks, const SweepStop& stop);

// "collide2d COMMAND --opt value ..." from the options given, for a file's
// provenance.
std::string command_line_of(const CLI::App& command);

// /provenance of a sweep's file: the ranks K, the sharding rule and the MPI
// library (attributes ranks, sharding, mpi).
void write_sweep_provenance(TableFile& file, const Ranks& ranks);

}  // namespace collide2d::cli
