#include "cli/sharded_sweep.hpp"

#include <atomic>
#include <chrono>
#include <cstring>
#include <deque>
#include <exception>
#include <iostream>
#include <mutex>
#include <thread>

#include "cli/commands.hpp"
#include "cli/interrupt.hpp"

#ifdef COLLIDE2D_HAVE_MPI
#include <mpi.h>
#endif

namespace collide2d::cli {
namespace {

// Message tags: a finished item (8 bytes of item number, then the line), and
// the end of a rank's share (the line: empty, "signal N" or an error).
constexpr int tag_item = 1;
constexpr int tag_end = 2;

struct Finished {
  std::int64_t item;
  std::string line;
};

// Runs `share` through sweep.run, handing each result to `deliver`; stops
// between items when `stop` is set or a signal has arrived. Returns what
// ended it: "" (done), "signal N" or the error.
template <class Deliver>
std::string run_share(const std::vector<std::int64_t>& share, const ShardedSweep& sweep, const std::atomic<bool>& stop,
                      Deliver deliver) {
  try {
    for (const std::int64_t item : share) {
      if (stop.load() || interrupt_signal() != 0) return "signal " + std::to_string(interrupt_signal());
      deliver(Finished{item, sweep.run(item)});
    }
  } catch (const Interrupted& e) {
    return "signal " + std::to_string(e.signal);
  } catch (const std::exception& e) {
    return e.what();
  }
  return "";
}

#ifdef COLLIDE2D_HAVE_MPI
// A rank's messages to rank 0, sent without waiting (MPI_Isend): a blocking
// send spins in MPI's progress loop whenever rank 0 has not yet taken the
// previous ones (it looks every few milliseconds), which cost more CPU than
// the cases themselves. Each buffer lives until its send completes.
class SendsToRoot {
 public:
  void send(int tag, std::int64_t item, const std::string& line) {
    std::string buffer(sizeof item, '\0');
    std::memcpy(buffer.data(), &item, sizeof item);
    buffer += line;
    pending_.push_back({std::move(buffer), MPI_REQUEST_NULL});
    Pending& p = pending_.back();  // a deque keeps its elements in place
    MPI_Isend(p.buffer.data(), static_cast<int>(p.buffer.size()), MPI_BYTE, 0, tag, MPI_COMM_WORLD, &p.request);
    reap();
  }
  // Waits until rank 0 has every message (at the end of the share).
  void wait_all() {
    for (Pending& p : pending_) MPI_Wait(&p.request, MPI_STATUS_IGNORE);
    pending_.clear();
  }

 private:
  struct Pending {
    std::string buffer;
    MPI_Request request;
  };
  void reap() {
    while (!pending_.empty()) {
      int done = 0;
      MPI_Test(&pending_.front().request, &done, MPI_STATUS_IGNORE);
      if (!done) return;
      pending_.pop_front();
    }
  }
  std::deque<Pending> pending_;
};

// Rank 0: receives whatever has arrived; returns the number of ranks that
// reported their end.
int receive_arrived(const ShardedSweep& sweep, SweepStop& stop) {
  int ended = 0;
  for (;;) {
    int flag = 0;
    MPI_Status status;
    MPI_Iprobe(MPI_ANY_SOURCE, MPI_ANY_TAG, MPI_COMM_WORLD, &flag, &status);
    if (!flag) return ended;
    int count = 0;
    MPI_Get_count(&status, MPI_BYTE, &count);
    std::string buffer(static_cast<std::size_t>(count), '\0');
    MPI_Recv(buffer.data(), count, MPI_BYTE, status.MPI_SOURCE, status.MPI_TAG, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
    std::int64_t item = 0;
    std::memcpy(&item, buffer.data(), sizeof item);
    const std::string line = buffer.substr(sizeof item);
    if (status.MPI_TAG == tag_item) {
      sweep.record(item, line, status.MPI_SOURCE);
    } else {
      ++ended;
      if (!line.empty() && line.rfind("signal ", 0) != 0)
        stop.errors.push_back("rank " + std::to_string(status.MPI_SOURCE) + ": " + line);
    }
  }
}
#endif

}  // namespace

std::vector<std::int64_t> share_of(const std::vector<std::int64_t>& items, int rank, int size) {
  std::vector<std::int64_t> share;
  for (std::size_t i = static_cast<std::size_t>(rank); i < items.size(); i += static_cast<std::size_t>(size))
    share.push_back(items[i]);
  return share;
}

SweepStop run_sharded_sweep(const Ranks& ranks, const std::vector<std::int64_t>& items, const ShardedSweep& sweep) {
  install_interrupt_handlers();
  const std::vector<std::int64_t> share = share_of(items, ranks.rank, ranks.size);
  SweepStop stop;
  std::atomic<bool> stop_worker{false};

#ifdef COLLIDE2D_HAVE_MPI
  if (ranks.rank != 0) {
    SendsToRoot sends;
    const std::string end =
        run_share(share, sweep, stop_worker, [&](const Finished& f) { sends.send(tag_item, f.item, f.line); });
    sends.send(tag_end, 0, end);
    sends.wait_all();
    if (end.rfind("signal ", 0) == 0) stop.signal = interrupt_signal();
    else if (!end.empty()) stop.errors.push_back("rank " + std::to_string(ranks.rank) + ": " + end);
    return stop;
  }
#endif

  // Rank 0: its share on a worker thread, the books on this one.
  std::mutex mutex;
  std::deque<Finished> queue;
  std::atomic<bool> worker_done{false};
  std::string worker_end;
  std::thread worker([&] {
    worker_end = run_share(share, sweep, stop_worker, [&](Finished f) {
      const std::lock_guard<std::mutex> lock(mutex);
      queue.push_back(std::move(f));
    });
    worker_done.store(true);
  });
  auto drain_queue = [&] {
    std::deque<Finished> arrived;
    {
      const std::lock_guard<std::mutex> lock(mutex);
      arrived.swap(queue);
    }
    for (const Finished& f : arrived) sweep.record(f.item, f.line, 0);
  };
  int other_ranks_ended = 0;
  for (;;) {
    drain_queue();
#ifdef COLLIDE2D_HAVE_MPI
    if (ranks.mpi) other_ranks_ended += receive_arrived(sweep, stop);
#endif
    if (sweep.tick) sweep.tick();
    if (const int sig = interrupt_signal()) {
      stop.signal = sig;
      if (sweep.stopping) sweep.stopping();
      break;
    }
    if (worker_done.load() && other_ranks_ended == ranks.size - 1) break;
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  stop_worker.store(true);
  worker.join();
  drain_queue();
  if (!worker_end.empty() && worker_end.rfind("signal ", 0) != 0) stop.errors.push_back("rank 0: " + worker_end);
  return stop;
}

RootDecision agree_on_items(const Ranks& ranks, const std::string& command, const std::function<void()>& on_every_rank,
                            const std::function<RootDecision()>& on_root) {
  RootDecision decision;
  try {
    on_every_rank();
    if (ranks.rank == 0) decision = on_root();
  } catch (const std::exception& e) {
    if (ranks.rank == 0) std::cerr << "collide2d " << command << ": " << e.what() << "\n";
    decision.refusal = exit_bad_input;
  }
  decision = broadcast_from_root(ranks, decision);
  if (decision.refusal != 0) stop_ranks(ranks);
  return decision;
}

int non_root_exit(const Ranks& ranks, const SweepStop& stop) {
  if (stop.finished()) stop_ranks(ranks);
  return stop.signal ? interrupted_exit_code(stop.signal) : stop.errors.empty() ? exit_ok : exit_bad_input;
}

std::string command_line_of(const CLI::App& command) {
  std::string line = "collide2d " + command.get_name();
  for (const auto& opt : command.get_options())
    if (opt->count() > 0 && opt->get_name() != "--help")
      for (const std::string& v : opt->results()) line += " " + opt->get_name() + " " + v;
  return line;
}

void write_sweep_provenance(TableFile& file, const Ranks& ranks) {
  file.attribute("/provenance", "ranks", static_cast<std::int64_t>(ranks.size));
  file.attribute("/provenance", "sharding",
                 std::string("the items in order, rank r of K taking items r, r + K, r + 2K, ... (cli/sharded_sweep.hpp)"));
  file.attribute("/provenance", "mpi", ranks.mpi ? mpi_library_description() : std::string("none (one rank)"));
}

}  // namespace collide2d::cli
